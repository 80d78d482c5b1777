#include "render/luts/skin_specular.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mane::render {

double beckmannDistribution(double nDotH, double roughness) {
  if (nDotH <= 0.0 || roughness <= 0.0) return 0.0;
  const double cos2 = nDotH * nDotH;
  const double tan2 = (1.0 - cos2) / cos2;
  const double a2 = roughness * roughness;
  return std::exp(-tan2 / a2) / (std::numbers::pi * a2 * cos2 * cos2);
}

double schlickFresnel(double cosTheta, double f0) {
  const double c = 1.0 - std::clamp(cosTheta, 0.0, 1.0);
  const double c2 = c * c;
  return f0 + (1.0 - f0) * c2 * c2 * c;
}

double kelemenSzirmayKalos(glm::dvec3 normal, glm::dvec3 toLight, glm::dvec3 toEye, double roughness, double rhoS,
                           double f0) {
  if (glm::dot(normal, toLight) <= 0.0 || glm::dot(normal, toEye) <= 0.0) return 0.0;
  const glm::dvec3 h = toLight + toEye;
  const double h2 = glm::dot(h, h);  // |L + V|² = 2(1 + L·V): [KS01]'s stand-in for G/(4 cosθi cosθo)
  if (h2 <= 0.0) return 0.0;
  const glm::dvec3 halfway = h / std::sqrt(h2);
  return rhoS * beckmannDistribution(glm::dot(normal, halfway), roughness) *
         schlickFresnel(glm::dot(halfway, toEye), f0) / h2;
}

double kelemenSzirmayKalosAlbedo(double nDotV, double roughness, double f0) {
  constexpr int kThetaSteps = 512, kPhiSteps = 256;
  const double cosV = std::clamp(nDotV, 1e-4, 1.0);
  const glm::dvec3 normal(0.0, 0.0, 1.0), toEye(std::sqrt(1.0 - cosV * cosV), 0.0, cosV);
  const double dTheta = 0.5 * std::numbers::pi / kThetaSteps, dPhi = 2.0 * std::numbers::pi / kPhiSteps;
  double sum = 0.0;
  for (int i = 0; i < kThetaSteps; ++i) {
    const double theta = (i + 0.5) * dTheta;
    for (int j = 0; j < kPhiSteps; ++j) {
      const double phi = (j + 0.5) * dPhi;
      const glm::dvec3 toLight(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      sum += kelemenSzirmayKalos(normal, toLight, toEye, roughness, 1.0, f0) * std::cos(theta) * std::sin(theta);
    }
  }
  return sum * dTheta * dPhi;
}

double encodeBeckmann(double d) {
  return 0.5 * std::pow(std::max(d, 0.0), 0.1);
}

double decodeBeckmann(double encoded) {
  return std::pow(2.0 * std::max(encoded, 0.0), 10.0);
}

}  // namespace mane::render
