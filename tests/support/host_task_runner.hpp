#pragma once
// Task runners as a host engine might write them, for the physics tests: one that runs a
// batch's tasks on threads of its own in an order unlike the built-in pool's, and broken ones
// whose failures the physics must report.

#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "physics/task_runner.hpp"

namespace mane::test {

/// Runs each batch on `threads` threads started for it, which take the tasks from the last to
/// the first: a schedule that shares nothing with the built-in pool's.
inline physics::TaskRunner reversedHostRunner(unsigned threads) {
  struct Batch {
    std::atomic<std::int64_t> next;
    std::vector<std::jthread> threads;
  };
  physics::TaskRunner runner;
  runner.concurrency = threads + 1;  // more tasks than threads: some take several
  runner.enqueue = [threads](std::uint32_t count,
                             const physics::TaskFunction& task) -> Result<physics::TaskGroup> {
    auto batch = std::make_unique<Batch>();
    batch->next = static_cast<std::int64_t>(count) - 1;
    for (unsigned t = 0; t < threads; ++t)
      batch->threads.emplace_back([b = batch.get(), &task] {
        for (std::int64_t i = b->next.fetch_sub(1); i >= 0; i = b->next.fetch_sub(1))
          task(static_cast<std::uint32_t>(i));
      });
    return batch.release();
  };
  runner.wait = [](physics::TaskGroup group) -> Result<void> {
    delete static_cast<Batch*>(group);  // joins
    return {};
  };
  return runner;
}

/// A runner whose enqueue always fails, starting nothing.
inline physics::TaskRunner refusingRunner() {
  physics::TaskRunner runner;
  runner.concurrency = 4;
  runner.enqueue = [](std::uint32_t, const physics::TaskFunction&) -> Result<physics::TaskGroup> {
    return fail("the host's job queue is full");
  };
  runner.wait = [](physics::TaskGroup) -> Result<void> { return {}; };
  return runner;
}

/// A runner that reports success but runs only task 0 of each batch (a host that drops jobs).
inline physics::TaskRunner droppingRunner() {
  physics::TaskRunner runner;
  runner.concurrency = 4;
  runner.enqueue = [](std::uint32_t, const physics::TaskFunction& task) -> Result<physics::TaskGroup> {
    task(0);
    return nullptr;
  };
  runner.wait = [](physics::TaskGroup) -> Result<void> { return {}; };
  return runner;
}

}  // namespace mane::test
