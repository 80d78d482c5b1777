#pragma once
// How the physics runs its parallel loops on somebody else's threads.
//
// Every parallel loop of a step (hair strands, cloth colours, dense strands, skinned vertices) is
// handed to a `TaskRunner` as one batch of independent tasks numbered 0 … count − 1. Each item of
// the loop (a strand, a constraint, a vertex) comes out the same whichever task computes it, and
// no value is combined across items, so the simulated state has the same bits whichever threads
// run the tasks, in whatever order, and for any task count (docs/design.md#determinism). A host engine with its own job system fills in `enqueue`
// and `wait`; otherwise `builtInTaskRunner` (thread_pool.hpp) runs the batches on a persistent
// pool of threads.

#include <cstdint>
#include <functional>

#include "common/error.hpp"

namespace mane::physics {

/// A batch a runner has started, as its `enqueue` returned it; only the runner knows what it
/// points to.
using TaskGroup = void*;

/// The body of a batch: called once with each task index in [0, count).
using TaskFunction = std::function<void(std::uint32_t task)>;

/// The callbacks through which the physics runs a batch of tasks on the host's workers.
///
/// Contract, per batch: the physics calls `enqueue(count, task)` and then, on success, always
/// `wait(group)` with the group returned, from the same thread. The runner must call
/// `task(i)` exactly once for every i in [0, count), on any threads and in any order, and
/// `wait` must return only when all those calls have returned. `task` stays valid until `wait`
/// returns. A runner that cannot start the batch returns an error from `enqueue` and must then
/// have started none of its tasks. Tasks do not throw and do not block on one another, so a
/// runner may also run them on the thread that calls `wait`.
///
/// A runner that breaks the contract in a detectable way (an error from `enqueue` or `wait`, or
/// `wait` returning before every task ran or while some still run) does not corrupt the
/// simulation: the tasks it did not start are run on the calling thread and those still running
/// are waited for, so the state is the one a working runner gives, and the call that used it
/// (`advance`, `interpolate`, ...) returns an error naming the failure.
struct TaskRunner {
  /// How many tasks each parallel loop is split into (≥ 1), typically the number of workers the
  /// runner has. Loops with less work use fewer. The results do not depend on it.
  std::uint32_t concurrency = 1;
  /// Starts `count` tasks of `task` (see the contract above); returns the handle `wait` takes.
  std::function<Result<TaskGroup>(std::uint32_t count, const TaskFunction& task)> enqueue;
  /// Blocks until every task of `group` has run.
  std::function<Result<void>(TaskGroup group)> wait;

  /// True when the callbacks are set; a runner without them runs every task on the calling
  /// thread.
  [[nodiscard]] bool hasCallbacks() const noexcept { return enqueue && wait; }
};

/// Checks a runner before a system keeps it: `concurrency` ≥ 1 and either both callbacks or
/// neither. `field` names the setting in the message (e.g. "HairSettings.tasks").
[[nodiscard]] Result<void> validateTaskRunner(const TaskRunner& runner, const char* field);

/// The built-in runner: a process-wide `ThreadPool` (thread_pool.hpp) of `workers` threads (0
/// counts as 1), started on first use and shared by every system given a runner of that size; 1
/// runs the tasks on the calling thread.
[[nodiscard]] TaskRunner builtInTaskRunner(unsigned workers);

/// `builtInTaskRunner` with one worker per hardware thread: the default of every settings
/// struct's `tasks`.
[[nodiscard]] TaskRunner defaultTaskRunner();

}  // namespace mane::physics
