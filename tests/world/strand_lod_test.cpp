// nalu's groom seen from four times its camera's distance, where its strands are about a quarter
// of a pixel wide: with a level-of-detail width of a pixel (render/strand_lod.hpp) about a
// quarter of them is drawn, each four times as wide, and the groom must cover the screen as the
// whole groom does. The
// head alone (no bunny, fins or post-processing, no hair shadows), rendered with its groom at the
// scene's level of detail, with every strand, and without the groom; the hair's coverage is
// the sum over the frame of what it changes.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"
#include "tests/world/nalu_frames.hpp"

namespace mane::scenes {
namespace {

constexpr vk::Extent2D kExtent{1280, 720};  // nalu.json's frame
constexpr float kFarther = 4.0f;            // times the camera's distance
constexpr int kChangedChannel = 4;          // as scalp_coverage_test.cpp counts a pixel changed

/// nalu.json's head alone (testing::naluHeadAlone), seen from kFarther times as far, changed by
/// `edit`.
std::optional<World> naluHeadFromAfar(const std::function<void(Scene&)>& edit) {
  std::optional<Scene> scene = testing::naluHeadAlone([&](Scene& head) {
    head.camera.position = head.camera.target + (head.camera.position - head.camera.target) * kFarther;
    edit(head);
  });
  if (!scene) return std::nullopt;
  auto world = World::create(std::move(*scene), testing::sharedResolver());
  EXPECT_TRUE(world.has_value()) << world.error().message;
  if (!world) return std::nullopt;
  return std::move(*world);
}

/// What the hair changes against the bald frame: pixels changed, and Σ over channels of |change|.
struct HairChange {
  std::size_t pixels = 0;
  double sum = 0.0;
};

HairChange hairChange(const std::vector<std::uint8_t>& withHair, const std::vector<std::uint8_t>& bald) {
  HairChange change;
  for (std::size_t at = 0; at + 3 < withHair.size() && at + 3 < bald.size(); at += 4) {
    int largest = 0;
    for (int c = 0; c < 3; ++c) {
      const int difference = std::abs(int(withHair[at + c]) - int(bald[at + c]));
      largest = std::max(largest, difference);
      change.sum += difference;
    }
    change.pixels += largest >= kChangedChannel ? 1 : 0;
  }
  return change;
}

class StrandLevelOfDetailFrame : public mane::testing::VulkanTest {};

TEST_F(StrandLevelOfDetailFrame, NalusGroomFromAfarCoversWhatItsEveryStrandCovers) {
  MANE_RESOLVE_OR_SKIP(head, "head/LeePerrySmith/LeePerrySmith.glb");
  std::optional<World> detailed =
      naluHeadFromAfar([](Scene& scene) { scene.grooms.at(0).rendering.settings.lodPixelWidth = 1.0f; });
  std::optional<World> everyStrand =
      naluHeadFromAfar([](Scene& scene) { scene.grooms.at(0).rendering.settings.lodPixelWidth = 0.0f; });
  std::optional<World> bald = naluHeadFromAfar([](Scene& scene) { scene.grooms.clear(); });
  ASSERT_TRUE(detailed && everyStrand && bald);

  for (const std::uint32_t samples : {1u, 4u}) {
    const render::RendererSettings settings{.extent = kExtent, .msaaSamples = samples};
    float keptShare = 0.0f;
    const std::vector<std::uint8_t> withLod = testing::renderFrame(
        device(), *detailed, settings,
        [&](const render::Renderer& renderer) { keptShare = renderer.hairChoices().at(0).keptShare; });
    const std::vector<std::uint8_t> whole = testing::renderFrame(device(), *everyStrand, settings);
    const std::vector<std::uint8_t> without = testing::renderFrame(device(), *bald, settings);
    const HairChange lod = hairChange(withLod, without), all = hairChange(whole, without);
    ASSERT_GT(all.pixels, 2000u) << "the groom should cover a few thousand pixels from afar";
    EXPECT_GT(keptShare, 0.2f);
    EXPECT_LT(keptShare, 0.3f) << "strands about a quarter of a pixel wide";
    // The coverage: what the hair takes from the frame, summed. Fewer strands touch fewer of the
    // pixels where strays cross the background, each more strongly; the count is printed.
    EXPECT_NEAR(lod.sum, all.sum, 0.05 * all.sum) << samples << "x: summed change";
    std::printf(
        "%ux: %.0f %% of the strands drawn: %zu pixels changed against %zu with every strand (%+.1f %%), "
        "summed change %+.1f %%\n",
        samples, 100.0 * keptShare, lod.pixels, all.pixels,
        100.0 * (double(lod.pixels) - double(all.pixels)) / double(all.pixels), 100.0 * (lod.sum - all.sum) / all.sum);
  }
}

}  // namespace
}  // namespace mane::scenes
