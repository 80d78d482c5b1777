// The hair ribbon pass (render/passes/hair_pass.hpp), shaded by the hair lighting pass
// (render/passes/hair_lighting_pass.hpp), against references independent of them:
//  - coverage: parallel straight strands of known world width seen head-on by an orthographic
//    camera cover their analytic projected area, width × length in pixels; strands narrower
//    than a pixel still cover their own area (analytic coverage at 1×, coverage-scaled alpha at
//    4× MSAA); at 1× each pixel holds its share of the strand, against a brute-force count;
//  - shading: the colour of a wide, opaque strand under one directional light equals the CPU
//    Marschner model (render/luts/marschner.hpp, double precision) for the pixel's tangent,
//    light and view directions times the light's irradiance, plus the ambient term;
//  - absorption: back-lit, blonde fibres transmit far more than dark ones, in the ratio the CPU
//    model predicts.
// Every test runs with the validation layers on; any message fails it (VulkanTest).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/hair_order.hpp"
#include "render/luts/marschner.hpp"
#include "render/luts/marschner_lut.hpp"
#include "render/passes/hair_lighting_pass.hpp"
#include "render/passes/hair_pass.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/render_target.hpp"
#include "tests/render/hair_pass_fixture.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

using namespace hair_fixture;

/// A hair pass over `data` drawn in fixed colours, one per vertex, with the buffers it reads.
struct FixedColourHair {
  Buffer positions;
  Buffer tangents;
  Buffer colours;
  std::unique_ptr<HairPass> pass;
};

FixedColourHair fixedColourHair(const Device& device, const StrandData& data, std::span<const glm::vec4> radiance) {
  const auto usage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer;
  FixedColourHair hair{
      .positions = Buffer::withData(device, std::as_bytes(std::span(data.positions)), usage),
      .tangents = Buffer::withData(device, std::as_bytes(std::span(data.tangents)), usage),
      .colours = Buffer::withData(device, std::as_bytes(radiance), usage | vk::BufferUsageFlagBits::eVertexBuffer)};
  auto pass = HairPass::create(device, {});
  if (!pass) throw std::runtime_error(pass.error().message);
  hair.pass = std::move(*pass);
  const auto set = hair.pass->setStrands({.positions = *hair.positions.buffer(),
                                          .tangents = *hair.tangents.buffer(),
                                          .radiance = *hair.colours.buffer(),
                                          .strandCount = data.strandCount(),
                                          .verticesPerStrand = data.verticesPerStrand});
  if (!set) throw std::runtime_error(set.error().message);
  return hair;
}

// ---------------------------------------------------------------------------------------------
// Coverage


Coverage renderParallelStrands(HairPassTest& test, vk::SampleCountFlagBits samples, float widthPixels) {
  const MarschnerLut& table = test.lut(blondeHairParams());
  const HairGroomSettings groom{.width = widthPixels * kMetresPerPixel, .opacity = 1.0f, .minimumPixelWidth = 1.0f};
  const std::array lights{DirectionalLight{.direction = {0, 0, 1}}};
  return measureCoverage(test.render(table, parallelStrands(), samples,
                                     {orthographicView(kCoverageExtent, kMetresPerPixel), kCoverageExtent}, lights,
                                     glm::vec3(0.1f), groom));
}

// Tolerance 1 %: counting is exact by construction (see parallelStrands) up to float rounding of
// edges that fall within ~1e-5 pixel of a centre (none do) and the 16-bit alpha (2^-11 relative).
void expectCoverage(HairPassTest& test, vk::SampleCountFlagBits samples) {
  const float width = 3.3f;
  const Coverage wide = renderParallelStrands(test, samples, width);
  EXPECT_EQ(test.lastChoice.primitive, HairPrimitive::kRibbons);
  EXPECT_EQ(test.lastChoice.wideVertices, 9u * kStrands) << "every vertex is wider than the minimum";
  const double area = kStrands * width * kLengthPixels;
  EXPECT_NEAR(wide.sum, area, 0.01 * area) << "3.3-pixel strands";
  std::printf("coverage %dx: 3.3 px strands %.2f px² vs analytic %.2f (%.3f %%)\n", int(samples), wide.sum, area,
              100.0 * (wide.sum - area) / area);
}

TEST_F(HairPassTest, WideStrandsCoverTheirProjectedAreaWithoutMsaa) {
  expectCoverage(*this, vk::SampleCountFlagBits::e1);
}

TEST_F(HairPassTest, WideStrandsCoverTheirProjectedAreaWith4xMsaa) {
  expectCoverage(*this, vk::SampleCountFlagBits::e4);
}

// A 0.3-pixel strand is drawn 1 pixel wide (the minimum) with alpha 0.3: it covers 0.3 pixel
// per row, never 0 and never a whole pixel.
void expectSubPixelCoverage(HairPassTest& test, vk::SampleCountFlagBits samples) {
  const float width = 0.3f;
  const Coverage thin = renderParallelStrands(test, samples, width);
  EXPECT_EQ(test.lastChoice.primitive, HairPrimitive::kLines);
  EXPECT_EQ(test.lastChoice.wideVertices, 0u);
  const double area = kStrands * width * kLengthPixels;
  EXPECT_NEAR(thin.sum, area, 0.01 * area) << "0.3-pixel strands";
  EXPECT_LE(thin.largest, width * 1.01f) << "a sub-pixel strand must not fill a pixel";
  EXPECT_GE(thin.lit, std::size_t(kStrands * kLengthPixels)) << "every row of every strand shows";
  std::printf("coverage %dx: 0.3 px strands %.2f px² vs analytic %.2f (%.3f %%), %zu pixels lit\n", int(samples),
              thin.sum, area, 100.0 * (thin.sum - area) / area, thin.lit);
}

TEST_F(HairPassTest, SubPixelStrandsCoverTheirAreaWithoutMsaa) {
  expectSubPixelCoverage(*this, vk::SampleCountFlagBits::e1);
}

