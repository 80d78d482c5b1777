#include "physics/thread_pool.hpp"

#include <algorithm>
#include <atomic>
#include <map>
#include <system_error>

namespace mane::physics {

struct ThreadPool::Batch {
  const TaskFunction* task = nullptr;
  std::uint32_t count = 0;
  std::atomic<std::uint32_t> next{0};  // next task index to claim
  std::atomic<std::uint32_t> done{0};  // tasks that have returned
  int runners = 0;                     // pool threads inside runTasksOf(*this); guarded by mutex_
};

ThreadPool::ThreadPool(unsigned workers) {
  const unsigned started = std::max(1u, workers) - 1;
  threads_.reserve(started);
  for (unsigned w = 0; w < started; ++w) {
    try {
      threads_.emplace_back([this] { workerLoop(); });
    } catch (const std::system_error&) {
      break;  // no more threads available: fewer workers, same results
    }
  }
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  threads_.clear();  // joins
}

TaskRunner ThreadPool::runner() {
  TaskRunner runner;
  runner.concurrency = workerCount();
  if (threads_.empty()) return runner;  // no callbacks: the calling thread runs everything
  runner.enqueue = [this](std::uint32_t count, const TaskFunction& task) { return enqueue(count, task); };
  runner.wait = [this](TaskGroup group) { return wait(group); };
  return runner;
}

void ThreadPool::runTasksOf(Batch& batch) {
  for (std::uint32_t task = batch.next.fetch_add(1, std::memory_order_relaxed); task < batch.count;
       task = batch.next.fetch_add(1, std::memory_order_relaxed)) {
    (*batch.task)(task);
    batch.done.fetch_add(1, std::memory_order_acq_rel);
  }
}

Result<TaskGroup> ThreadPool::enqueue(std::uint32_t count, const TaskFunction& task) {
  auto batch = std::make_unique<Batch>();
  batch->task = &task;
  batch->count = count;
  {
    const std::lock_guard lock(mutex_);
    if (stopping_) return fail("the thread pool is shutting down.");
    open_.push_back(batch.get());
  }
  wake_.notify_all();
  return batch.release();
}

Result<void> ThreadPool::wait(TaskGroup group) {
  const std::unique_ptr<Batch> batch(static_cast<Batch*>(group));
  runTasksOf(*batch);  // the waiting thread is one of the workers
  std::unique_lock lock(mutex_);
  std::erase(open_, batch.get());
  // Every task is claimed; wait for the workers still running one, and for the pool threads
  // that picked the batch to let go of it before it is freed.
  finished_.wait(lock, [&] { return batch->done.load() == batch->count && batch->runners == 0; });
  return {};
}

void ThreadPool::workerLoop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || !open_.empty(); });
    if (open_.empty()) return;  // stopping, nothing left
    Batch& batch = *open_.front();
    ++batch.runners;
    lock.unlock();
    runTasksOf(batch);
    lock.lock();
    // All of its tasks are claimed: no other worker needs to look at it.
    std::erase(open_, &batch);
    if (--batch.runners == 0) finished_.notify_all();
  }
}

TaskRunner builtInTaskRunner(unsigned workers) {
  workers = std::max(1u, workers);
  TaskRunner runner;
  runner.concurrency = workers;
  if (workers == 1) return runner;
  // The pool of each size is started on first use, so a settings struct's default costs nothing
  // until something runs on it, and kept to the end of the process.
  static std::mutex poolsMutex;
  static std::map<unsigned, std::unique_ptr<ThreadPool>> pools;
  const auto pool = [workers]() -> ThreadPool& {
    const std::lock_guard lock(poolsMutex);
    auto& slot = pools[workers];
    if (!slot) slot = std::make_unique<ThreadPool>(workers);
    return *slot;
  };
  runner.enqueue = [pool](std::uint32_t count, const TaskFunction& task) { return pool().enqueue(count, task); };
  runner.wait = [pool](TaskGroup group) { return pool().wait(group); };
  return runner;
}

TaskRunner defaultTaskRunner() {
  return builtInTaskRunner(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace mane::physics
