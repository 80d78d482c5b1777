// Curl and frizz of dense strands (physics/interpolation.hpp): a strand round a straight guide
// winds the helix its radius, turns and phase give, checked in double; frizz stays within its
// cube and spreads as a uniform variable does; a layout with curl keeps every other field of the
// layout without it.

#include <cmath>
#include <cstddef>
#include <cstring>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"
#include "physics/interpolation.hpp"

namespace mane::physics {
namespace {

constexpr std::uint32_t kGuideVertices = 21;
constexpr float kGuideLength = 0.2f;

// One straight guide from the origin down −y; its frame is the fixed axes (no partners).
DenseStrandLayout straightGuideLayout(std::uint32_t denseVertices, std::vector<DenseStrand> strands) {
  DenseStrandLayout layout;
  layout.guideCount = 1;
  layout.guideVertexCount = kGuideVertices;
  layout.vertexCount = denseVertices;
  layout.guideFrames = {{0, 0}};
  for (DenseStrand& strand : strands) strand.vertexScale = float(kGuideVertices - 1) / float(denseVertices - 1);
  layout.strands = std::move(strands);
  layout.curve = StrandCurve::kLinear;
  return layout;
}

std::vector<glm::vec3> straightGuide() {
  std::vector<glm::vec3> guide;
  for (std::uint32_t v = 0; v < kGuideVertices; ++v)
    guide.push_back({0.0f, -kGuideLength * float(v) / float(kGuideVertices - 1), 0.0f});
  return guide;
}

std::vector<glm::vec3> interpolate(const DenseStrandLayout& layout) {
  std::vector<glm::vec3> out(layout.vertexTotal());
  auto done = interpolateDenseStrands(straightGuide(), layout, out, {}, 1u);
  EXPECT_TRUE(done.has_value()) << (done ? "" : done.error().message);
  return out;
}

// Along −y the formula's axes are a = d × n = −x and b = d × a = −z: vertex i lies at
// −R(t)·(cos 2π(φ + T·t), 0, sin 2π(φ + T·t)) off the guide, R(t) = r·min(4t, 1).
TEST(StrandCurl, AStrandRoundAStraightGuideWindsTheHelixItsCurlGives) {
  const float radius = 0.005f, turns = 3.5f, phase = 0.2f;
  constexpr std::uint32_t kDense = 81;
  const auto layout = straightGuideLayout(kDense, {{.curlRadius = radius, .curlTurns = turns, .curlPhase = phase}});
  const auto points = interpolate(layout);
  double worst = 0.0;
  for (std::uint32_t i = 0; i < kDense; ++i) {
    const double t = double(i) / (kDense - 1);
    const double r = radius * std::min(4.0 * t, 1.0);
    const double angle = 2.0 * std::numbers::pi * (phase + turns * t);
    const glm::dvec3 expected(-r * std::cos(angle), -kGuideLength * t, -r * std::sin(angle));
    worst = std::max(worst, glm::length(glm::dvec3(points[i]) - expected));
  }
  // Float rounding of positions 0.2 m from the origin (6e-8 per ulp), not the series: its error
  // is below 4e-7 of the 5 mm radius.
  EXPECT_LT(worst, 2e-7) << "metres from the helix";
  RecordProperty("worst_from_helix_nm", std::to_string(worst * 1e9));
}

// Frizz f: vertex i of a strand strays from where it would lie without it by f·t·(x0, x1, x2),
// each x uniform in [−1, 1): within the cube, of mean 0 and root mean square 1/√3.
TEST(StrandCurl, FrizzStaysInItsCubeAndSpreadsAsAUniformVariable) {
  constexpr std::uint32_t kDense = 11, kStrands = 3000;
  const float frizz = 0.001f;
  const auto plain = interpolate(straightGuideLayout(kDense, std::vector<DenseStrand>(kStrands)));
  const auto frizzed = interpolate(straightGuideLayout(kDense, std::vector<DenseStrand>(kStrands, {.frizz = frizz})));
  glm::dvec3 sum(0.0), squares(0.0);
  for (std::uint32_t s = 0; s < kStrands; ++s)
    for (std::uint32_t i = 0; i < kDense; ++i) {
      const std::size_t at = std::size_t(s) * kDense + i;
      const double t = double(i) / (kDense - 1);
      const glm::dvec3 offset = glm::dvec3(frizzed[at]) - glm::dvec3(plain[at]);
      for (int c = 0; c < 3; ++c) ASSERT_LE(std::abs(offset[c]), frizz * t + 1e-9) << s << ", " << i;
      if (i + 1 == kDense) {
        sum += offset / double(frizz);
        squares += offset * offset / double(frizz * frizz);
      }
    }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(sum[c] / kStrands, 0.0, 0.03) << "axis " << c;
    EXPECT_NEAR(std::sqrt(squares[c] / kStrands), 1.0 / std::sqrt(3.0), 0.02) << "axis " << c;
  }
  EXPECT_NE(frizzed[kDense - 1], frizzed[2 * kDense - 1]) << "two strands on one guide frizz alike";
}

// Curl is drawn from each strand's random stream after everything else, so curled strands keep
// their guides, weights, offsets, clump and length; each winds once per period of its length, its
// radius within the variation.
TEST(StrandCurl, ACurledLayoutKeepsTheStraightLayoutsStrands) {
  GroomSettings groom;
  groom.strandCount = 200;
  groom.particlesPerStrand = 16;
  groom.strandLength = 0.3f;
  const auto guides = *generateGroom(groom);
  DenseGroomSettings straight;
  straight.strandCount = 2000;
  straight.blend = GuideBlend::kBarycentric;
  DenseGroomSettings curled = straight;
  curled.curlRadius = 0.004f;
  curled.curlPeriod = 0.025f;
  curled.curlVariation = 0.25f;
  const auto a = buildDenseStrandLayout(guides, straight);
  const auto b = buildDenseStrandLayout(guides, curled);
  ASSERT_TRUE(a.has_value() && b.has_value());
  for (std::size_t s = 0; s < a->strands.size(); ++s) {
    const DenseStrand& x = a->strands[s];
    const DenseStrand& y = b->strands[s];
    ASSERT_EQ(0, std::memcmp(&x, &y, offsetof(DenseStrand, curlRadius))) << "strand " << s;
    double length = 0.0;
    const auto& home = guides[x.guides[0]];
    for (std::size_t v = 0; v + 1 < home.size(); ++v)
      length += glm::distance(glm::dvec3(home[v]), glm::dvec3(home[v + 1]));
    EXPECT_NEAR(y.curlTurns, x.lengthScale * length / 0.025, 1e-4 * y.curlTurns) << "strand " << s;
    EXPECT_GE(y.curlRadius, 0.004f * 0.75f) << "strand " << s;
    EXPECT_LE(y.curlRadius, 0.004f * 1.25f) << "strand " << s;
    EXPECT_GE(y.curlPhase, 0.0f);
    EXPECT_LT(y.curlPhase, 1.0f);
  }
}

TEST(StrandCurl, SettingsOutOfRangeAreNamed) {
  const std::vector<std::vector<glm::vec3>> guides{straightGuide()};
  const auto message = [&](auto change) {
    DenseGroomSettings settings;
    change(settings);
    auto layout = buildDenseStrandLayout(guides, settings);
    return layout ? std::string("(built)") : layout.error().message;
  };
  EXPECT_EQ(message([](DenseGroomSettings& s) { s.curlRadius = 0.06f; }),
            "Dense groom settings: curlRadius must be in [0, 0.05] metres.");
  EXPECT_EQ(message([](DenseGroomSettings& s) { s.curlPeriod = 0.0f; }),
            "Dense groom settings: curlPeriod must be in [0.001, 10] metres.");
  EXPECT_EQ(message([](DenseGroomSettings& s) { s.curlVariation = -0.1f; }),
            "Dense groom settings: curlVariation must be in [0, 1].");
  EXPECT_EQ(message([](DenseGroomSettings& s) { s.frizz = 0.02f; }),
            "Dense groom settings: frizz must be in [0, 0.01] metres.");
  DenseStrandLayout bad = straightGuideLayout(3, {{.curlPhase = 1.0f}});
  EXPECT_FALSE(validateStrandLayout(bad).has_value());
}

}  // namespace
}  // namespace mane::physics