TEST_F(HairPassTest, SubPixelStrandsCoverTheirAreaWith4xMsaa) {
  expectSubPixelCoverage(*this, vk::SampleCountFlagBits::e4);
}

// Hidden strands: the parallel strands (centres at pixel x 4.05 + 12.1·i) behind an opaque depth
// of 0 over the left half of the view's 8-pixel tiles, 1 (nothing) over the right half. The five
// strands whose pixels all lie left of x = 60 are neither drawn nor shaded; the other five are
// drawn exactly as without any occlusion, pixel for pixel.
void expectHiddenLeftHalf(HairPassTest& test, vk::SampleCountFlagBits samples, float widthPixels) {
  const MarschnerLut& table = test.lut(blondeHairParams());
  const HairGroomSettings groom{.width = widthPixels * kMetresPerPixel, .opacity = 1.0f, .minimumPixelWidth = 1.0f};
  const std::array lights{DirectionalLight{.direction = {0, 0, 1}}};
  const HairView view{orthographicView(kCoverageExtent, kMetresPerPixel), kCoverageExtent};
  const Pixels everything = test.render(table, parallelStrands(), samples, view, lights, glm::vec3(0.1f), groom);
  EXPECT_EQ(test.lastChoice.hiddenVertices, 0u);

  const HairOcclusionTiles grid{.tiles = {kCoverageExtent.width / 8, kCoverageExtent.height / 8}, .tileSize = 8};
  std::vector<float> depths(std::size_t(grid.tiles.x) * grid.tiles.y);
  for (std::size_t i = 0; i < depths.size(); ++i) depths[i] = i % grid.tiles.x < grid.tiles.x / 2 ? 0.0f : 1.0f;
  test.occlusion = std::pair(depths, grid);
  const Pixels hidden = test.render(table, parallelStrands(), samples, view, lights, glm::vec3(0.1f), groom);
  test.occlusion.reset();
  EXPECT_EQ(test.lastChoice.hiddenVertices, 5u * 9u) << "the five left strands' vertices";
  double leftBefore = 0.0, leftAfter = 0.0;
  std::size_t rightDiffering = 0;
  for (std::size_t i = 0; i < hidden.size(); ++i) {
    if (i % kCoverageExtent.width < 60) {
      leftBefore += everything[i].a;
      leftAfter += hidden[i].a;
    } else if (hidden[i] != everything[i]) {
      ++rightDiffering;
    }
  }
  EXPECT_GT(leftBefore, 0.0);
  EXPECT_EQ(leftAfter, 0.0) << "a hidden strand was drawn";
  EXPECT_EQ(rightDiffering, 0u) << "a visible strand was drawn differently";
}

// Segments off the screen: the parallel strands (roots at y = −49.75 pixels, tips at +50.25,
// vertices 12.5 pixels apart) seen through a band 40 pixels high from y = 30 down to −10, so that
// three segments at the root end lie wholly below it and one at the tip wholly above. The band is
// compared with the same rows of a view 160 pixels high that holds the whole strands (the same
// pixel grid, 60 rows more on either side), where nothing is off the screen: the same pixels,
// with 4 vertices of each strand left out (three at the root, one at the tip) instead of none.
void expectOffScreenLeftOut(HairPassTest& test, vk::SampleCountFlagBits samples, float widthPixels) {
  const MarschnerLut& table = test.lut(blondeHairParams());
  const HairGroomSettings groom{.width = widthPixels * kMetresPerPixel, .opacity = 1.0f, .minimumPixelWidth = 1.0f};
  const std::array lights{DirectionalLight{.direction = {0, 0, 1}}};
  // Rows 0 .. rows − 1 from world y = top downwards, a pixel of kMetresPerPixel, centred in x.
  const auto band = [&](float topPixels, std::uint32_t rows) {
    const vk::Extent2D extent{kCoverageExtent.width, rows};
    const float halfWidth = 0.5f * kMetresPerPixel * float(extent.width);
    const float top = topPixels * kMetresPerPixel;
    glm::mat4 projection =
        glm::orthoRH_ZO(-halfWidth, halfWidth, top - float(rows) * kMetresPerPixel, top, 0.01f, 3.0f);
    projection[1][1] = -projection[1][1];
    return HairView{projection * glm::lookAtRH(glm::vec3(0, 0, 1), glm::vec3(0), glm::vec3(0, 1, 0)), extent};
  };
  const float bandTop = 30.0f;
  const Pixels whole =
      test.render(table, parallelStrands(), samples, band(bandTop + 60.0f, 160), lights, glm::vec3(0.1f), groom);
  EXPECT_EQ(test.lastChoice.hiddenVertices, 0u);
  const Pixels cut = test.render(table, parallelStrands(), samples, band(bandTop, 40), lights, glm::vec3(0.1f), groom);
  EXPECT_EQ(test.lastChoice.hiddenVertices, 4u * kStrands) << "three at the root, one at the tip, of every strand";
  // The two views' projections round differently; with one sample, the coverage each pixel
  // computes from its distance to the strand shows it in the last bits of the half floats.
  const float tolerance = samples == vk::SampleCountFlagBits::e1 ? 1e-3f : 0.0f;
  std::size_t differing = 0;
  double drawn = 0.0;
  float largest = 0.0f;
  for (std::size_t i = 0; i < cut.size(); ++i) {
    const glm::vec4 difference = glm::abs(cut[i] - whole[i + 60 * kCoverageExtent.width]);
    const float channel = std::max(std::max(difference.r, difference.g), std::max(difference.b, difference.a));
    largest = std::max(largest, channel);
    differing += channel > tolerance ? 1 : 0;
    drawn += cut[i].a;
  }
  EXPECT_EQ(differing, 0u) << "pixels of the band differ from the same rows of the whole view, by up to " << largest;
  EXPECT_GT(drawn, 0.0);
}

