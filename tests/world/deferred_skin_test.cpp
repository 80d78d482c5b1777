// The deferred skin (render/passes/surface_pass.hpp, "Deferred skin") on scenes/nalu.json: the
// head's pre-integrated skin drawn into a G-buffer and lit once per pixel gives the frame the
// forward fragment shader gives, byte for byte, with the fins, the furred bunny, the sun's disc
// and the hair drawn over and around it. Under 4× MSAA the skin stays forward.

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/renderer_upload.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

const std::filesystem::path kNalu = std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json";
constexpr vk::Extent2D kExtent{320, 180};

class DeferredSkin : public mane::testing::VulkanTest {
protected:
  struct Frame {
    std::vector<std::uint8_t> pixels;
    bool deferred = false;
  };

  Frame render(World& world, std::uint32_t samples, bool deferSkin) {
    auto renderer =
        render::Renderer::create(device(), {.extent = kExtent, .msaaSamples = samples, .deferSkin = deferSkin});
    EXPECT_TRUE(renderer.has_value()) << renderer.error().message;
    if (!renderer) return {};
    EXPECT_TRUE((*renderer)->setScene(world.staticScene()).has_value());
    auto uploaded = uploadFrameState(world, **renderer);
    EXPECT_TRUE(uploaded.has_value()) << uploaded.error().message;
    auto rendered = (*renderer)->render(world.frameInput());
    EXPECT_TRUE(rendered.has_value()) << rendered.error().message;
    auto pixels = (*renderer)->readOutput();
    EXPECT_TRUE(pixels.has_value());
    return {.pixels = pixels ? *pixels : std::vector<std::uint8_t>{},
            .deferred = (*renderer)->defersSkin(world.frameInput())};
  }
};

TEST_F(DeferredSkin, NaluLooksTheSameWithTheSkinLitOncePerPixel) {
  auto scene = loadScene(kNalu);
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  scene->simulation.settleSeconds = 0.0f;
  auto world = World::create(std::move(*scene), testing::sharedResolver());
  ASSERT_TRUE(world.has_value()) << world.error().message;
  // Into the animation, the head turned and the hair over it moving.
  for (int frame = 0; frame < 20; ++frame) ASSERT_TRUE(world->advance(1.0 / 30.0, 2).has_value());

  const Frame deferred = render(*world, 1, true);
  const Frame forward = render(*world, 1, false);
  ASSERT_TRUE(deferred.deferred);
  ASSERT_FALSE(forward.deferred);
  ASSERT_EQ(deferred.pixels.size(), std::size_t(kExtent.width) * kExtent.height * 4);
  ASSERT_EQ(forward.pixels.size(), deferred.pixels.size());
  std::size_t differing = 0;
  int largest = 0;
  for (std::size_t i = 0; i < deferred.pixels.size(); ++i) {
    const int difference = std::abs(int(deferred.pixels[i]) - int(forward.pixels[i]));
    differing += difference != 0 ? 1 : 0;
    largest = std::max(largest, difference);
  }
  EXPECT_EQ(differing, 0u) << "channels differ, by up to " << largest;

  EXPECT_FALSE(render(*world, 4, true).deferred) << "a multisampled target keeps no G-buffer";
}

}  // namespace
}  // namespace mane::scenes
