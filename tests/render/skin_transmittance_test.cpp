// SkinProfile::transmittance against its definition: the profile R(r) integrated over a plane
// of entry points at depth d, by brute-force quadrature in the plane's radius.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "render/luts/skin_profile.hpp"

namespace mane::render {
namespace {

// ∫₀^∞ R(√(d² + ρ²)) 2πρ dρ by the midpoint rule, 0.2 µm steps out to 30 mm (20 σ of the
// widest Gaussian).
glm::dvec3 planeIntegral(const SkinProfile& profile, double depth) {
  constexpr double kStep = 2e-4;
  glm::dvec3 sum(0.0);
  for (double rho = 0.5 * kStep; rho < 30.0; rho += kStep)
    sum += profile.reflectance(std::sqrt(depth * depth + rho * rho)) * (2.0 * std::numbers::pi * rho * kStep);
  return sum;
}

TEST(SkinTransmittance, EqualsTheProfileSummedOverAPlaneAtThatDepth) {
  const SkinProfile profile;
  for (double depth : {0.0, 0.05, 0.3, 1.0, 2.5, 6.0}) {
    const glm::dvec3 expected = planeIntegral(profile, depth);
    const glm::dvec3 actual = profile.transmittance(depth);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-4) << "depth " << depth << " mm, channel " << c;
  }
}

TEST(SkinTransmittance, IsOneAtTheSurfaceAndRedLastsLongest) {
  const SkinProfile profile;
  const glm::dvec3 surface = profile.transmittance(0.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(surface[c], 1.0, 1e-3);
  // Red has the wide Gaussians (1.99 and 7.41 mm²): through 1 mm of skin it is most of what is left.
  const glm::dvec3 millimetre = profile.transmittance(1.0);
  EXPECT_GT(millimetre.r, 0.35);
  EXPECT_GT(millimetre.r, 10.0 * millimetre.g);
  EXPECT_GT(millimetre.g, millimetre.b);
}

}  // namespace
}  // namespace mane::render