TEST_F(HairPassTest, SegmentsOffTheScreenAreLeftOutAndTheRestDrawnAsInALargerView) {
  expectOffScreenLeftOut(*this, vk::SampleCountFlagBits::e1, 3.3f);  // ribbons
  EXPECT_EQ(lastChoice.primitive, HairPrimitive::kRibbons);
  expectOffScreenLeftOut(*this, vk::SampleCountFlagBits::e4, 0.3f);  // lines
  EXPECT_EQ(lastChoice.primitive, HairPrimitive::kLines);
}

TEST_F(HairPassTest, StrandsBehindTheOpaqueDepthAreNeitherDrawnNorShaded) {
  expectHiddenLeftHalf(*this, vk::SampleCountFlagBits::e1, 3.3f);  // ribbons
  EXPECT_EQ(lastChoice.primitive, HairPrimitive::kRibbons);
  expectHiddenLeftHalf(*this, vk::SampleCountFlagBits::e4, 0.3f);  // lines
  EXPECT_EQ(lastChoice.primitive, HairPrimitive::kLines);
}

// ---------------------------------------------------------------------------------------------
// Lines standing in for ribbons

// Lines must cover a strand's area at any slope: rectangular lines do, where a parallelogram
// (non-strict) line 1 pixel wide along its minor axis covers cos 45° ≈ 0.71 of it at 45°.
// Twelve parallel 0.3-pixel strands 160 pixels long at `degrees` from vertical, 12 pixels apart,
// their centres at sub-pixel offsets spread over a pixel, drawn as lines of `lineWidth` pixels.
void expectSlopedCoverage(HairPassTest& test, vk::SampleCountFlagBits samples, float degrees, float lineWidth) {
  constexpr vk::Extent2D kExtent{256, 256};
  constexpr int kSloped = 12;
  constexpr float kLength = 160.0f, kWidth = 0.3f;
  const float angle = glm::radians(degrees);
  const glm::vec2 along(std::sin(angle), std::cos(angle)), across(std::cos(angle), -std::sin(angle));
  StrandData data;
  for (int i = 0; i < kSloped; ++i) {
    const glm::vec2 centre = across * (12.0f * (float(i) - 5.5f) + (float(i) + 0.5f) / float(kSloped));
    const glm::vec2 root = centre - 0.5f * kLength * along, tip = centre + 0.5f * kLength * along;
    addStraightStrand(data, glm::vec3(root * kMetresPerPixel, 0.0f), glm::vec3(tip * kMetresPerPixel, 0.0f), 9);
  }
  const HairGroomSettings groom{.width = kWidth * kMetresPerPixel, .opacity = 1.0f, .minimumPixelWidth = lineWidth};
  const std::array lights{DirectionalLight{.direction = {0, 0, 1}}};
  const Coverage coverage = measureCoverage(test.render(test.lut(blondeHairParams()), data, samples,
                                                        {orthographicView(kExtent, kMetresPerPixel), kExtent}, lights,
                                                        glm::vec3(0.1f), groom));
  EXPECT_EQ(test.lastChoice.primitive, HairPrimitive::kLines);
  const double area = kSloped * kWidth * kLength;
  // 1 %: each strand's ends cross pixel centres at its own offsets, a fraction of a pixel of
  // length (a few tenths of a percent) per strand; alpha is half-float.
  EXPECT_NEAR(coverage.sum, area, 0.01 * area) << degrees << "° from vertical";
  // With MSAA the line's alpha is the strand's width over the line's; with one sample a pixel
  // takes its share of the strand, at most the length of the strand across it, 1 / cos of the
  // slope from the nearer axis, times the width.
  const float largest = samples == vk::SampleCountFlagBits::e1
                            ? kWidth / std::max(std::abs(std::cos(angle)), std::abs(std::sin(angle)))
                            : kWidth / lineWidth;
  EXPECT_LE(coverage.largest, largest * 1.01f) << "a sub-pixel strand must not fill a pixel";
  std::printf("sloped %dx, %.0f°, %.0f-pixel lines: %.2f px² vs analytic %.2f (%.3f %%)\n", int(samples), degrees,
              lineWidth, coverage.sum, area, 100.0 * (coverage.sum - area) / area);
}

TEST_F(HairPassTest, LinesCoverTheAreaOfSlopedStrands) {
  for (const vk::SampleCountFlagBits samples : {vk::SampleCountFlagBits::e1, vk::SampleCountFlagBits::e4})
    for (const float degrees : {0.0f, 30.0f, 45.0f, 60.0f, 90.0f}) expectSlopedCoverage(*this, samples, degrees, 1.0f);
}

