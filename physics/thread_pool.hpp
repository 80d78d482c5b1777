#pragma once
// The physics' own task runner: a pool of threads started once and kept, which wake for each
// batch of tasks instead of being started for every parallel loop.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "physics/task_runner.hpp"

namespace mane::physics {

/// A persistent pool of worker threads that runs `TaskRunner` batches.
///
/// `workers` threads share each batch: the thread that calls `wait` is one of them (it takes
/// tasks of its own batch while it waits), so the pool starts `workers − 1` threads, once, in its
/// constructor. Several threads may run batches on one pool at the same time. Not movable: the
/// runners it hands out point to it.
class ThreadPool {
public:
  /// `workers` ≥ 1 threads in all (0 counts as 1; 1 runs every task on the calling thread).
  /// When the system refuses to start a thread, the pool keeps those it has: the results are
  /// the same, only slower.
  explicit ThreadPool(unsigned workers);
  ~ThreadPool();  ///< Joins the threads; no batch may be running.
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Threads that run tasks, the waiting caller included.
  [[nodiscard]] unsigned workerCount() const noexcept { return static_cast<unsigned>(threads_.size()) + 1; }
  /// A runner whose batches run on this pool (`concurrency` = `workerCount()`); the pool must
  /// outlive every system that uses it.
  [[nodiscard]] TaskRunner runner();

  /// The runner's callbacks (see `TaskRunner`'s contract).
  [[nodiscard]] Result<TaskGroup> enqueue(std::uint32_t count, const TaskFunction& task);
  [[nodiscard]] Result<void> wait(TaskGroup group);

private:
  struct Batch;
  void workerLoop();
  // Claims and runs tasks of `batch` until none is left to claim.
  void runTasksOf(Batch& batch);

  std::mutex mutex_;
  std::condition_variable wake_;          // workers: a batch was enqueued, or the pool stops
  std::condition_variable finished_;      // waiters: a batch's last task returned
  std::vector<Batch*> open_;              // batches with tasks left to claim, oldest first
  bool stopping_ = false;
  std::vector<std::jthread> threads_;
};

}  // namespace mane::physics
