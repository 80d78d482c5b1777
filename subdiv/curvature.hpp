#pragma once
// Curvature of a parametric surface S(u, v) from its first and second derivatives, through
// the first (E, F, G) and second (L, M, N) fundamental forms (do Carmo, "Differential
// Geometry of Curves and Surfaces", §3-3).

#include <glm/vec3.hpp>

namespace mane::subdiv {

/// Curvatures in 1/metre. Sign convention: positive where the surface bends away from its
/// normal n = normalize(∂u × ∂v), so a sphere with outward normals has mean curvature +1/R
/// and a cylinder +1/(2R).
struct SurfaceCurvature {
  float mean = 0.0f;        ///< H = (k1 + k2) / 2
  float gaussian = 0.0f;    ///< K = k1 · k2
  float principal1 = 0.0f;  ///< k1 ≥ k2
  float principal2 = 0.0f;
};

/// H = −(E·N − 2F·M + G·L) / (2(EG − F²)) and K = (L·N − M²) / (EG − F²), with
/// L = Suu·n, M = Suv·n, N = Svv·n (the minus gives the sign convention above); k1,2 =
/// H ± √(H² − K). All zero where the tangents are degenerate (EG − F² ≈ 0).
[[nodiscard]] SurfaceCurvature curvatureFromDerivatives(const glm::dvec3& du, const glm::dvec3& dv,
                                                        const glm::dvec3& duu, const glm::dvec3& duv,
                                                        const glm::dvec3& dvv);

}  // namespace mane::subdiv