// With one sample per pixel each pixel must hold the share of its square that the strand covers:
// against a brute-force count of 64 × 64 points per pixel inside the strand's band, for strands
// drawn as lines (0.3 and 0.9 pixels) and as ribbons (2.5 pixels) at slopes from 0° to 70°. Only
// pixels at least 3 pixels from the strands' ends count, where the band is straight and
// infinite as far as the pixel can tell.
TEST_F(HairPassTest, OneSamplePerPixelTakesEachPixelsShareOfTheStrand) {
  constexpr vk::Extent2D kExtent{160, 160};
  constexpr float kLength = 120.0f;
  constexpr int kPerSide = 64;
  for (const float width : {0.3f, 0.9f, 2.5f})
    for (const float degrees : {0.0f, 20.0f, 45.0f, 70.0f}) {
      const float angle = glm::radians(degrees);
      const glm::vec2 along(std::sin(angle), std::cos(angle)), across(std::cos(angle), -std::sin(angle));
      // Three strands, their centres at sub-pixel offsets, 30 pixels apart.
      std::vector<glm::vec2> centres;
      StrandData data;
      for (int i = 0; i < 3; ++i) {
        const glm::vec2 centre = across * (30.0f * float(i - 1) + 0.17f + 0.31f * float(i));
        centres.push_back(centre);
        addStraightStrand(data, glm::vec3((centre - 0.5f * kLength * along) * kMetresPerPixel, 0.0f),
                          glm::vec3((centre + 0.5f * kLength * along) * kMetresPerPixel, 0.0f), 9);
      }
      const HairGroomSettings groom{.width = width * kMetresPerPixel, .opacity = 1.0f, .minimumPixelWidth = 1.0f};
      const std::array lights{DirectionalLight{.direction = {0, 0, 1}}};
      const Pixels pixels =
          render(lut(blondeHairParams()), data, vk::SampleCountFlagBits::e1,
                 {orthographicView(kExtent, kMetresPerPixel), kExtent}, lights, glm::vec3(0.1f), groom);
      EXPECT_EQ(lastChoice.primitive,
                width < 1.0f && device().wideLines() ? HairPrimitive::kLines : HairPrimitive::kRibbons);
      double largestError = 0.0, errorSum = 0.0;
      std::size_t counted = 0;
      for (std::uint32_t y = 0; y < kExtent.height; ++y)
        for (std::uint32_t x = 0; x < kExtent.width; ++x) {
          // The pixel's centre in the view's pixel frame: x right, y up, the origin at the middle.
          const glm::vec2 centre(float(x) + 0.5f - 0.5f * float(kExtent.width),
                                 0.5f * float(kExtent.height) - float(y) - 0.5f);
          for (const glm::vec2& strand : centres) {
            const glm::vec2 offset = centre - strand;
            if (std::abs(glm::dot(offset, across)) > 0.5f * width + 2.0f) continue;
            if (std::abs(glm::dot(offset, along)) > 0.5f * kLength - 3.0f) continue;
            int inside = 0;
            for (int j = 0; j < kPerSide; ++j)
              for (int i = 0; i < kPerSide; ++i) {
                const glm::vec2 point =
                    offset + glm::vec2((float(i) + 0.5f) / kPerSide - 0.5f, (float(j) + 0.5f) / kPerSide - 0.5f);
                inside += std::abs(glm::dot(point, across)) <= 0.5f * width ? 1 : 0;
              }
            const double error =
                std::abs(double(pixels[y * kExtent.width + x].a) - double(inside) / (kPerSide * kPerSide));
            largestError = std::max(largestError, error);
            errorSum += error;
            ++counted;
          }
        }
      ASSERT_GT(counted, 300u);
      // 64 points a side place an edge within 1/64 of a pixel; alpha is half-float.
      EXPECT_LE(largestError, 0.02) << width << "-pixel strands at " << degrees << "°";
      EXPECT_LE(errorSum / double(counted), 0.003) << width << "-pixel strands at " << degrees << "°";
      std::printf("%.1f px at %2.0f°: %zu pixels, coverage error mean %.4f, largest %.4f\n", width, degrees, counted,
                  errorSum / double(counted), largestError);
    }
}

// ---------------------------------------------------------------------------------------------
// Level of detail

