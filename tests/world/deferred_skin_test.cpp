// The deferred skin (render/passes/deferred_skin_pass.hpp) on scenes/nalu.json: the
// head's pre-integrated skin drawn into a G-buffer and lit once per pixel gives the frame the
// forward fragment shader gives, byte for byte, with the fins, the furred bunny, the sun's disc
// and the hair drawn over and around it, under either hair shadow mode. Under 4× MSAA the skin
// stays forward.

#include <optional>

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
  const auto defers = [&](bool& deferred) {
    return [&world, out = &deferred](const render::Renderer& renderer) {
      *out = renderer.defersSkin(world->frameInput());
    };
  };
  // Both hair shadow modes: the deferred lighting looks either map up at the G-buffer's position.
  for (const render::HairShadowMode shadows :
       {render::HairShadowMode::kOpacityShadowMap, render::HairShadowMode::kDeepOpacityMap}) {
    bool deferred = false, forwardDeferred = true;
    const auto pixels = testing::renderFrame(device(), *world, {.extent = kExtent}, defers(deferred), shadows);
    const auto forward = testing::renderFrame(device(), *world, {.extent = kExtent, .deferSkin = false},
                                              defers(forwardDeferred), shadows);
    ASSERT_TRUE(deferred);
    ASSERT_FALSE(forwardDeferred);
    ASSERT_EQ(pixels.size(), std::size_t(kExtent.width) * kExtent.height * 4);
    ASSERT_EQ(forward.size(), pixels.size());
    const testing::ChannelDifferences differences = testing::compareChannels(pixels, forward);
    EXPECT_EQ(differences.differing, 0u) << "hair shadow mode " << int(shadows) << ": channels differ, by up to "
                                         << differences.largest;
  }

  bool multisampledDeferred = true;
  testing::renderFrame(device(), *world, {.extent = kExtent, .msaaSamples = 4}, defers(multisampledDeferred));
  EXPECT_FALSE(multisampledDeferred) << "a multisampled target keeps no G-buffer";
}

}  // namespace
}  // namespace mane::scenes
