// Hair hidden behind the opaque scene (render/passes/hair_pass.hpp, "Hidden strands") on
// scenes/nalu.json, whose long hair falls behind the head and the shoulders: the frame drawn with
// the hidden segments left out is the frame drawn with every segment, byte for byte, at 1× and 4×
// MSAA, while a large share of the strands' vertices is left out.

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <iostream>
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

class HiddenHair : public mane::testing::VulkanTest {
protected:
  struct Frame {
    std::vector<std::uint8_t> pixels;
    double hiddenShare = 0.0;  // of the groom's dense vertices
  };

  Frame render(World& world, std::uint32_t samples, bool hideOccludedHair) {
    auto renderer = render::Renderer::create(
        device(), {.extent = kExtent, .msaaSamples = samples, .hideOccludedHair = hideOccludedHair});
    EXPECT_TRUE(renderer.has_value()) << renderer.error().message;
    if (!renderer) return {};
    const render::StaticScene statics = world.staticScene();
    EXPECT_TRUE((*renderer)->setScene(statics).has_value());
    auto uploaded = uploadFrameState(world, **renderer);
    EXPECT_TRUE(uploaded.has_value()) << uploaded.error().message;
    auto rendered = (*renderer)->render(world.frameInput());
    EXPECT_TRUE(rendered.has_value()) << rendered.error().message;
    auto pixels = (*renderer)->readOutput();
    EXPECT_TRUE(pixels.has_value());
    const render::DenseStrandLayout& layout = statics.grooms.at(0).layout;
    const double vertices = double(layout.strands.size()) * layout.vertexCount;
    return {.pixels = pixels ? *pixels : std::vector<std::uint8_t>{},
            .hiddenShare = (*renderer)->hairChoices().at(0).hiddenVertices / vertices};
  }
};

TEST_F(HiddenHair, NaluLooksTheSameWithTheHiddenHairLeftOut) {
  auto scene = loadScene(kNalu);
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  scene->simulation.settleSeconds = 0.0f;
  auto world = World::create(std::move(*scene), testing::sharedResolver());
  ASSERT_TRUE(world.has_value()) << world.error().message;
  ASSERT_FALSE(world->staticScene().grooms.empty());
  // Into the animation, the head turned and the hair moving.
  for (int frame = 0; frame < 20; ++frame) ASSERT_TRUE(world->advance(1.0 / 30.0, 2).has_value());

  for (const std::uint32_t samples : {1u, 4u}) {
    const Frame hidden = render(*world, samples, true);
    const Frame everything = render(*world, samples, false);
    ASSERT_EQ(hidden.pixels.size(), std::size_t(kExtent.width) * kExtent.height * 4);
    std::size_t differing = 0;
    int largest = 0;
    for (std::size_t i = 0; i < hidden.pixels.size() && i < everything.pixels.size(); ++i) {
      const int difference = std::abs(int(hidden.pixels[i]) - int(everything.pixels[i]));
      differing += difference != 0 ? 1 : 0;
      largest = std::max(largest, difference);
    }
    EXPECT_EQ(differing, 0u) << samples << "× MSAA: channels differ, by up to " << largest;
    // Without the opaque depth only the segments off the screen are left out (the hair's ends
    // below the frame); with it, those behind the head and shoulders too.
    EXPECT_GT(hidden.hiddenShare, everything.hiddenShare + 0.2) << samples << "× MSAA";
    std::cout << samples << "× MSAA: " << hidden.hiddenShare << " of the vertices hidden, " << everything.hiddenShare
              << " off the screen\n";
  }
}

}  // namespace
}  // namespace mane::scenes