// 512 strands a quarter pixel wide across the whole view, at random places and slopes within
// 20° of vertical (about four to a pixel's width, so that they overlap as a groom's do and cover
// about half of each pixel), drawn whole and at a quarter of its strands
// (render/strand_lod.hpp): the coverage, Σ alpha, over the view must stay within 5 % of the
// whole groom's, and over each band 32 pixels wide within 15 % (a quarter of a band's 128
// strands, at random places, is itself uneven by about that much). Without the width
// compensation a quarter of the strands would cover about a quarter.
TEST_F(HairPassTest, AQuarterOfTheStrandsWidenedCoverWhatTheWholeGroomCovers) {
  constexpr vk::Extent2D kExtent{128, 128};
  constexpr int kPatchStrands = 512;
  constexpr float kLength = 200.0f;  // past the view's top and bottom: no ends in view
  StrandData data;
  std::uint32_t state = 12345u;
  const auto uniform = [&state] {  // a fixed linear congruential sequence in [0, 1)
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  for (int i = 0; i < kPatchStrands; ++i) {
    const glm::vec2 centre(128.0f * uniform() - 64.0f, 0.0f);
    const float angle = glm::radians(40.0f * uniform() - 20.0f);
    const glm::vec2 along(std::sin(angle), std::cos(angle));
    addStraightStrand(data, glm::vec3((centre - 0.5f * kLength * along) * kMetresPerPixel, 0.0f),
                      glm::vec3((centre + 0.5f * kLength * along) * kMetresPerPixel, 0.0f), 9);
  }
  const HairGroomSettings groom{.width = 0.25f * kMetresPerPixel, .opacity = 0.8f, .minimumPixelWidth = 1.0f};
  const std::array lights{DirectionalLight{.direction = {0, 0, 1}}};
  const HairView view{orthographicView(kExtent, kMetresPerPixel), kExtent};
  const MarschnerLut& table = lut(blondeHairParams());
  for (const vk::SampleCountFlagBits samples : {vk::SampleCountFlagBits::e1, vk::SampleCountFlagBits::e4}) {
    keptShare = 1.0f;
    const Pixels whole = render(table, data, samples, view, lights, glm::vec3(0.1f), groom);
    EXPECT_EQ(lastChoice.keptShare, 1.0f);
    const std::uint32_t hiddenInWhole = lastChoice.hiddenVertices;
    keptShare = 0.25f;
    const Pixels quarter = render(table, data, samples, view, lights, glm::vec3(0.1f), groom);
    EXPECT_EQ(lastChoice.keptShare, 0.25f);
    // Three strands of every four left out (the ranks of 512 strands), with the vertices off the view.
    EXPECT_GE(lastChoice.hiddenVertices, kPatchStrands / 4 * 3 * data.verticesPerStrand);
    EXPECT_LE(lastChoice.hiddenVertices, kPatchStrands / 4 * 3 * data.verticesPerStrand + hiddenInWhole);
    const double wholeSum = measureCoverage(whole).sum, quarterSum = measureCoverage(quarter).sum;
    EXPECT_NEAR(quarterSum, wholeSum, 0.05 * wholeSum) << int(samples) << "x: the view's coverage";
    double worstBand = 0.0;
    for (std::uint32_t band = 0; band < kExtent.width; band += 32) {
      double a = 0.0, b = 0.0;
      for (std::uint32_t y = 0; y < kExtent.height; ++y)
        for (std::uint32_t x = band; x < band + 32; ++x) {
          a += whole[y * kExtent.width + x].a;
          b += quarter[y * kExtent.width + x].a;
        }
      worstBand = std::max(worstBand, std::abs(b - a) / a);
    }
    EXPECT_LE(worstBand, 0.15) << int(samples) << "x: a band's coverage";
    std::printf(
        "%dx: a quarter of the strands covers %.1f px² against the whole groom's %.1f (%+.2f %%); worst "
        "band %.2f %%\n",
        int(samples), quarterSum, wholeSum, 100.0 * (quarterSum - wholeSum) / wholeSum, 100.0 * worstBand);
  }
  keptShare = 1.0f;
}

TEST_F(HairPassTest, WideLinesCoverTheAreaOfSlopedStrands) {
  if (!device().wideLines()) GTEST_SKIP() << "the device has no wide lines: ribbons are drawn instead";
  for (const float degrees : {0.0f, 45.0f}) expectSlopedCoverage(*this, vk::SampleCountFlagBits::e1, degrees, 2.0f);
}

// The choice, against a CPU reference in double precision: tapered strands receding from a
// perspective camera, so that their width on screen runs from about 2.3 pixels at the nearest
// roots to a tenth of a pixel at the farthest tips, as the groom's width varies. Per vertex the
// width in pixels is twice the half width times the pixels per metre of projecting the root
// half-width offset along s = t × ωe (shaders/hair_uniforms.glsl); a vertex is wide above the
// minimum pixel width, and lines lose what it exceeds that by. The GPU must count the same wide
// vertices, report the same uncovered share, and draw lines exactly when that share is ≤ 1 %.
struct LineLoss {
  std::uint32_t wideVertices = 0;
  double uncovered = 0.0;      ///< Σ max(w − min, 0) / Σ w
  double closestRatio = 1e30;  ///< min |w / min − 1|: how near a vertex comes to the threshold
};

LineLoss lineLossOnCpu(const StrandData& data, const HairView& view, const HairGroomSettings& groom) {
  const glm::dmat4 viewProjection(view.viewProjection);
  const glm::dvec4 eye(hairEye(view.viewProjection));
  const glm::dvec2 halfViewport(0.5 * view.extent.width, 0.5 * view.extent.height);
  const double rootHalfWidth = 0.5 * double(groom.width);
  LineLoss loss;
  double width = 0.0, lost = 0.0;
  for (std::size_t v = 0; v < data.positions.size(); ++v) {
    const glm::dvec3 point(data.positions[v]);
    const glm::dvec3 toEye = eye.w != 0.0 ? glm::normalize(glm::dvec3(eye) - point) : glm::dvec3(eye);
    const glm::dvec3 side = glm::normalize(glm::cross(glm::dvec3(data.tangents[v]), toEye));
    const glm::dvec4 centre = viewProjection * glm::dvec4(point, 1.0);
    const glm::dvec4 edge = viewProjection * glm::dvec4(point + side * rootHalfWidth, 1.0);
    const double pixelsPerMetre =
        glm::length((glm::dvec2(edge) / edge.w - glm::dvec2(centre) / centre.w) * halfViewport) / rootHalfWidth;
    const double halfWidth = rootHalfWidth * glm::mix(1.0, double(groom.tipWidthScale), double(data.positions[v].w));
    const double widthInLines = 2.0 * halfWidth * pixelsPerMetre / double(groom.minimumPixelWidth);
    width += widthInLines;
    if (widthInLines > 1.0) {
      ++loss.wideVertices;
      lost += widthInLines - 1.0;
    }
    loss.closestRatio = std::min(loss.closestRatio, std::abs(widthInLines - 1.0));
  }
  loss.uncovered = lost / width;
  return loss;
}

TEST_F(HairPassTest, DrawsLinesWhenTheyLeaveAtMostOnePercentOfTheWidthUncovered) {
  StrandData data;
  for (int i = 0; i < 16; ++i) {
    const float x = -0.06f + 0.008f * float(i);
    addStraightStrand(data, {x, 0.02f * float(i % 3), 0.0f}, {x + 0.01f, -0.05f, -0.3f}, 12);
  }
  const vk::Extent2D extent{256, 256};
  const Camera camera{.position = {0.0f, 0.0f, 0.3f}, .target = {0.0f, 0.0f, 0.0f}, .verticalFovRadians = 0.7f};
  const HairView view{camera.projection(1.0f) * camera.view(), extent};
  const std::vector<glm::vec4> radiance(data.positions.size(), glm::vec4(1.0f));
  const FixedColourHair hair = fixedColourHair(device(), data, radiance);
  const std::unique_ptr<HairPass>& pass = hair.pass;
  bool narrow = false, slightlyWide = false, wide = false;
  for (const float width : {0.5e-3f, 0.8e-3f, 0.9e-3f, 1.2e-3f, 2.0e-3f}) {
    const HairGroomSettings groom{.width = width, .tipWidthScale = 0.3f};
    const LineLoss expected = lineLossOnCpu(data, view, groom);
    ASSERT_GT(expected.closestRatio, 1e-4) << "no vertex may sit on the threshold, where float and double differ";
    ASSERT_GT(std::abs(expected.uncovered - 0.01), 1e-4) << "nor the groom on the 1 % threshold";
    ASSERT_TRUE(pass->update(view, groom).has_value());
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { pass->record(commands); });
    const HairPrimitiveChoice choice = pass->lastChoice();
    EXPECT_EQ(choice.wideVertices, expected.wideVertices) << "width " << width;
    // The GPU rounds each vertex's width to 1/4096 of the minimum: 1e-5 of the sum at most.
    EXPECT_NEAR(choice.uncoveredByLines, expected.uncovered, 1e-5) << "width " << width;
    EXPECT_EQ(choice.primitive, expected.uncovered <= 0.01 ? HairPrimitive::kLines : HairPrimitive::kRibbons)
        << "width " << width;
    narrow = narrow || expected.wideVertices == 0;
    slightlyWide = slightlyWide || (expected.wideVertices > 0 && expected.uncovered <= 0.01);
    wide = wide || expected.uncovered > 0.01;
    std::printf(
        "width %.1f mm: %u of %zu vertices wide (CPU %u), %.5f of the width uncovered by lines (CPU %.5f): %s\n",
        width * 1e3, choice.wideVertices, data.positions.size(), expected.wideVertices, choice.uncoveredByLines,
        expected.uncovered, choice.primitive == HairPrimitive::kLines ? "lines" : "ribbons");
  }
  EXPECT_TRUE(narrow && slightlyWide && wide) << "the widths must give every case";
}

