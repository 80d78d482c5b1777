// The CPU side of the fur from one photograph: Ukaji et al.'s shell thresholds
// (render/luts/fur_shells.hpp) against the paper's formulas evaluated independently here, and the
// fins' silhouette edges (MeshEdges in render/passes/fur_pass.hpp) against a sphere's analytic
// silhouette. No Vulkan device.

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "render/luts/fur_shells.hpp"
#include "render/passes/fur_pass.hpp"

namespace mane::render {
namespace {

// IEC 61966-2-1 decode, written out again so the test does not trust linearFromSrgb.
double srgbToLinear(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A photo of grey pixels: luminance = the linear grey (Rec. 709's weights sum to 1).
struct GreyPhoto {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::vector<int> codes;
  TextureData texture() const { return {width, height, rgba}; }
};

GreyPhoto greyPhoto(std::uint32_t width, const std::vector<int>& codes) {
  GreyPhoto photo{width, std::uint32_t(codes.size() / width), {}, codes};
  for (const int code : codes)
    photo.rgba.insert(photo.rgba.end(), {std::uint8_t(code), std::uint8_t(code), std::uint8_t(code), 255});
  return photo;
}

// Ukaji et al.: I(n) ≤ I < I(n−1) with I(n) = I_max·e^(−ln(I_max/I_min)·n/N), i.e.
// n = ceil(N·ln(I_max/I)/ln(I_max/I_min)), clamped to 1 … N.
int predictedLayer(double luminance, double iMin, double iMax, int layers) {
  const double n = std::ceil(layers * std::log(iMax / luminance) / std::log(iMax / iMin));
  return int(std::clamp(n, 1.0, double(layers)));
}

TEST(FurShells, LuminanceIsRec709OfLinearisedSrgb) {
  EXPECT_NEAR(photoLuminance(255, 0, 0), 0.2126, 1e-6);
  EXPECT_NEAR(photoLuminance(0, 255, 0), 0.7152, 1e-6);
  EXPECT_NEAR(photoLuminance(0, 0, 255), 0.0722, 1e-6);
  // sRGB 128 is linear 0.2158605 (IEC 61966-2-1).
  EXPECT_NEAR(photoLuminance(128, 128, 128), 0.2158605, 1e-6);
}

// The thresholds are eq. 4 exactly: I(0) = I_max, I(N) = I_min, a constant ratio between
// neighbours; the depth of I(n) by eq. 1 is the layer depth of eq. 3, and a = ln(I_max/I_min)/h_b.
TEST(FurShells, ThresholdsFollowTheExponentialDecay) {
  auto model = FurShellModel::create({.minimum = 0.02f, .maximum = 0.7f}, 15, 0.012f);
  ASSERT_TRUE(model.has_value()) << model.error().message;
  EXPECT_NEAR(model->threshold(0), 0.7, 1e-7);
  EXPECT_NEAR(model->threshold(15), 0.02, 1e-8);
  EXPECT_NEAR(model->attenuation(), std::log(0.7 / 0.02) / 0.012, 1e-3);
  const double ratio = std::pow(0.02 / 0.7, 1.0 / 15.0);
  for (std::uint32_t n = 1; n <= 15; ++n) {
    EXPECT_NEAR(model->threshold(n) / model->threshold(n - 1), ratio, 1e-6) << "layer " << n;
    EXPECT_NEAR(model->depthOf(model->threshold(n)), 0.012 * n / 15.0, 1e-6) << "layer " << n;
    EXPECT_NEAR(model->layerHeight(n), 0.012 * (1.0 - n / 15.0), 1e-7) << "layer " << n;
  }
}

// Every sRGB grey from 1 to 255, 4 pixels each, split into N = 8 layers with a known range:
// each pixel's layer is the formula's (no grey lies within 1e-9 of a bin edge, checked).
TEST(FurShells, EveryPixelLandsInTheLayerTheFormulaPredicts) {
  std::vector<int> codes;
  for (int code = 1; code <= 255; ++code) codes.insert(codes.end(), 4, code);
  const GreyPhoto photo = greyPhoto(4, codes);
  const double iMin = 0.01, iMax = 0.8;
  auto model = FurShellModel::create({.minimum = float(iMin), .maximum = float(iMax)}, 8, 0.01f);
  ASSERT_TRUE(model.has_value());
  const std::vector<float> luminances = photoLuminances(photo.texture());
  ASSERT_EQ(luminances.size(), codes.size());
  std::vector<int> seen(9, 0);
  for (std::size_t i = 0; i < codes.size(); ++i) {
    const double luminance = srgbToLinear(codes[i]);
    ASSERT_NEAR(luminances[i], luminance, 1e-6) << "code " << codes[i];
    const double edge = 8 * std::log(iMax / luminance) / std::log(iMax / iMin);
    ASSERT_GT(std::abs(edge - std::round(edge)), 1e-4) << "code " << codes[i] << " sits on a bin edge";
    const int expected = predictedLayer(luminance, iMin, iMax, 8);
    EXPECT_EQ(int(model->layerOf(luminances[i])), expected) << "code " << codes[i];
    ++seen[expected];
  }
  for (int n = 1; n <= 8; ++n) EXPECT_GT(seen[n], 0) << "layer " << n << " got no grey";
}

// Eight grey levels with known pixel counts (the photo's histogram by construction): the pixels
// per layer are the sums of the counts of the levels in each layer's band, and the histogram
// the module computes has each level's count in the level's bin.
TEST(FurShells, PixelCountsPerLayerMatchTheHistogram) {
  const std::vector<int> levels{250, 215, 180, 150, 120, 95, 70, 45};
  const std::vector<int> counts{40, 12, 30, 7, 25, 18, 9, 3};
  std::vector<int> codes;
  for (std::size_t k = 0; k < levels.size(); ++k) codes.insert(codes.end(), counts[k], levels[k]);
  while (codes.size() % 8 != 0) codes.push_back(levels[0]);  // pad to whole rows (counted below)
  const int padding = int(codes.size()) - 144;
  const GreyPhoto photo = greyPhoto(8, codes);
  const std::vector<float> luminances = photoLuminances(photo.texture());
  const double iMin = srgbToLinear(45), iMax = srgbToLinear(250);
  auto model = FurShellModel::create({.minimum = float(iMin), .maximum = float(iMax)}, 6, 0.01f);
  ASSERT_TRUE(model.has_value());

  std::vector<std::uint32_t> expected(6, 0);
  for (std::size_t k = 0; k < levels.size(); ++k)
    expected[predictedLayer(srgbToLinear(levels[k]), iMin, iMax, 6) - 1] += counts[k] + (k == 0 ? padding : 0);
  EXPECT_EQ(layerPixelCounts(*model, luminances), expected);

  const std::vector<std::uint32_t> histogram = luminanceHistogram(luminances, 4096);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const auto bin = std::size_t(srgbToLinear(levels[k]) * 4096);
    EXPECT_EQ(histogram[bin], std::uint32_t(counts[k] + (k == 0 ? padding : 0))) << "level " << levels[k];
  }
}

// A 100×100 photo whose luminances spread evenly over [0.05, 0.6], with 0.5 % of its pixels
// replaced by white glints and 0.5 % by black dead pixels: the 1st/99th percentiles land inside
// the core, within the 2 % of its range those outliers and the percentile itself can move them.
// The plain minimum and maximum are the outliers.
TEST(FurShells, RobustRangeIgnoresInjectedOutliers) {
  constexpr int kPixels = 10000;
  std::vector<float> luminances(kPixels);
  for (int i = 0; i < kPixels; ++i) luminances[i] = 0.05f + 0.55f * float(i) / float(kPixels - 1);
  // Every 200th pixel white, every 200th (offset by 100) black: 50 + 50 outliers.
  for (int i = 0; i < kPixels; i += 200) luminances[i] = 1.0f;
  for (int i = 100; i < kPixels; i += 200) luminances[i] = 0.0f;
  auto robust = robustLuminanceRange(luminances);
  ASSERT_TRUE(robust.has_value()) << robust.error().message;
  const float slack = 0.02f * 0.55f;
  EXPECT_GE(robust->minimum, 0.05f);
  EXPECT_LE(robust->minimum, 0.05f + slack);
  EXPECT_LE(robust->maximum, 0.6f);
  EXPECT_GE(robust->maximum, 0.6f - slack);

  auto naive = robustLuminanceRange(luminances, {.low = 0.0, .high = 1.0});
  ASSERT_TRUE(naive.has_value());
  EXPECT_EQ(naive->maximum, 1.0f);
  EXPECT_EQ(naive->minimum, kMinimumLuminance) << "black is floored: eq. 2 needs I_min > 0";
}

TEST(FurShells, RefusesPhotosWithoutContrastAndBadSettings) {
  const GreyPhoto flat = greyPhoto(4, std::vector<int>(16, 128));
  const auto refused = FurShellModel::fromPhoto(flat.texture());
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("contrast"), std::string::npos) << refused.error().message;
  EXPECT_FALSE(FurShellModel::create({0.1f, 0.5f}, 0, 0.01f).has_value());
  EXPECT_FALSE(FurShellModel::create({0.1f, 0.5f}, kMaxFurLayers + 1, 0.01f).has_value());
  EXPECT_FALSE(FurShellModel::create({0.1f, 0.5f}, 8, -1.0f).has_value());
  EXPECT_FALSE(FurShellModel::create({0.0f, 0.5f}, 8, 0.01f).has_value());
}

// ---------------------------------------------------------------------------------------------
// Fins on silhouette edges

// A UV sphere of radius 1 with a uv seam (duplicated column) and pole rings, as real meshes are
// split: the edges must still be found by position.
struct Sphere {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

Sphere uvSphere(int rings, int segments) {
  Sphere sphere;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const double theta = std::numbers::pi * r / rings, phi = 2.0 * std::numbers::pi * (s % segments) / segments;
      const bool pole = r == 0 || r == rings;  // exactly one point, as a modeller's sphere has
      sphere.positions.push_back(
          pole ? glm::vec3(0.0f, float(std::cos(theta)), 0.0f)
               : glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  const auto at = [&](int r, int s) { return std::uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s)
      sphere.indices.insert(sphere.indices.end(),
                            {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r + 1, s)});
  return sphere;
}

// Seen from a point 4 radii away, the analytic silhouette of the unit sphere is where
// n·(eye − n) = 0. Every fin's edge midpoint direction m satisfies it within the angle two
// faces of the mesh can differ by (Δ = π/rings, the largest step between neighbouring face
// normals: sin Δ bounds |cos| of the angle to the view); fins are not anywhere else. The fins
// form closed loops (every vertex they touch has an even number of them: around a vertex of a
// closed mesh the facing flips an even number of times), and the loop goes all the way round.
TEST(FurFins, SilhouetteEdgesOfASphereLieOnItsAnalyticSilhouette) {
  const int rings = 24, segments = 48;
  const Sphere sphere = uvSphere(rings, segments);
  auto edges = MeshEdges::build(sphere.positions, sphere.indices);
  ASSERT_TRUE(edges.has_value()) << edges.error().message;
  for (const auto& edge : edges->edges()) ASSERT_FALSE(edge.boundary) << "the seam must not be a boundary";

  const double tolerance = std::sin(std::numbers::pi / rings);
  for (const glm::vec4 eye : {glm::vec4(0, 0, 4, 1), glm::vec4(2.5f, 1.5f, -2.0f, 1), glm::vec4(0, 1, 0, 0)}) {
    std::vector<glm::uvec2> fins;
    edges->findSilhouette(eye, fins);
    ASSERT_GE(fins.size(), std::size_t(segments / 2)) << "too few fins to go round";
    std::map<std::uint64_t, int> degree;  // by position: seam copies are one vertex
    const auto key = [&](std::uint32_t v) {
      const glm::ivec3 q(glm::round(sphere.positions[v] * 1e5f));
      return (std::uint64_t(q.x + 200000) << 40) ^ (std::uint64_t(q.y + 200000) << 20) ^ std::uint64_t(q.z + 200000);
    };
    for (const glm::uvec2 fin : fins) {
      const glm::vec3 midpoint = 0.5f * (sphere.positions[fin.x] + sphere.positions[fin.y]);
      const glm::vec3 normal = glm::normalize(midpoint);
      const glm::vec3 toEye = glm::normalize(glm::vec3(eye) - eye.w * midpoint);
      EXPECT_LE(std::abs(glm::dot(normal, toEye)), tolerance) << "a fin away from the silhouette";
      ++degree[key(fin.x)];
      ++degree[key(fin.y)];
    }
    for (const auto& [vertex, count] : degree) EXPECT_EQ(count % 2, 0) << "the silhouette is not a closed loop";
  }
}

}  // namespace
}  // namespace mane::render
