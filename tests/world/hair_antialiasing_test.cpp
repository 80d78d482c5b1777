// nalu's hair drawn with one sample per pixel (analytic coverage) against the same hair drawn with
// 64: the frame 20 frames into nalu.json's animation, without post-processing (the auto gain
// would follow the frame's brightness). The reference is the frame rendered at 4 × 4 times the
// pixels with 4× MSAA, its blocks of 4 × 4 pixels averaged in linear light: 64 samples per pixel.
// The hair's pixels are those its strands change: the frame with its groom against the frame
// without, both at 4× MSAA with hair shadows off, so that only the pixels a strand covers count,
// not the skin its shadow falls on. Over them the 1× frame must come at least as close to the
// reference as the 4× MSAA frame does.

#include <algorithm>
#include <cmath>
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

constexpr vk::Extent2D kExtent{1280, 720};    // nalu.json's frame
constexpr std::uint32_t kReferenceScale = 4;  // pixels of the reference per pixel of the frame, each way
// The smallest change, in one 8-bit channel, that counts a pixel as the hair's (as in
// scalp_coverage_test.cpp): above the frames' rounding noise.
constexpr int kChangedChannel = 4;

/// nalu.json without post-processing, changed by `edit`, 20 frames into its animation. Every
/// strand drawn: the reference's strands are four times as wide on screen, which the level of
/// detail would draw differently.
std::optional<World> naluWithoutPost(const std::function<void(Scene&)>& edit) {
  return testing::naluIntoItsAnimation([&](Scene& scene) {
    scene.post = {};
    scene.grooms.at(0).rendering.settings.lodPixelWidth = 0.0f;
    edit(scene);
  });
}

double linearFromSrgb(std::uint8_t value) {
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double srgbFromLinear(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return 255.0 * (c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055);
}

/// RGB of `large` (RGBA8, kReferenceScale times kExtent each way) averaged over each frame
/// pixel's block in linear light, re-encoded, as kExtent's pixels × 3 doubles.
std::vector<double> averageBlocks(const std::vector<std::uint8_t>& large) {
  const std::uint32_t largeWidth = kExtent.width * kReferenceScale;
  std::vector<double> averaged(std::size_t(kExtent.width) * kExtent.height * 3);
  for (std::uint32_t y = 0; y < kExtent.height; ++y)
    for (std::uint32_t x = 0; x < kExtent.width; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (std::uint32_t j = 0; j < kReferenceScale; ++j)
          for (std::uint32_t i = 0; i < kReferenceScale; ++i)
            sum += linearFromSrgb(
                large[4 * ((std::size_t(y) * kReferenceScale + j) * largeWidth + x * kReferenceScale + i) + c]);
        averaged[3 * (std::size_t(y) * kExtent.width + x) + c] =
            srgbFromLinear(sum / double(kReferenceScale * kReferenceScale));
      }
  return averaged;
}

class HairAntiAliasing : public mane::testing::VulkanTest {};

TEST_F(HairAntiAliasing, OneSampleComesAsCloseToSixtyFourAsFourSamplesDo) {
  MANE_RESOLVE_OR_SKIP(head, "head/LeePerrySmith/LeePerrySmith.glb");
  std::optional<World> shaded = naluWithoutPost([](Scene&) {});
  std::optional<World> unshadowed =
      naluWithoutPost([](Scene& scene) { scene.hairShadows.mode = render::HairShadowMode::kOff; });
  std::optional<World> bald = naluWithoutPost([](Scene& scene) {
    scene.hairShadows.mode = render::HairShadowMode::kOff;
    scene.grooms.clear();
  });
  ASSERT_TRUE(shaded && unshadowed && bald);

  const auto frame = [&](World& world, std::uint32_t samples, std::uint32_t scale = 1) {
    return testing::renderFrame(device(), world,
                                {.extent = {kExtent.width * scale, kExtent.height * scale}, .msaaSamples = samples});
  };
  const std::vector<std::uint8_t> withHair = frame(*unshadowed, 4), withoutHair = frame(*bald, 4);
  const std::vector<std::uint8_t> single = frame(*shaded, 1), four = frame(*shaded, 4);
  const std::vector<std::uint8_t> large = frame(*shaded, 4, kReferenceScale);
  const std::size_t size = std::size_t(kExtent.width) * kExtent.height * 4;
  ASSERT_EQ(withHair.size(), size);
  ASSERT_EQ(withoutHair.size(), size);
  ASSERT_EQ(single.size(), size);
  ASSERT_EQ(four.size(), size);
  ASSERT_EQ(large.size(), size * kReferenceScale * kReferenceScale);
  const std::vector<double> reference = averageBlocks(large);

  std::size_t hairPixels = 0;
  double singleError = 0.0, fourError = 0.0, singleToFour = 0.0;
  for (std::size_t pixel = 0; pixel < size / 4; ++pixel) {
    int change = 0;
    for (int c = 0; c < 3; ++c)
      change = std::max(change, std::abs(int(withHair[4 * pixel + c]) - int(withoutHair[4 * pixel + c])));
    if (change < kChangedChannel) continue;
    ++hairPixels;
    for (int c = 0; c < 3; ++c) {
      const double truth = reference[3 * pixel + c];
      singleError += std::abs(single[4 * pixel + c] - truth);
      fourError += std::abs(four[4 * pixel + c] - truth);
      singleToFour += std::abs(int(single[4 * pixel + c]) - int(four[4 * pixel + c]));
    }
  }
  ASSERT_GT(hairPixels, 20000u) << "nalu's hair should fill much of the frame";
  const double channels = 3.0 * double(hairPixels);
  std::printf(
      "%zu hair pixels, mean |difference| in 1/255: 1x against 64 samples %.2f, 4x against 64 samples %.2f, "
      "1x against 4x %.2f\n",
      hairPixels, singleError / channels, fourError / channels, singleToFour / channels);
  EXPECT_LE(singleError, fourError) << "one sample with analytic coverage should be no further from 64 than 4× MSAA";
}

}  // namespace
}  // namespace mane::scenes