// Every vertex of 1,280 is capped at 1,024 line widths of 4,096 units: the width sum, 1,280 × 2²²,
// passes 2³² and must carry into its high word. Lines would leave 1,023 of each 1,024 uncovered.
TEST_F(HairPassTest, TheWidthSumsCarryPast32Bits) {
  StrandData data;
  for (int i = 0; i < 64; ++i)
    addStraightStrand(data, {0.001f * float(i), -0.05f, 0.0f}, {0.001f * float(i), 0.05f, 0.0f}, 20);
  const std::vector<glm::vec4> radiance(data.positions.size(), glm::vec4(1.0f));
  const FixedColourHair hair = fixedColourHair(device(), data, radiance);
  const HairView view{orthographicView(kCoverageExtent, kMetresPerPixel), kCoverageExtent};
  ASSERT_TRUE(hair.pass->update(view, {.width = 2.0f}).has_value()) << "2,000 pixels wide";
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { hair.pass->record(commands); });
  const HairPrimitiveChoice choice = hair.pass->lastChoice();
  EXPECT_EQ(choice.wideVertices, 1280u);
  EXPECT_DOUBLE_EQ(choice.uncoveredByLines, 1023.0 / 1024.0);
  EXPECT_EQ(choice.primitive, HairPrimitive::kRibbons);
}

// ---------------------------------------------------------------------------------------------
// Shading

constexpr vk::Extent2D kShadingExtent{64, 64};

// One opaque strand 20 pixels wide through the image centre, tilted towards the camera so that
// θr ≠ 0, seen by an orthographic camera along −z (ωr = +z at every pixel).
const glm::vec3 kTiltedTangent = glm::normalize(glm::vec3(0.0f, 1.0f, 0.45f));

StrandData tiltedStrand() {
  StrandData data;
  addStraightStrand(data, -0.03f * kTiltedTangent, 0.03f * kTiltedTangent, 16);
  return data;
}

// The unit vector at longitudinal angle θi (radians, from the normal plane of kTiltedTangent) and
// azimuth φ (degrees, from the eye's projection +z on that plane).
glm::vec3 lightAt(double thetaI, double phiDegrees) {
  const glm::dvec3 t(kTiltedTangent);
  const glm::dvec3 u = glm::normalize(glm::dvec3(0, 0, 1) - t.z * t);
  const glm::dvec3 w = glm::cross(t, u);
  const double phi = phiDegrees * std::numbers::pi / 180.0;
  return glm::vec3(std::sin(thetaI) * t + std::cos(thetaI) * (std::cos(phi) * u + std::sin(phi) * w));
}

glm::dvec3 centreColour(const Pixels& pixels, vk::Extent2D extent, int dx = 0, int dy = 0) {
  const std::size_t i = std::size_t(extent.height / 2 + dy) * extent.width + extent.width / 2 + dx;
  return glm::dvec3(pixels[i]);
}

