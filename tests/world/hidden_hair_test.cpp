// Hair hidden behind the opaque scene (render/passes/hair_pass.hpp, "Hidden strands") on
// scenes/nalu.json, whose long hair falls behind the head and the shoulders: the frame drawn with
// the hidden segments left out is the frame drawn with every segment, byte for byte, at 1× and 4×
// MSAA, while a large share of the strands' vertices is left out.

#include <cstdint>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/vulkan_fixture.hpp"
#include "tests/world/nalu_frames.hpp"

namespace mane::scenes {
namespace {

constexpr vk::Extent2D kExtent{320, 180};

class HiddenHair : public mane::testing::VulkanTest {
protected:
  struct Frame {
    std::vector<std::uint8_t> pixels;
    double hiddenShare = 0.0;  // of the groom's dense vertices
  };

  Frame render(World& world, std::uint32_t samples, bool hideOccludedHair) {
    Frame frame;
    frame.pixels = testing::renderFrame(
        device(), world, {.extent = kExtent, .msaaSamples = samples, .hideOccludedHair = hideOccludedHair},
        [&](const render::Renderer& renderer) {
          const render::StaticScene statics = world.staticScene();
          const DenseStrandLayout& layout = statics.grooms.at(0).layout;
          const double vertices = double(layout.strands.size()) * layout.vertexCount;
          frame.hiddenShare = renderer.hairChoices().at(0).hiddenVertices / vertices;
        });
    return frame;
  }
};

TEST_F(HiddenHair, NaluLooksTheSameWithTheHiddenHairLeftOut) {
  // Every strand drawn: at this frame size the level of detail would leave most of them out.
  std::optional<World> world =
      testing::naluIntoItsAnimation([](Scene& scene) { scene.grooms.at(0).rendering.settings.lodPixelWidth = 0.0f; });
  ASSERT_TRUE(world.has_value());
  ASSERT_FALSE(world->staticScene().grooms.empty());

  for (const std::uint32_t samples : {1u, 4u}) {
    const Frame hidden = render(*world, samples, true);
    const Frame everything = render(*world, samples, false);
    ASSERT_EQ(hidden.pixels.size(), std::size_t(kExtent.width) * kExtent.height * 4);
    const testing::ChannelDifferences differences = testing::compareChannels(hidden.pixels, everything.pixels);
    EXPECT_EQ(differences.differing, 0u) << samples << "× MSAA: channels differ, by up to " << differences.largest;
    // Without the opaque depth only the segments off the screen are left out (the hair's ends
    // below the frame); with it, those behind the head and shoulders too.
    EXPECT_GT(hidden.hiddenShare, everything.hiddenShare + 0.2) << samples << "× MSAA";
    std::cout << samples << "× MSAA: " << hidden.hiddenShare << " of the vertices hidden, " << everything.hiddenShare
              << " off the screen\n";
  }
}

}  // namespace
}  // namespace mane::scenes
