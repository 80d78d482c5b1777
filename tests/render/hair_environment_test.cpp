// The environment's light scattered by a fibre's lobes (render/luts/hair_environment.hpp), against
// the full model of render/luts/marschner.hpp integrated by brute force over the sphere.

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "render/luts/gauss_legendre.hpp"
#include "render/luts/hair_environment.hpp"
#include "render/luts/marschner.hpp"

namespace mane::render {
namespace {

constexpr double kPi = std::numbers::pi;

double legendre(int l, double mu) {
  return l == 0 ? 1.0 : (l == 1 ? mu : 0.5 * (3.0 * mu * mu - 1.0));
}

// ∫ S(ωi, ωr) P_l(ωi·t) dωi over the sphere for l = 0, 1, 2, t = z and the eye at (θr, φ = 0):
// θi by composite 8-point Gauss–Legendre on 90 panels (2° each, about half the narrowest lobe's
// width), φ by 36 midpoints, which converge geometrically for the smooth periodic detector of
// width β_N = 10° (aliasing ~exp(−(36 β_N)²/2)).
std::array<glm::dvec3, 3> scatteredByTheFullModel(const HairShadingParams& params, double thetaR) {
  const std::vector<QuadratureNode> base = gaussLegendre(8);
  const auto direction = [](double theta, double phi) {
    return glm::dvec3(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), std::sin(theta));
  };
  const glm::dvec3 toEye = direction(thetaR, 0.0);
  constexpr int kPanels = 90, kPhiNodes = 36;
  std::array<glm::dvec3, 3> sums{};
  for (int panel = 0; panel < kPanels; ++panel)
    for (const QuadratureNode& node : base) {
      const double width = kPi / kPanels;
      const double thetaI = -0.5 * kPi + width * (panel + 0.5 + 0.5 * node.position);
      glm::dvec3 ring(0.0);
      for (int j = 0; j < kPhiNodes; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / kPhiNodes;
        ring += hairScattering(params, direction(thetaI, phi), toEye, glm::dvec3(0.0, 0.0, 1.0));
      }
      const double weight = 0.5 * width * node.weight * std::cos(thetaI) * (2.0 * kPi / kPhiNodes);
      for (int l = 0; l < 3; ++l) sums[l] += weight * legendre(l, std::sin(thetaI)) * ring;
    }
  return sums;
}

// A sky that does not change round the fibre, L = P_l(ωi·t), is the case the band weights hold
// exactly: its radiance at t is P_l(1) = 1 in band l and 0 in the others, so the fibre shows the
// weight of band l. Both grooms, the eye across the fibre and at grazing angles on either side.
TEST(HairEnvironment, BandWeightsScatterASkySymmetricRoundTheFibreAsTheFullModelDoes) {
  for (const HairShadingParams& params : {blondeHairParams(), darkHairParams()})
    for (const double degrees : {-65.0, 0.0, 40.0}) {
      const double thetaR = degrees * kPi / 180.0;
      const HairEnvironmentBands bands = hairEnvironmentBands(params, thetaR);
      const double scale = bands.reflected[0] + bands.crossed[0].r;
      const std::array<glm::dvec3, 3> scattered = scatteredByTheFullModel(params, thetaR);
      for (int l = 0; l < 3; ++l) {
        const glm::dvec3& expected = scattered[l];
        const glm::dvec3 weights = bands.crossed[l] + glm::dvec3(bands.reflected[l]);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(weights[c], expected[c], 1e-4 * scale)
              << "θr " << degrees << "°, band " << l << ", channel " << c << ", σa " << params.absorption.r;
      }
    }
}

// The lobes' cones: the R lobe reflects round the mirror cone θi = 2α_R − θr, so band 1 weighs
// the environment at sin(2α_R − θr) of band 0 (less the lobe's spread); dark hair, whose interior
// absorbs the rest, is nearly all R.
TEST(HairEnvironment, TheReflectedLobeSeesTheEnvironmentAlongItsMirrorCone) {
  const HairShadingParams params = darkHairParams();
  for (const double degrees : {-50.0, -10.0, 30.0}) {
    const double thetaR = degrees * kPi / 180.0;
    const HairEnvironmentBands bands = hairEnvironmentBands(params, thetaR);
    const double cone = std::sin(2.0 * params.r.shift - thetaR);
    EXPECT_NEAR(bands.reflected[1] / bands.reflected[0], cone, 0.02) << degrees << "°";
    EXPECT_LT(bands.crossed[0].r, 0.05 * bands.reflected[0]);
  }
}

TEST(HairEnvironment, TheTableSamplesTheEyeAngleFromEdgeToEdge) {
  const HairShadingParams params = blondeHairParams();
  const std::vector<HairEnvironmentBands> table = hairEnvironmentTable(params);
  ASSERT_EQ(table.size(), kHairEnvironmentSamples);
  const std::size_t middle = kHairEnvironmentSamples / 2;
  EXPECT_EQ(table[middle].reflected[1], hairEnvironmentBands(params, 0.0).reflected[1]);
  EXPECT_EQ(table.back().crossed[2], hairEnvironmentBands(params, 0.5 * kPi).crossed[2]);
}

}  // namespace
}  // namespace mane::render