TEST_F(HairPassTest, ColourOnAStrandMatchesTheCpuMarschnerModel) {
  const HairShadingParams params = blondeHairParams();
  const MarschnerLut& table = lut(params);
  const glm::vec3 ambient(0.02f, 0.025f, 0.03f);
  const HairGroomSettings groom{.width = 20 * kMetresPerPixel, .opacity = 1.0f};
  const glm::dvec3 toEye(0.0, 0.0, 1.0);
  // Lights on the peaks of the three lobes for this strand's θr = asin(ωr·t) ≈ 24°: each lobe
  // peaks at θh = (θi + θr)/2 = α_p, so θi = 2α_p − θr; R at φ = 20°, TRT at φ = 10° (its
  // azimuthal peak lies near φ = 0 at this θr), TT from behind (φ = 165°).
  const double thetaR = std::asin(double(kTiltedTangent.z));
  const std::array lights{
      DirectionalLight{
          .direction = lightAt(2.0 * params.r.shift - thetaR, 20.0), .color = {1.0f, 0.9f, 0.8f}, .intensity = 2.0f},
      DirectionalLight{.direction = lightAt(2.0 * params.trt.shift - thetaR, 10.0), .intensity = 1.5f},
      DirectionalLight{.direction = lightAt(2.0 * params.tt.shift - thetaR, 165.0), .intensity = 1.0f}};
  const AzimuthalLobes albedo = azimuthalAlbedo(params, 1.0);
  const glm::dvec3 ambientAlbedo = albedo.tt + albedo.trt + glm::dvec3(albedo.r);
  for (const DirectionalLight& light : lights) {
    const Pixels pixels = render(table, tiltedStrand(), vk::SampleCountFlagBits::e1,
                                 {orthographicView(kShadingExtent, kMetresPerPixel), kShadingExtent},
                                 std::span(&light, 1), ambient, groom);
    // Reference: S from the CPU model (double) × perpendicular irradiance, plus ambient radiance
    // × the white-furnace albedo at θr = 0 (the pass's documented ambient term).
    const glm::dvec3 scattering =
        hairScattering(params, glm::dvec3(light.direction), toEye, glm::dvec3(kTiltedTangent));
    const glm::dvec3 expected =
        scattering * glm::dvec3(light.color * light.intensity) + glm::dvec3(ambient) * ambientAlbedo;
    // Pixels on the strand, away from its edges; all see the same directions.
    for (const auto& [dx, dy] : std::array{std::pair{0, 0}, std::pair{-5, 10}, std::pair{4, -12}}) {
      const glm::dvec3 colour = centreColour(pixels, kShadingExtent, dx, dy);
      for (int c = 0; c < 3; ++c) {
        // 2 %: the LUTs reproduce the model within 1 % (marschner_lut.hpp), the 16-bit target
        // rounds by 2^-11, lavapipe's asin/acos move a lookup by < 0.05 texel.
        EXPECT_NEAR(colour[c], expected[c], 0.02 * expected[c])
            << "light (" << light.direction.x << ", " << light.direction.y << ", " << light.direction.z << ") channel "
            << c << " pixel offset " << dx << "," << dy;
      }
      if (dx == 0)
        std::printf("shading: light (%.2f %.2f %.2f): GPU (%.5f %.5f %.5f) CPU (%.5f %.5f %.5f)\n", light.direction.x,
                    light.direction.y, light.direction.z, colour.r, colour.g, colour.b, expected.r, expected.g,
                    expected.b);
    }
  }
}

// Back-lit (the light behind the strand, facing the camera): TT carries the light through the
// fibre, and dark hair absorbs it (σa ≈ 27× blonde's). Through the FrameInput path with a
// perspective camera, ambient 0. The relation: blonde is brighter in every channel, by the ratio
// of the CPU model at the centre pixel's directions within 5 % (LUTs 1 % each, the view
// direction of the centre pixel vs the strand's centre, half floats).
TEST_F(HairPassTest, BlondeTransmitsMoreThanDarkWhenBackLit) {
  const HairShadingParams blonde = blondeHairParams();
  const HairShadingParams dark = darkHairParams();
  FrameInput frame{
      .camera = {.position = {0, 0, 0.3f}, .target = {0, 0, 0}},
      .lights = {DirectionalLight{.direction = glm::normalize(glm::vec3(0.1f, 0.2f, -1.0f)), .intensity = 3.0f}},
      .ambient = glm::vec3(0.0f)};
  const HairGroomSettings groom{.width = 0.03f};
  auto draw = [&](const HairShadingParams& params) {
    const float aspect = float(kShadingExtent.width) / float(kShadingExtent.height);
    return render(lut(params), tiltedStrand(), vk::SampleCountFlagBits::e1,
                  {frame.camera.projection(aspect) * frame.camera.view(), kShadingExtent}, frame.lights, frame.ambient,
                  groom);
  };
  const glm::dvec3 blondeColour = centreColour(draw(blonde), kShadingExtent);
  const glm::dvec3 darkColour = centreColour(draw(dark), kShadingExtent);
  const glm::dvec3 toLight(frame.lights[0].direction);
  const glm::dvec3 toEye(0.0, 0.0, 1.0);
  const glm::dvec3 tangent(kTiltedTangent);
  const glm::dvec3 expectedRatio =
      hairScattering(blonde, toLight, toEye, tangent) / hairScattering(dark, toLight, toEye, tangent);
  for (int c = 0; c < 3; ++c) {
    ASSERT_GT(darkColour[c], 0.0) << "channel " << c;
    const double ratio = blondeColour[c] / darkColour[c];
    EXPECT_GT(ratio, 2.0) << "channel " << c;
    EXPECT_NEAR(ratio, expectedRatio[c], 0.05 * expectedRatio[c]) << "channel " << c;
  }
  // Pheomelanin absorbs blue most: blonde transmission is warm.
  EXPECT_GT(blondeColour.r, blondeColour.b);
  std::printf("back-lit: blonde (%.4f %.4f %.4f) dark (%.5f %.5f %.5f), CPU ratio (%.2f %.2f %.2f)\n", blondeColour.r,
              blondeColour.g, blondeColour.b, darkColour.r, darkColour.g, darkColour.b, expectedRatio.r,
              expectedRatio.g, expectedRatio.b);
}

// ---------------------------------------------------------------------------------------------
// Compositing

