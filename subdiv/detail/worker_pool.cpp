#include "subdiv/detail/worker_pool.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <system_error>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif

namespace mane::subdiv::detail {
namespace {

using Task = void (*)(const void*, std::size_t);

// How long a thread polls for the next loop, or a caller for its loop's end, before it sleeps:
// the loops of one frame follow each other within this, and a polling thread needs no waking.
constexpr auto kPollFor = std::chrono::microseconds(50);

/// Waits until ready(value) holds and returns the value seen.
template <typename T, typename Ready>
T waitFor(const std::atomic<T>& value, const Ready& ready) {
  const auto start = std::chrono::steady_clock::now();
  for (unsigned polls = 1;; ++polls) {
    const T seen = value.load(std::memory_order_acquire);
    if (ready(seen)) return seen;
    if (polls % 64 == 0 && std::chrono::steady_clock::now() - start > kPollFor)
      value.wait(seen, std::memory_order_acquire);
#if defined(__x86_64__)
    else
      __builtin_ia32_pause();
#endif
  }
}

class KeptThreads {
public:
  KeptThreads() {
#if defined(__linux__)
    if (sched_getaffinity(0, sizeof allowed_, &allowed_) != 0) CPU_ZERO(&allowed_);
#endif
  }
  KeptThreads(const KeptThreads&) = delete;
  KeptThreads& operator=(const KeptThreads&) = delete;

  ~KeptThreads() {
    stopping_.store(true, std::memory_order_relaxed);
    loop_.fetch_add(kNextLoop, std::memory_order_release);
    loop_.notify_all();
    threads_.clear();  // joins
  }

  bool run(std::size_t workers, Task task, const void* context) {
    if (workers > kMaxWorkers) return false;
    if (busy_.exchange(true, std::memory_order_acquire)) return false;
    const Release release{busy_};
    try {
      while (threads_.size() + 1 < workers) {
        const std::size_t worker = threads_.size() + 1;
        threads_.emplace_back([this, worker, seen = loop_.load(std::memory_order_relaxed)] { serve(worker, seen); });
      }
    } catch (const std::system_error&) {
      return false;  // the threads started wait for a later loop
    }
    keepOffCallersCpu();
    task_ = task;
    context_ = context;
    unfinished_.store(workers - 1, std::memory_order_relaxed);
    // The loop's number and its worker count change together, so no thread can pair one
    // loop's count with another's number.
    const std::uint64_t previous = loop_.load(std::memory_order_relaxed);
    loop_.store((previous & ~kWorkerMask) + kNextLoop + workers, std::memory_order_release);
    loop_.notify_all();
    task(context, 0);
    waitFor(unfinished_, [](std::size_t left) { return left == 0; });
    return true;
  }

private:
  // loop_ holds the loop's number above its worker count.
  static constexpr std::uint64_t kWorkerMask = 0xff;
  static constexpr std::uint64_t kNextLoop = kWorkerMask + 1;
  static constexpr std::size_t kMaxWorkers = kWorkerMask;

  /// Linux wakes a sleeping thread on the CPU of the thread that wakes it, where it waits for
  /// the caller's own range to end: a frame's loop, run after the threads slept through the
  /// rest of the frame, took as long on two threads as on one (measured on this project's
  /// 2-core VM: the woken thread started 0.9–1.0 ms after a 1 ms range began, and 0.1–0.2 ms
  /// after when barred from the caller's CPU). So the kept threads may run anywhere but there.
  void keepOffCallersCpu() {
#if defined(__linux__)
    const int cpu = sched_getcpu();
    if (cpu < 0 || cpu == callerCpu_ || !CPU_ISSET(cpu, &allowed_) || CPU_COUNT(&allowed_) < 2) return;
    callerCpu_ = cpu;
    cpu_set_t others = allowed_;
    CPU_CLR(cpu, &others);
    for (std::jthread& thread : threads_) pthread_setaffinity_np(thread.native_handle(), sizeof others, &others);
#endif
  }

  void serve(std::size_t worker, std::uint64_t seen) {
    for (;;) {
      seen = waitFor(loop_, [seen](std::uint64_t loop) { return loop != seen; });
      if (stopping_.load(std::memory_order_relaxed)) return;
      if (worker >= (seen & kWorkerMask)) continue;  // not one of this loop's workers
      task_(context_, worker);
      if (unfinished_.fetch_sub(1, std::memory_order_acq_rel) == 1) unfinished_.notify_one();
    }
  }

  /// Clears a flag on leaving a scope.
  struct Release {
    std::atomic<bool>& flag;
    ~Release() { flag.store(false, std::memory_order_release); }
  };

  std::atomic<bool> busy_{false};  ///< set by the one caller whose loop the threads run
  std::atomic<std::uint64_t> loop_{0};
  std::atomic<std::size_t> unfinished_{0};
  std::atomic<bool> stopping_{false};
  // Written by the caller before it publishes the loop, read by the loop's workers.
  Task task_ = nullptr;
  const void* context_ = nullptr;
#if defined(__linux__)
  cpu_set_t allowed_;   ///< the CPUs the process may run on
  int callerCpu_ = -1;  ///< the CPU the kept threads were last barred from
#endif
  std::vector<std::jthread> threads_;  ///< declared last, so joined before the rest goes
};

}  // namespace

bool runOnKeptThreads(std::size_t workers, Task task, const void* context) {
  static KeptThreads threads;
  return threads.run(workers, task, context);
}

}  // namespace mane::subdiv::detail
