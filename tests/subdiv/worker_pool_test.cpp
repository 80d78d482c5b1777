// The kept threads behind forEachRange (subdiv/detail/worker_pool.hpp): every range runs
// exactly once per loop, loop after loop, with or without the threads sleeping between
// loops; a loop started inside a loop is refused and runs on threads of its own; a background
// thread pauses while foreground work runs beside it, unless the foreground waits for it.

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "subdiv/detail/parallel_ranges.hpp"
#include "subdiv/detail/worker_pool.hpp"

namespace mane::subdiv::detail {
namespace {

struct Calls {
  std::array<std::atomic<int>, 8> perRange{};
};

void countCall(const void* context, std::size_t range) {
  auto& calls = *static_cast<Calls*>(const_cast<void*>(context));
  calls.perRange[range].fetch_add(1);
}

TEST(KeptThreads, EveryRangeRunsOncePerLoopLoopAfterLoop) {
  Calls calls;
  constexpr int kLoops = 2000;
  for (int loop = 0; loop < kLoops; ++loop) {
    // Range counts that change from loop to loop: no thread may run a range of a loop twice.
    const std::size_t ranges = 2 + static_cast<std::size_t>(loop % 5);
    ASSERT_TRUE(runOnKeptThreads(ranges, countCall, &calls));
    for (std::size_t r = 0; r < calls.perRange.size(); ++r)
      ASSERT_EQ(calls.perRange[r].exchange(0), r < ranges ? 1 : 0) << "loop " << loop << ", range " << r;
  }
}

TEST(KeptThreads, LoopsAfterTheThreadsSleptRunEveryWorker) {
  Calls calls;
  for (int loop = 0; loop < 5; ++loop) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // past the polling: the threads sleep
    ASSERT_TRUE(runOnKeptThreads(3, countCall, &calls));
    for (std::size_t r = 0; r < 3; ++r) ASSERT_EQ(calls.perRange[r].exchange(0), 1);
  }
}

TEST(KeptThreads, ALoopInsideALoopIsRefusedAndForEachRangeStillRunsItsRanges) {
  std::atomic<int> refused{0};
  std::vector<int> innerItems(4 * 100, 0);
  forEachRange(4, 4, [&](std::size_t outer, std::size_t, std::size_t) {
    Calls ignored;
    if (!runOnKeptThreads(2, countCall, &ignored)) refused.fetch_add(1);
    // The nested loop falls back to threads of its own and still covers its items once.
    forEachRange(100, 2, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) ++innerItems[outer * 100 + i];
    });
  });
  EXPECT_EQ(refused.load(), 4);
  for (int count : innerItems) EXPECT_EQ(count, 1);
}

// A background thread that counts its steps, yielding to foreground work before each.
class CountingBackground {
public:
  CountingBackground()
      : thread_([this](std::stop_token stop) {
          const BackgroundScope scope;
          while (!stop.stop_requested()) {
            yieldToForeground();
            steps_.fetch_add(1);
          }
        }) {}
  ~CountingBackground() {
    thread_.request_stop();
    const WaitingForBackground waiting;  // the thread may be paused by a test's foreground work
    thread_.join();
  }

  long steps() const { return steps_.load(); }

  /// Whether the thread takes a step beyond `steps` within 10 s.
  bool goesOnBeyond(long steps) const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (steps_.load() <= steps && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
    return steps_.load() > steps;
  }

private:
  std::atomic<long> steps_{0};
  std::jthread thread_;
};

TEST(KeptThreads, ABackgroundThreadPausesWhileForegroundWorkRunsAndGoesOnAfter) {
  CountingBackground background;
  ASSERT_TRUE(background.goesOnBeyond(0));
  long stepsAtStart = 0, stepsAtEnd = 0;
  {
    const ForegroundWork foreground(2);
    stepsAtStart = background.steps();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    stepsAtEnd = background.steps();
  }
  // A step begun before the foreground work began may end during it; no other.
  EXPECT_LE(stepsAtEnd - stepsAtStart, 1);
  EXPECT_TRUE(background.goesOnBeyond(stepsAtEnd + 1)) << "the background thread did not go on";
}

TEST(KeptThreads, OneThreadsForegroundWorkAndABackgroundThreadsOwnDoNotPauseTheBackground) {
  CountingBackground background;
  ASSERT_TRUE(background.goesOnBeyond(0));
  {
    const ForegroundWork oneThread(1);
    EXPECT_TRUE(background.goesOnBeyond(background.steps() + 1));
  }
  // A background thread's loop on two threads: its own kept threads, which work in the
  // background too and do not pause it, nor themselves.
  std::atomic<int> ranges{0};
  std::jthread backgroundLoop([&] {
    const BackgroundScope scope;
    const ForegroundWork notForeground(2);
    forEachRange(2, 2, [&](std::size_t, std::size_t, std::size_t) {
      yieldToForeground();
      ranges.fetch_add(1);
    });
  });
  backgroundLoop.join();
  EXPECT_EQ(ranges.load(), 2);
  EXPECT_TRUE(background.goesOnBeyond(background.steps() + 1));
}

TEST(KeptThreads, WaitingForTheBackgroundLetsItRunBesideForegroundWork) {
  CountingBackground background;
  ASSERT_TRUE(background.goesOnBeyond(0));
  const ForegroundWork foreground(2);
  const long paused = background.steps();
  const WaitingForBackground waiting;
  EXPECT_TRUE(background.goesOnBeyond(paused + 1));
}

TEST(KeptThreads, ThreadsAskedForAreWorkersUpToOnePerMinimumOfItems) {
  EXPECT_EQ(workerCount(10'000, 2, 100), 2u);
  EXPECT_EQ(workerCount(10'000, 0, 100), 1u);
  EXPECT_EQ(workerCount(150, 4, 100), 1u);
  EXPECT_EQ(workerCount(350, 4, 100), 3u);
}

}  // namespace
}  // namespace mane::subdiv::detail