// Two half-transparent strands on the same screen path, a red one 0.1 m in front of a blue one,
// stored front first. Drawn in buffer order the blue one lands on top, which is wrong; in the
// order StrandDrawOrder gives for the eye in front, the pixel is the "over" composite of the
// front strand over the back one: C = α·c_front + (1 − α)·α·c_back, alpha 1 − (1 − α)².
TEST_F(HairPassTest, StrandsSortedBackToFrontCompositeFrontOverBack) {
  StrandData data;
  addStraightStrand(data, {0.0f, -0.02f, 0.1f}, {0.0f, 0.02f, 0.1f}, 4);    // front
  addStraightStrand(data, {0.0f, -0.02f, -0.1f}, {0.0f, 0.02f, -0.1f}, 4);  // back
  std::vector<glm::vec4> radiance(4, glm::vec4(1, 0, 0, 1));
  radiance.resize(8, glm::vec4(0, 0, 1, 1));
  const FixedColourHair hair = fixedColourHair(device(), data, radiance);
  const std::unique_ptr<HairPass>& pass = hair.pass;
  const HairView view{orthographicView(kShadingExtent, kMetresPerPixel), kShadingExtent};
  constexpr float kAlpha = 0.5f;
  ASSERT_TRUE(pass->update(view, {.width = 20 * kMetresPerPixel, .opacity = kAlpha}).has_value());

  const auto centre = [&] {
    const RenderTarget target(device(), {.extent = kShadingExtent});
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      pass->record(commands);
      target.beginScene(commands, glm::vec4(0.0f));
      pass->draw(commands);
      commands.endRendering();
      transition(commands, target.hdr(), vk::ImageLayout::eColorAttachmentOptimal, vk::ImageLayout::eTransferSrcOptimal,
                 vk::PipelineStageFlagBits2::eColorAttachmentOutput, vk::AccessFlagBits2::eColorAttachmentWrite,
                 vk::PipelineStageFlagBits2::eTransfer, vk::AccessFlagBits2::eTransferRead);
    });
    const std::vector<std::byte> bytes = readBack(device(), target.hdr(), 8);
    std::array<std::uint16_t, 4> halves{};
    std::memcpy(
        halves.data(),
        bytes.data() + 8 * (std::size_t(kShadingExtent.height / 2) * kShadingExtent.width + kShadingExtent.width / 2),
        8);
    return glm::vec4(glm::unpackHalf1x16(halves[0]), glm::unpackHalf1x16(halves[1]), glm::unpackHalf1x16(halves[2]),
                     glm::unpackHalf1x16(halves[3]));
  };
  const glm::vec4 unsorted = centre();
  EXPECT_NEAR(unsorted.b, kAlpha, 1e-3) << "buffer order draws the back strand last, on top";

  StrandDrawOrder order(DenseStrandLayout{
      .guideCount = 2, .strands = {DenseStrand{.guides = {0, 0, 0}}, DenseStrand{.guides = {1, 0, 0}}}});
  const std::array middles{glm::vec3(0.0f, 0.0f, 0.1f), glm::vec3(0.0f, 0.0f, -0.1f)};
  const auto backToFront = order.backToFront(middles, hairEye(view.viewProjection));
  ASSERT_EQ(std::vector<std::uint32_t>(backToFront.begin(), backToFront.end()), (std::vector<std::uint32_t>{1, 0}));
  ASSERT_TRUE(pass->setDrawOrder(backToFront).has_value());
  const glm::vec4 sorted = centre();
  EXPECT_NEAR(sorted.r, kAlpha, 1e-3);
  EXPECT_NEAR(sorted.b, (1 - kAlpha) * kAlpha, 1e-3);
  EXPECT_NEAR(sorted.a, 1 - (1 - kAlpha) * (1 - kAlpha), 1e-3);
  EXPECT_NEAR(unsorted.a, sorted.a, 1e-3) << "coverage does not depend on the order";

  const std::array repeated{0u, 0u};
  EXPECT_FALSE(pass->setDrawOrder(repeated).has_value());
  EXPECT_FALSE(pass->setDrawOrder(std::span<const std::uint32_t>(repeated).first(1)).has_value());
}

// ---------------------------------------------------------------------------------------------
// Bad input

TEST_F(HairPassTest, RejectsBadStrandsAndGroomSettings) {
  auto pass = HairPass::create(device(), {});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  EXPECT_FALSE((*pass)->setStrands({}).has_value()) << "null buffers";
  const Buffer buffer(device(), 64, vk::BufferUsageFlagBits::eStorageBuffer, vk::MemoryPropertyFlagBits::eDeviceLocal);
  EXPECT_FALSE((*pass)
                   ->setStrands({.positions = *buffer.buffer(),
                                 .tangents = *buffer.buffer(),
                                 .radiance = *buffer.buffer(),
                                 .verticesPerStrand = 1})
                   .has_value());
  // Counts alone decide these two (nothing is read from the buffers): 2 vertices a strand.
  const auto tooMany = [&](std::uint32_t strands) {
    const auto set = (*pass)->setStrands({.positions = *buffer.buffer(),
                                          .tangents = *buffer.buffer(),
                                          .radiance = *buffer.buffer(),
                                          .strandCount = strands,
                                          .verticesPerStrand = 2});
    return set.has_value() ? std::string() : set.error().message;
  };
  EXPECT_NE(tooMany(1u << 29).find("2^32"), std::string::npos) << "8 indices a segment";
  // One vertex more than a texel buffer holds, where the indices still fit.
  const std::uint64_t texels = device().limits().maxTexelBufferElements;
  if (4 * texels + 8 <= std::numeric_limits<std::uint32_t>::max()) {
    EXPECT_NE(tooMany(std::uint32_t(texels / 2 + 1)).find("texel buffers"), std::string::npos);
  }
  const HairView view{orthographicView(kShadingExtent, kMetresPerPixel), kShadingExtent};
  EXPECT_FALSE((*pass)->update(view, {.width = 0.0f}).has_value());
  EXPECT_FALSE((*pass)->update(view, {.width = std::nanf("")}).has_value());
  EXPECT_FALSE((*pass)->update(view, {.opacity = 1.5f}).has_value());
  EXPECT_FALSE((*pass)->update(view, {.minimumPixelWidth = 0.0f}).has_value());
  EXPECT_FALSE((*pass)->update(view, {.lodPixelWidth = -1.0f}).has_value());
  EXPECT_FALSE((*pass)->update(view, {}, 0.01f).has_value()) << "fewer strands than the least share";
  EXPECT_FALSE((*pass)->update(view, {}, 1.5f).has_value());
  EXPECT_FALSE((*pass)->update(HairView{glm::mat4(0.0f), kShadingExtent}, {}).has_value());
  EXPECT_FALSE((*pass)->update(HairView{view.viewProjection, {0, 0}}, {}).has_value());
  EXPECT_TRUE((*pass)->update(view, {}).has_value());
}

}  // namespace
}  // namespace mane::render
