#include "physics/task_runner.hpp"

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "physics/detail/parallel_tasks.hpp"

namespace mane::physics {

Result<void> validateTaskRunner(const TaskRunner& runner, const char* field) {
  if (runner.concurrency < 1) return fail(std::string(field) + ".concurrency must be at least 1, got 0.");
  if (static_cast<bool>(runner.enqueue) != static_cast<bool>(runner.wait))
    return fail(std::string(field) + " has " + (runner.enqueue ? "an enqueue but no wait" : "a wait but no enqueue") +
                " callback; give both, or neither to run every task on the calling thread.");
  return {};
}

namespace detail {

Result<void> runTaskBatch(const TaskRunner& runner, std::uint32_t count, void (*body)(void*, std::uint32_t),
                          void* context) {
  if (count <= 1 || !runner.hasCallbacks()) {
    for (std::uint32_t task = 0; task < count; ++task) body(context, task);
    return {};
  }
  // Per task: 0 not started, 1 running, 2 done. A task runs only when it moves from 0 to 1, so a
  // runner that calls a task twice cannot apply its work twice. After `wait`, the tasks never
  // started are run here, and any still running (a runner whose wait returned early) are waited
  // for, so no task outlives this batch.
  enum : std::uint8_t { kNotStarted, kRunning, kDone };
  struct Batch {
    void (*body)(void*, std::uint32_t);
    void* context;
    std::uint32_t count;
    std::unique_ptr<std::atomic<std::uint8_t>[]> state;
    std::atomic<std::uint32_t> misuse{0};  // calls with an index out of range or a repeated one
  } batch{body, context, count, std::make_unique<std::atomic<std::uint8_t>[]>(count)};
  const TaskFunction task = [b = &batch](std::uint32_t index) {
    std::uint8_t expected = kNotStarted;
    if (index >= b->count || !b->state[index].compare_exchange_strong(expected, kRunning, std::memory_order_acq_rel)) {
      b->misuse.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    b->body(b->context, index);
    b->state[index].store(kDone, std::memory_order_release);
  };

  std::string failure;
  if (auto group = runner.enqueue(count, task); !group) {
    failure = "the task runner could not start " + std::to_string(count) + " tasks: " + group.error().message;
  } else if (auto waited = runner.wait(*group); !waited) {
    failure = "the task runner's wait failed: " + waited.error().message;
  }
  std::uint32_t missed = 0, running = 0;
  for (std::uint32_t index = 0; index < count; ++index) {
    std::uint8_t expected = kNotStarted;
    if (batch.state[index].compare_exchange_strong(expected, kRunning, std::memory_order_acq_rel)) {
      ++missed;
      body(context, index);
      batch.state[index].store(kDone, std::memory_order_release);
      continue;
    }
    if (batch.state[index].load(std::memory_order_acquire) == kDone) continue;
    ++running;
    while (batch.state[index].load(std::memory_order_acquire) != kDone) std::this_thread::yield();
  }
  if (failure.empty() && running > 0)
    failure = "the task runner returned from wait with " + std::to_string(running) + " of " + std::to_string(count) +
              " tasks still running";
  if (failure.empty() && missed > 0)
    failure = "the task runner returned from wait with " + std::to_string(missed) + " of " + std::to_string(count) +
              " tasks not run";
  if (failure.empty() && batch.misuse.load() > 0)
    failure = "the task runner called tasks out of range or more than once (" + std::to_string(batch.misuse.load()) +
              " calls)";
  if (failure.empty()) return {};
  return fail(failure + "; the tasks it did not run were run on the calling thread.");
}

}  // namespace detail
}  // namespace mane::physics
