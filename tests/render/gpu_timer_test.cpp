// GpuTimer: each pass gets its time, and a pass begun right after another ended starts at that
// end's timestamp, so back-to-back passes tile the frame without gaps.

#include <stdexcept>

#include <gtest/gtest.h>

#include "render/gpu_timer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

using GpuTimerTest = testing::VulkanTest;

TEST_F(GpuTimerTest, BackToBackPassesShareTheirBoundaryTimestamp) {
  GpuTimer timer(device(), 3);
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    timer.reset(commands);
    timer.begin(commands, PassName("first"));
    timer.end(commands);
    timer.begin(commands, PassName("second"));
    timer.end(commands);
    // A barrier between two passes counts with the later one: it still starts where the last ended.
    const vk::MemoryBarrier2 barrier{.srcStageMask = vk::PipelineStageFlagBits2::eAllCommands,
                                     .srcAccessMask = vk::AccessFlagBits2::eMemoryWrite,
                                     .dstStageMask = vk::PipelineStageFlagBits2::eAllCommands,
                                     .dstAccessMask = vk::AccessFlagBits2::eMemoryRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &barrier});
    timer.begin(commands, PassName("third"));
    timer.end(commands);
  });
  const std::vector<PassTiming> timings = timer.results();
  ASSERT_EQ(timings.size(), 3u);
  EXPECT_EQ(timings[0].pass, PassName("first"));
  EXPECT_EQ(timings[1].pass, PassName("second"));
  EXPECT_EQ(timings[2].pass, PassName("third"));
  EXPECT_EQ(timings[0].startMilliseconds, 0.0);
  for (std::size_t i = 0; i < timings.size(); ++i) {
    EXPECT_GE(timings[i].milliseconds, 0.0) << timings[i].pass;
    if (i > 0) {
      EXPECT_DOUBLE_EQ(timings[i].startMilliseconds, timings[i - 1].startMilliseconds + timings[i - 1].milliseconds)
          << timings[i].pass;
    }
  }
}

// A hand-off writes a timestamp that no pass begins or ends at: the pass around it spans it, the
// next pass writes its own beginning, and hand-offs count against the timer's room.
TEST_F(GpuTimerTest, AHandOffTimesNothing) {
  GpuTimer timer(device(), 3);
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    timer.reset(commands);
    timer.begin(commands, PassName("around"));
    timer.handOff(commands);
    timer.end(commands);
    timer.handOff(commands);
    timer.begin(commands, PassName("after"));
    timer.end(commands);
    EXPECT_THROW(timer.handOff(commands), std::logic_error) << "six timestamps fill the room of three passes";
  });
  const std::vector<PassTiming> timings = timer.results();
  ASSERT_EQ(timings.size(), 2u);
  EXPECT_EQ(timings[0].pass, PassName("around"));
  EXPECT_EQ(timings[1].pass, PassName("after"));
  EXPECT_GE(timings[0].milliseconds, 0.0);
  EXPECT_GE(timings[1].startMilliseconds, timings[0].startMilliseconds + timings[0].milliseconds);
}

TEST_F(GpuTimerTest, EndWithoutABegunPassIsAnError) {
  GpuTimer timer(device(), 1);
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    timer.reset(commands);
    EXPECT_THROW(timer.end(commands), std::logic_error);
    timer.begin(commands, PassName("only"));
    timer.end(commands);
    EXPECT_THROW(timer.end(commands), std::logic_error);
  });
  ASSERT_EQ(timer.results().size(), 1u);
}

}  // namespace
}  // namespace mane::render
