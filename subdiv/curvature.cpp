#include "subdiv/curvature.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace mane::subdiv {

SurfaceCurvature curvatureFromDerivatives(const glm::dvec3& du, const glm::dvec3& dv, const glm::dvec3& duu,
                                          const glm::dvec3& duv, const glm::dvec3& dvv) {
  const double e = glm::dot(du, du);
  const double f = glm::dot(du, dv);
  const double g = glm::dot(dv, dv);
  const double metric = e * g - f * f;  // |du × dv|²
  // Relative test: the parametrisation's scale is arbitrary, its degeneracy is not.
  if (!(metric > 1e-24 * e * g) || !(metric > 0.0)) return {};
  const glm::dvec3 normal = glm::cross(du, dv) / std::sqrt(metric);
  const double l = glm::dot(duu, normal);
  const double m = glm::dot(duv, normal);
  const double n = glm::dot(dvv, normal);
  const double mean = -(e * n - 2.0 * f * m + g * l) / (2.0 * metric);
  const double gaussian = (l * n - m * m) / metric;
  // H² − K ≥ 0 in exact arithmetic (umbilics give 0); rounding may dip below.
  const double spread = std::sqrt(std::max(mean * mean - gaussian, 0.0));
  return SurfaceCurvature{.mean = static_cast<float>(mean),
                          .gaussian = static_cast<float>(gaussian),
                          .principal1 = static_cast<float>(mean + spread),
                          .principal2 = static_cast<float>(mean - spread)};
}

}  // namespace mane::subdiv
