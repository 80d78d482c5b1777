#pragma once
// Internal: one parallel loop of a system run through its TaskRunner, with the checks that keep a
// failing runner from leaving a half-done step behind.

#include <cstdint>
#include <string>

#include "common/error.hpp"
#include "physics/task_runner.hpp"

namespace mane::physics::detail {

/// Runs `body(task)` for every task in [0, count) through `runner`, or on the calling thread
/// when `count` ≤ 1 or the runner has no callbacks. When the runner fails (an error from its
/// callbacks, tasks left unrun or an index out of range), the tasks it did not run are run here,
/// each still exactly once, and the failure comes back as the error (a complete sentence).
[[nodiscard]] Result<void> runTaskBatch(const TaskRunner& runner, std::uint32_t count, void (*body)(void*, std::uint32_t),
                                        void* context);

/// `runTaskBatch` for any callable `body(std::uint32_t task)`.
template <class Body>
[[nodiscard]] Result<void> runTasks(const TaskRunner& runner, std::uint32_t count, Body& body) {
  return runTaskBatch(
      runner, count, [](void* context, std::uint32_t task) { (*static_cast<Body*>(context))(task); }, &body);
}

/// How many tasks a loop over `items` independent items is split into: the runner's
/// concurrency, at most one task per `minItemsPerTask` items, at least 1.
[[nodiscard]] inline std::uint32_t taskCountFor(const TaskRunner& runner, std::size_t items,
                                                std::size_t minItemsPerTask = 1) {
  const std::size_t byWork = items / (minItemsPerTask == 0 ? 1 : minItemsPerTask);
  const std::size_t count = byWork < runner.concurrency ? byWork : runner.concurrency;
  return count == 0 ? 1u : static_cast<std::uint32_t>(count);
}

/// The first item of task `task` when `items` are cut into `count` contiguous ranges by index.
[[nodiscard]] inline std::size_t taskRangeBegin(std::size_t items, std::uint32_t count, std::uint32_t task) {
  return items * task / count;
}

}  // namespace mane::physics::detail
