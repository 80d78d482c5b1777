// Per-strand looks (render/hair_data.hpp HairStrandLook, render/strand_looks.hpp) in the hair
// pass and the hair lighting pass, against the groom-wide settings they scale and against the
// parallel strands' exact coverage (hair_pass_fixture.hpp):
//  - a strand's width, tip width and opacity factors draw it exactly as the groom's settings
//    scaled by the same factors would, pixel for pixel (the factors here are powers of two, so
//    the products are exact), and each strand takes its own;
//  - a strand's colour multiplies the light that crossed the fibre (TT, TRT, ambient) and leaves
//    the reflection off its surface (R) the light's colour.
// Every test runs with the validation layers on; any message fails it (VulkanTest).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/strand_looks.hpp"
#include "tests/render/hair_pass_fixture.hpp"

namespace mane::render {
namespace {

using namespace hair_fixture;

const std::array kFrontLight{DirectionalLight{.direction = {0, 0, 1}}};

/// The parallel strands drawn `groom`-wide with `looks` (none: plain).
Pixels drawParallel(HairPassTest& test, vk::SampleCountFlagBits samples, const HairGroomSettings& groom,
                    std::vector<HairStrandLook> looks = {}) {
  test.looks = std::move(looks);
  const Pixels pixels = test.render(test.lut(blondeHairParams()), parallelStrands(), samples,
                                    {orthographicView(kCoverageExtent, kMetresPerPixel), kCoverageExtent},
                                    kFrontLight, glm::vec3(0.1f), groom);
  test.looks.clear();
  return pixels;
}

std::size_t differingPixels(const Pixels& a, const Pixels& b) {
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differing += a[i] != b[i] ? 1 : 0;
  return differing;
}

TEST_F(HairPassTest, WidthFactorsDrawAsTheGroomsWidthAndTaperScaledAlike) {
  // Factors 2 (width) and 0.5 (tip) on a 3.3-pixel groom draw what a 6.6-pixel groom tapering to
  // half does, pixel for pixel; untapered, twice the width covers twice the area (exact counting,
  // parallelStrands: 1 % for the 16-bit alpha).
  for (const auto samples : {vk::SampleCountFlagBits::e1, vk::SampleCountFlagBits::e4}) {
    const float width = 3.3f * kMetresPerPixel;
    const std::vector<HairStrandLook> wider(kStrands, HairStrandLook{.widthScale = 2.0f, .tipWidthScale = 0.5f});
    const Pixels scaled = drawParallel(*this, samples, {.width = width}, wider);
    const Pixels settings = drawParallel(*this, samples, {.width = 2.0f * width, .tipWidthScale = 0.5f});
    EXPECT_EQ(differingPixels(scaled, settings), 0u) << int(samples) << "x";

    const std::vector<HairStrandLook> doubled(kStrands, HairStrandLook{.widthScale = 2.0f});
    const double plain = measureCoverage(drawParallel(*this, samples, {.width = width})).sum;
    const double twice = measureCoverage(drawParallel(*this, samples, {.width = width}, doubled)).sum;
    const double area = kStrands * 3.3 * kLengthPixels;
    EXPECT_NEAR(plain, area, 0.01 * area) << int(samples) << "x";
    EXPECT_NEAR(twice, 2.0 * area, 0.01 * 2.0 * area) << int(samples) << "x";
  }
}

TEST_F(HairPassTest, EachStrandTakesItsOwnLook) {
  // The five left strands plain, the five right ones twice as wide and half as opaque: left of
  // x = 58 (between strand 4's right edge at 54.1 and strand 5's doubled left edge at 61.3) the
  // pixels are the plain groom's, right of it those of a groom drawn so throughout.
  const auto samples = vk::SampleCountFlagBits::e4;
  const float width = 3.3f * kMetresPerPixel;
  std::vector<HairStrandLook> looks(kStrands);
  for (int s = kStrands / 2; s < kStrands; ++s) looks[s] = {.widthScale = 2.0f, .opacityScale = 0.5f};
  const Pixels mixed = drawParallel(*this, samples, {.width = width}, looks);
  const Pixels plain = drawParallel(*this, samples, {.width = width});
  const Pixels wide = drawParallel(*this, samples, {.width = 2.0f * width, .opacity = 0.5f});
  std::size_t leftDiffering = 0, rightDiffering = 0;
  for (std::size_t i = 0; i < mixed.size(); ++i) {
    if (i % kCoverageExtent.width < 58)
      leftDiffering += mixed[i] != plain[i] ? 1 : 0;
    else
      rightDiffering += mixed[i] != wide[i] ? 1 : 0;
  }
  EXPECT_EQ(leftDiffering, 0u);
  EXPECT_EQ(rightDiffering, 0u);
}

TEST_F(HairPassTest, AnOpacityFactorScalesTheStrandsCoverage) {
  // As the groom's opacity does, pixel for pixel, for ribbons (3.3 pixels) and for the lines that
  // stand in for sub-pixel strands (0.3 pixels): half the opacity, half the summed alpha (1 %).
  for (const float pixels : {3.3f, 0.3f}) {
    const auto samples = vk::SampleCountFlagBits::e4;
    const float width = pixels * kMetresPerPixel;
    const std::vector<HairStrandLook> half(kStrands, HairStrandLook{.opacityScale = 0.5f});
    const Pixels scaled = drawParallel(*this, samples, {.width = width}, half);
    EXPECT_EQ(lastChoice.primitive, pixels < 1.0f ? HairPrimitive::kLines : HairPrimitive::kRibbons);
    const Pixels settings = drawParallel(*this, samples, {.width = width, .opacity = 0.5f});
    EXPECT_EQ(differingPixels(scaled, settings), 0u) << pixels << " px";
    const double area = kStrands * double(pixels) * kLengthPixels;
    EXPECT_NEAR(measureCoverage(scaled).sum, 0.5 * area, 0.01 * 0.5 * area) << pixels << " px";
  }
}

// One opaque vertical strand 20 pixels wide through the image centre.
constexpr vk::Extent2D kColourExtent{64, 64};

StrandData wideStrand() {
  StrandData data;
  addStraightStrand(data, {0.0f, -0.025f, 0.0f}, {0.0f, 0.025f, 0.0f}, 8);
  return data;
}

glm::vec3 centre(const Pixels& pixels) {
  return glm::vec3(pixels[std::size_t(kColourExtent.height / 2) * kColourExtent.width + kColourExtent.width / 2]);
}

TEST_F(HairPassTest, AStrandsColourTintsTheLightThroughTheFibreNotItsSurfaceReflection) {
  const MarschnerLut& table = lut(blondeHairParams());
  const HairGroomSettings groom{.width = 20 * kMetresPerPixel};
  const HairView view{orthographicView(kColourExtent, kMetresPerPixel), kColourExtent};
  const auto draw = [&](glm::vec3 colour, std::span<const DirectionalLight> lights) {
    looks = {HairStrandLook{.colour = colour}};
    const glm::vec3 pixel = centre(render(table, wideStrand(), vk::SampleCountFlagBits::e1, view, lights,
                                          glm::vec3(0.05f), groom));
    looks.clear();
    return pixel;
  };
  // Lit on the R lobe's peak, θi = 2α_R for this strand's θr = 0 (as in hair_pass_test.cpp's
  // shading test; tangent +y, eye +z), 20° off the eye in azimuth, plus the ambient term.
  const double thetaI = 2.0 * blondeHairParams().r.shift;
  const double phi = 20.0 * 3.14159265358979 / 180.0;
  const glm::vec3 toLight(float(std::sin(phi) * std::cos(thetaI)), float(std::sin(thetaI)),
                          float(std::cos(phi) * std::cos(thetaI)));
  const std::array light{DirectionalLight{.direction = toLight, .intensity = 2.0f}};
  const glm::vec3 white = draw(glm::vec3(1.0f), light);
  const glm::vec3 black = draw(glm::vec3(0.0f), light);
  const glm::vec3 half = draw(glm::vec3(0.5f), light);
  const glm::vec3 red = draw({1.0f, 0.0f, 0.0f}, light);
  // Colour 0 leaves the surface reflection R alone: less than all of it, more than none.
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(black[c], 0.0f) << "channel " << c;
    EXPECT_LT(black[c], 0.9f * white[c]) << "channel " << c;
    // Linear in the colour: halfway between (16-bit target: 2^-10 relative, twice).
    EXPECT_NEAR(half[c], 0.5f * (white[c] + black[c]), 2e-3f * white[c]) << "channel " << c;
  }
  // A red strand: its red channel is the white strand's, bit for bit (× 1); green and blue only R.
  EXPECT_EQ(red.r, white.r);
  EXPECT_EQ(red.g, black.g);
  EXPECT_EQ(red.b, black.b);
  EXPECT_GT(red.r, red.g);
  // Ambient alone: all of it crossed fibres, so the colour takes it whole.
  const glm::vec3 ambientRed = draw({1.0f, 0.0f, 0.0f}, {});
  EXPECT_GT(ambientRed.r, 0.0f);
  EXPECT_EQ(ambientRed.g, 0.0f);
  EXPECT_EQ(ambientRed.b, 0.0f);
  std::printf("strand colour: white (%.4f %.4f %.4f) black (%.4f %.4f %.4f) red (%.4f %.4f %.4f)\n", white.r, white.g,
              white.b, black.r, black.g, black.b, red.r, red.g, red.b);
}

TEST_F(HairPassTest, StrandLooksAreCheckedAndMustCoverEveryStrand) {
  EXPECT_TRUE(validateStrandLooks({}, 3).has_value()) << "none: every strand plain";
  std::vector<HairStrandLook> looks(3);
  EXPECT_TRUE(validateStrandLooks(looks, 3).has_value());
  EXPECT_FALSE(validateStrandLooks(looks, 4).has_value()) << "one per strand";
  looks[1].widthScale = 0.0f;
  const auto zero = validateStrandLooks(looks, 3);
  ASSERT_FALSE(zero.has_value());
  EXPECT_NE(zero.error().message.find("strand look 1"), std::string::npos) << zero.error().message;
  looks[1] = {.opacityScale = 1.5f};
  EXPECT_FALSE(validateStrandLooks(looks, 3).has_value());
  looks[1] = {.colour = {0.0f, -0.1f, 0.0f}};
  EXPECT_FALSE(validateStrandLooks(looks, 3).has_value());

  // A pass refuses a buffer too small for its strands.
  const StrandData data = parallelStrands();
  const auto usage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer;
  const Buffer positions = Buffer::withData(device(), std::as_bytes(std::span(data.positions)), usage);
  auto pass = HairPass::create(device(), {});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  ASSERT_TRUE((*pass)
                  ->setStrands({.positions = *positions.buffer(),
                                .tangents = *positions.buffer(),
                                .radiance = *positions.buffer(),
                                .strandCount = data.strandCount(),
                                .verticesPerStrand = data.verticesPerStrand})
                  .has_value());
  const Buffer few = uploadStrandLooks(device(), std::vector<HairStrandLook>(2), 2);
  EXPECT_FALSE((*pass)->setStrandLooks(few).has_value());
  const Buffer enough = uploadStrandLooks(device(), {}, data.strandCount());
  EXPECT_TRUE((*pass)->setStrandLooks(enough).has_value());
}

}  // namespace
}  // namespace mane::render
