#include "render/luts/skin_profile.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace mane::render {

double skinGaussian(double variance, double radius) {
  return std::exp(-radius * radius / (2.0 * variance)) / (2.0 * std::numbers::pi * variance);
}

glm::dvec3 SkinProfile::reflectance(double radius) const {
  glm::dvec3 sum(0.0);
  for (const SkinGaussian& g : gaussians) sum += g.weight * skinGaussian(g.variance, radius);
  return sum;
}

glm::dvec3 SkinProfile::reflectanceAtWorldDistance(double distance) const {
  return reflectance(millimetres(distance)) * (millimetresPerUnit * millimetresPerUnit);
}

Result<void> validate(const SkinProfile& profile) {
  if (!std::isfinite(profile.millimetresPerUnit) || profile.millimetresPerUnit <= 0.0)
    return fail("skin profile: millimetresPerUnit is " + std::to_string(profile.millimetresPerUnit) +
                ", expected a finite number > 0");
  glm::dvec3 sums(0.0);
  for (std::size_t i = 0; i < profile.gaussians.size(); ++i) {
    const SkinGaussian& g = profile.gaussians[i];
    if (!std::isfinite(g.variance) || g.variance <= 0.0)
      return fail("skin profile: gaussians[" + std::to_string(i) + "].variance is " + std::to_string(g.variance) +
                  " mm², expected a finite number > 0");
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(g.weight[c]) || g.weight[c] < 0.0)
        return fail("skin profile: gaussians[" + std::to_string(i) + "].weight[" + std::to_string(c) + "] is " +
                    std::to_string(g.weight[c]) + ", expected a finite number ≥ 0");
    sums += g.weight;
  }
  // ∫ R dA = Σ w: a profile that does not sum to 1 would brighten or darken the diffuse term.
  for (int c = 0; c < 3; ++c)
    if (std::abs(sums[c] - 1.0) > 1e-3)
      return fail("skin profile: the weights of channel " + std::to_string(c) + " sum to " + std::to_string(sums[c]) +
                  ", expected 1 (within 1e-3)");
  return {};
}

glm::dvec3 SkinProfile::transmittance(double thickness) const {
  glm::dvec3 sum(0.0);
  for (const SkinGaussian& g : gaussians) sum += g.weight * std::exp(-thickness * thickness / (2.0 * g.variance));
  return sum;
}

glm::dvec3 SkinProfile::broadShare(double minVariance) const {
  glm::dvec3 share(0.0);
  for (const SkinGaussian& gaussian : gaussians)
    if (gaussian.variance >= minVariance) share += gaussian.weight;
  return share;
}

}  // namespace mane::render
