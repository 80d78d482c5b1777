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
  /// `background`: the threads work in the background (inBackground), for background callers.
  explicit KeptThreads(bool background) : background_(background) {
#if defined(__linux__)
    if (sched_getaffinity(0, sizeof allowed_, &allowed_) != 0) CPU_ZERO(&allowed_);
#endif
  }
  KeptThreads(const KeptThreads&) = delete;
  KeptThreads& operator=(const KeptThreads&) = delete;

  ~KeptThreads() {
    stopping_.store(true, std::memory_order_relaxed);
    state_.fetch_add(std::uint64_t(1) << kLoopShift, std::memory_order_release);
    state_.notify_all();
    threads_.clear();  // joins
  }

  bool run(std::size_t ranges, Task task, const void* context) {
    if (ranges > kMaxRanges) return false;
    if (busy_.exchange(true, std::memory_order_acquire)) return false;
    const Release release{busy_};
    try {
      while (threads_.size() + 1 < ranges) {
        threads_.emplace_back([this, loop = loopOf(state_.load(std::memory_order_relaxed))] { serve(loop); });
#if defined(__linux__)
        callerCpu_ = -1;  // the new thread is not barred from any CPU yet
#endif
      }
    } catch (const std::system_error&) {
      return false;  // the threads started wait for a later loop
    }
    keepOffCallersCpu();
    task_ = task;
    context_ = context;
    unfinished_.store(ranges, std::memory_order_relaxed);
    const std::uint64_t loop = loopOf(state_.load(std::memory_order_relaxed)) + 1;
    state_.store(loop << kLoopShift | std::uint64_t(ranges) << kRangesShift, std::memory_order_release);
    state_.notify_all();
    runRanges(loop);
    waitFor(unfinished_, [](std::size_t left) { return left == 0; });
    return true;
  }

private:
  // state_ holds the loop's number (bits 16 and up), its range count (bits 8–15) and the next
  // range to claim (bits 0–7): one word, so that no thread claims a range of a loop it did not
  // see published.
  static constexpr int kRangesShift = 8;
  static constexpr int kLoopShift = 16;
  static constexpr std::uint64_t kByte = 0xff;
  static constexpr std::size_t kMaxRanges = kByte;

  static std::uint64_t loopOf(std::uint64_t state) {
    return state >> kLoopShift;
  }

  /// Claims and runs ranges of loop `loop` until none is left to claim. Ranges go to whichever
  /// thread is free, so a kept thread that the system is slow to run delays the loop by no more
  /// than the range it has claimed: the caller runs the rest.
  void runRanges(std::uint64_t loop) {
    std::uint64_t state = state_.load(std::memory_order_acquire);
    while (loopOf(state) == loop && (state & kByte) < (state >> kRangesShift & kByte)) {
      if (!state_.compare_exchange_weak(state, state + 1, std::memory_order_acq_rel, std::memory_order_acquire))
        continue;
      task_(context_, static_cast<std::size_t>(state & kByte));
      if (unfinished_.fetch_sub(1, std::memory_order_acq_rel) == 1) unfinished_.notify_one();
      state = state_.load(std::memory_order_acquire);
    }
  }

  /// Linux wakes a sleeping thread on the CPU of the thread that wakes it, where it waits for
  /// the caller's own range to end: a frame's loop, run after the threads slept through the
  /// rest of the frame, then takes as long on two threads as on one. So the kept threads may run
  /// anywhere but there.
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

  void serve(std::uint64_t seenLoop) {
    inBackground = background_;
    for (;;) {
      const std::uint64_t state =
          waitFor(state_, [seenLoop](std::uint64_t current) { return loopOf(current) != seenLoop; });
      if (stopping_.load(std::memory_order_relaxed)) return;
      seenLoop = loopOf(state);
      runRanges(seenLoop);
    }
  }

  /// Clears a flag on leaving a scope.
  struct Release {
    std::atomic<bool>& flag;
    ~Release() { flag.store(false, std::memory_order_release); }
  };

  std::atomic<bool> busy_{false};  ///< set by the one caller whose loop the threads run
  std::atomic<std::uint64_t> state_{0};
  std::atomic<std::size_t> unfinished_{0};  ///< ranges of the loop not yet run
  std::atomic<bool> stopping_{false};
  const bool background_;
  // Written by the caller before it publishes the loop, read by the threads that claim its ranges.
  Task task_ = nullptr;
  const void* context_ = nullptr;
#if defined(__linux__)
  cpu_set_t allowed_;   ///< the CPUs the process may run on
  int callerCpu_ = -1;  ///< the CPU the kept threads were last barred from
#endif
  std::vector<std::jthread> threads_;  ///< declared last, so joined before the rest goes
};

}  // namespace

bool runOnKeptThreads(std::size_t ranges, Task task, const void* context) {
  // Apart, so that a frame's loops and a preparation's run side by side: the preparation's
  // threads pause at their next checkpoint while the frame's run.
  static KeptThreads foreground(false), background(true);
  return (inBackground ? background : foreground).run(ranges, task, context);
}

}  // namespace mane::subdiv::detail
