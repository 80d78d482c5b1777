#include "render/luts/hair_environment.hpp"

#include <cmath>
#include <numbers>

namespace mane::render {

HairEnvironmentBands hairEnvironmentBands(const HairShadingParams& params, double thetaR) {
  // ∫ M_p P_l(sin θi) cos θi dθi for each lobe and band.
  std::array<std::array<double, 3>, 3> moments{};  // [lobe][band]
  const double step = std::numbers::pi / double(kHairEnvironmentNodes);
  for (std::size_t k = 0; k < kHairEnvironmentNodes; ++k) {
    const double thetaI = -0.5 * std::numbers::pi + (double(k) + 0.5) * step;
    const double mu = std::sin(thetaI);
    const std::array<double, 3> legendre{1.0, mu, 0.5 * (3.0 * mu * mu - 1.0)};
    const LongitudinalLobes m = longitudinalScattering(params, thetaI, thetaR);
    const double weight = std::cos(thetaI) * step;
    for (std::size_t l = 0; l < 3; ++l) {
      moments[0][l] += m.r * legendre[l] * weight;
      moments[1][l] += m.tt * legendre[l] * weight;
      moments[2][l] += m.trt * legendre[l] * weight;
    }
  }
  const AzimuthalLobes albedo = azimuthalAlbedo(params, std::cos(thetaR));
  HairEnvironmentBands bands;
  for (std::size_t l = 0; l < 3; ++l) {
    bands.reflected[l] = albedo.r * moments[0][l];
    bands.crossed[l] = albedo.tt * moments[1][l] + albedo.trt * moments[2][l];
  }
  return bands;
}

std::vector<HairEnvironmentBands> hairEnvironmentTable(const HairShadingParams& params) {
  std::vector<HairEnvironmentBands> table;
  table.reserve(kHairEnvironmentSamples);
  for (std::size_t k = 0; k < kHairEnvironmentSamples; ++k)
    table.push_back(hairEnvironmentBands(
        params, -0.5 * std::numbers::pi + std::numbers::pi * double(k) / double(kHairEnvironmentSamples - 1)));
  return table;
}

}  // namespace mane::render
