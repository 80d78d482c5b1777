// The deferred skin (render/passes/surface_pass.hpp, "Deferred skin") on scenes/nalu.json: the
// head's pre-integrated skin drawn into a G-buffer and lit once per pixel gives the frame the
// forward fragment shader gives, byte for byte, with the fins, the furred bunny, the sun's disc
// and the hair drawn over and around it. Under 4× MSAA the skin stays forward.

#include <gtest/gtest.h>

#include "tests/support/vulkan_fixture.hpp"
#include "tests/world/nalu_frames.hpp"

namespace mane::scenes {
namespace {

constexpr vk::Extent2D kExtent{320, 180};

class DeferredSkin : public mane::testing::VulkanTest {};

TEST_F(DeferredSkin, NaluLooksTheSameWithTheSkinLitOncePerPixel) {
  std::optional<World> world = testing::naluIntoItsAnimation();
  ASSERT_TRUE(world.has_value());
  bool deferred = false, forwardDeferred = true, multisampledDeferred = true;
  const auto pixels =
      testing::renderFrame(device(), *world, {.extent = kExtent, .deferSkin = true},
                           [&](const render::Renderer& r) { deferred = r.defersSkin(world->frameInput()); });
  const auto forward =
      testing::renderFrame(device(), *world, {.extent = kExtent, .deferSkin = false},
                           [&](const render::Renderer& r) { forwardDeferred = r.defersSkin(world->frameInput()); });
  ASSERT_TRUE(deferred);
  ASSERT_FALSE(forwardDeferred);
  ASSERT_EQ(pixels.size(), std::size_t(kExtent.width) * kExtent.height * 4);
  ASSERT_EQ(forward.size(), pixels.size());
  const testing::ChannelDifferences differences = testing::compareChannels(pixels, forward);
  EXPECT_EQ(differences.differing, 0u) << "channels differ, by up to " << differences.largest;

  testing::renderFrame(device(), *world, {.extent = kExtent, .msaaSamples = 4, .deferSkin = true},
                       [&](const render::Renderer& r) { multisampledDeferred = r.defersSkin(world->frameInput()); });
  EXPECT_FALSE(multisampledDeferred) << "a multisampled target keeps no G-buffer";
}

}  // namespace
}  // namespace mane::scenes
