// Strand resampling: equal arc-length spacing, exact endpoints, length preserved to the
// discretisation bound, and errors for degenerate input.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "physics/strand_resample.hpp"

namespace mane::physics {
namespace {

double polylineLength(const std::vector<glm::vec3>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i)
    length += glm::length(glm::dvec3(points[i]) - glm::dvec3(points[i - 1]));
  return length;
}

TEST(StrandResample, StraightLineWithUnevenInputBecomesExactlyEquallySpaced) {
  // Collinear points at uneven spacing, one repeated (a zero-length segment): on a straight line
  // arc length equals chord length, so every output gap must be L/(N − 1). Tolerance 1e-5
  // relative: float coordinates of size ~1 carry 6e-8 relative rounding per point.
  const glm::vec3 root(0.1f, 1.5f, -0.2f);
  const glm::vec3 direction = glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f));
  const std::vector<float> along{0.0f, 0.01f, 0.05f, 0.05f, 0.2f, 0.21f, 0.6f};
  std::vector<glm::vec3> points;
  for (float s : along) points.push_back(root + direction * s);

  const std::size_t count = 16;
  auto resampled = resampleStrand(points, count);
  ASSERT_TRUE(resampled.has_value()) << resampled.error().message;
  ASSERT_EQ(resampled->size(), count);
  const double total = polylineLength(points);
  const double expected = total / static_cast<double>(count - 1);
  for (std::size_t i = 1; i < count; ++i) {
    const double gap = glm::length(glm::dvec3((*resampled)[i]) - glm::dvec3((*resampled)[i - 1]));
    EXPECT_NEAR(gap, expected, 1e-5 * expected) << "gap " << i;
  }
}

TEST(StrandResample, RootAndTipAreCopiedBitForBit) {
  const std::vector<glm::vec3> points{
      {0.123456f, -7.654321f, 3.3333333f}, {0.2f, -7.5f, 3.4f}, {1.0e-3f, 2.0f, 9.87654f}};
  for (std::size_t count : {2u, 3u, 7u, 64u}) {
    auto resampled = resampleStrand(points, count);
    ASSERT_TRUE(resampled.has_value()) << resampled.error().message;
    EXPECT_EQ(resampled->front(), points.front()) << count;
    EXPECT_EQ(resampled->back(), points.back()) << count;
  }
}

TEST(StrandResample, CircleArcKeepsItsLengthWithinTheDiscretisationBound) {
  // A quarter circle of radius R = 0.3 m given as m = 1000 chords, resampled to N = 32 points.
  // The output points lie on the input chords at equal arc steps. Reference: the exact arc length
  // L = Rθ. A chord spanning angle φ is 2R·sin(φ/2) = Rφ(1 − φ²/24 + …), so replacing the arc by
  // n = N − 1 chords loses at most L·θ²/(24 n²); the input polyline itself is shorter than the
  // arc by at most L·θ²/(24 m²). The output length must lie within the sum of both bounds
  // (plus float rounding) below L, and never above the input polyline (triangle inequality).
  const double radius = 0.3;
  const double angle = std::numbers::pi / 2.0;
  const std::size_t inputSegments = 1000;
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i <= inputSegments; ++i) {
    const double phi = angle * static_cast<double>(i) / static_cast<double>(inputSegments);
    points.emplace_back(static_cast<float>(radius * std::cos(phi)), static_cast<float>(radius * std::sin(phi)), 0.0f);
  }
  const std::size_t count = 32;
  auto resampled = resampleStrand(points, count);
  ASSERT_TRUE(resampled.has_value()) << resampled.error().message;

  const double exact = radius * angle;
  const double n = static_cast<double>(count - 1);
  const double m = static_cast<double>(inputSegments);
  const double bound = exact * angle * angle / 24.0 * (1.0 / (n * n) + 1.0 / (m * m));
  const double floatRounding = 1e-6 * exact;
  const double length = polylineLength(*resampled);
  EXPECT_LE(length, polylineLength(points) + floatRounding);
  EXPECT_GE(length, exact - bound - floatRounding) << "lost " << exact - length << " m, bound " << bound << " m";
  // Every output point is on the input polyline: between the circle and its chords' sagitta.
  const double sagitta = radius * (1.0 - std::cos(angle / m / 2.0));
  for (const glm::vec3& p : *resampled) {
    const double r = glm::length(glm::dvec3(p));
    EXPECT_LE(r, radius + 1e-6);
    EXPECT_GE(r, radius - sagitta - 1e-6);
  }
}

TEST(StrandResample, PointsAreEquallySpacedByArcLengthAroundCorners) {
  // An L-shaped strand: 1 m along +X then 1 m along +Y. With N = 5 the arc-length steps are
  // 0.5 m, so the output is (0,0), (0.5,0), (1,0) — the corner itself — (1,0.5), (1,1). Exact in
  // binary floating point.
  const std::vector<glm::vec3> points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  auto resampled = resampleStrand(points, 5);
  ASSERT_TRUE(resampled.has_value()) << resampled.error().message;
  const std::vector<glm::vec3> expected{{0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}, {1, 0.5f, 0}, {1, 1, 0}};
  EXPECT_EQ(*resampled, expected);
}

TEST(StrandResample, DegenerateInputIsAnError) {
  const std::vector<glm::vec3> one{{0, 0, 0}};
  auto tooFew = resampleStrand(one, 8);
  ASSERT_FALSE(tooFew.has_value());
  EXPECT_NE(tooFew.error().message.find("1 point"), std::string::npos) << tooFew.error().message;

  const std::vector<glm::vec3> line{{0, 0, 0}, {0, -1, 0}};
  auto countOne = resampleStrand(line, 1);
  ASSERT_FALSE(countOne.has_value());
  EXPECT_NE(countOne.error().message.find("at least 2"), std::string::npos) << countOne.error().message;

  const std::vector<glm::vec3> coincident{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  auto zero = resampleStrand(coincident, 4);
  ASSERT_FALSE(zero.has_value());
  EXPECT_NE(zero.error().message.find("zero length"), std::string::npos) << zero.error().message;

  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<glm::vec3> withNan{{0, 0, 0}, {0, -0.1f, 0}, {0, nan, 0}};
  auto bad = resampleStrand(withNan, 4);
  ASSERT_FALSE(bad.has_value());
  EXPECT_NE(bad.error().message.find("point 2"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("not a finite"), std::string::npos) << bad.error().message;

  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<glm::vec3> withInf{{inf, 0, 0}, {0, -0.1f, 0}};
  EXPECT_FALSE(resampleStrand(withInf, 4).has_value());
}

TEST(StrandResample, GroomErrorsNameTheStrand) {
  const std::vector<std::vector<glm::vec3>> groom{{{0, 0, 0}, {0, -1, 0}}, {{0, 0, 0}, {0, 0, 0}}};
  auto resampled = resampleGroom(groom, 4);
  ASSERT_FALSE(resampled.has_value());
  EXPECT_NE(resampled.error().message.find("strand 1"), std::string::npos) << resampled.error().message;
  EXPECT_NE(resampled.error().message.find("zero length"), std::string::npos) << resampled.error().message;

  EXPECT_FALSE(resampleGroom({}, 4).has_value());

  auto good = resampleGroom(std::span(groom).first(1), 3);
  ASSERT_TRUE(good.has_value()) << good.error().message;
  ASSERT_EQ(good->size(), 1u);
  EXPECT_EQ((*good)[0], (std::vector<glm::vec3>{{0, 0, 0}, {0, -0.5f, 0}, {0, -1, 0}}));
}

}  // namespace
}  // namespace mane::physics
