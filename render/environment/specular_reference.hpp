#pragma once
// The environment's specular pre-filter by brute force, the reference of the GPU chain
// (render/environment/specular_chain.hpp). Karis's split sum ("Real Shading in Unreal Engine 4",
// 2013) takes the view along the reflected direction n; the pre-filtered radiance is then
//   L̃(n) = ∫ L(l)·D(h)·max(n·l, 0) dl / ∫ D(h)·max(n·l, 0) dl,  h = normalize(n + l),
// with D the GGX (Trowbridge–Reitz) distribution of α = roughness². Here every texel of the
// source is a sample, weighted by its solid angle.

#include <glm/vec3.hpp>

#include "render/environment/environment_map.hpp"

namespace mane::render {

/// GGX's D(h) for the cosine between h and the normal, α = roughness² (Walter et al. 2007, eq. 33).
[[nodiscard]] double ggxDistribution(double cosine, double roughness);

/// L̃(n) above for unit `direction`, roughness in (0, 1].
[[nodiscard]] glm::vec3 prefilteredRadianceReference(const CubeMap& source, glm::vec3 direction, float roughness);

}  // namespace mane::render
