// The kept threads behind forEachRange (subdiv/detail/worker_pool.hpp): every range runs
// exactly once per loop, loop after loop, with or without the threads sleeping between
// loops; a loop started inside a loop is refused and runs on threads of its own; a background
// thread takes one worker from the loops beside it.

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

TEST(KeptThreads, ABackgroundThreadTakesOneWorkerFromTheLoopsBesideIt) {
  EXPECT_EQ(workerCount(10'000, 2, 100), 2u);
  {
    BackgroundThreadToken preparing;
    EXPECT_EQ(workerCount(10'000, 2, 100), 1u);
    EXPECT_EQ(workerCount(10'000, 4, 100), 3u);
    EXPECT_EQ(workerCount(10'000, 1, 100), 1u);
    BackgroundThreadToken moved = std::move(preparing);  // counted once, by whichever holds it
    EXPECT_EQ(workerCount(10'000, 4, 100), 3u);
  }
  EXPECT_EQ(workerCount(10'000, 2, 100), 2u);
}

}  // namespace
}  // namespace mane::subdiv::detail
