#pragma once
// Diffuse light from an environment by nine spherical harmonics (Ramamoorthi and Hanrahan 2001,
// "An Efficient Representation for Irradiance Environment Maps"): the radiance projected on the
// real harmonics of bands 0 to 2, convolved with the clamped cosine. The irradiance they give
// differs from the exact one by about 3 % on average (their §3), and exactly matches it for any
// radiance made of those bands alone, a constant sky included.

#include <array>

#include <glm/vec3.hpp>

#include "render/environment/environment_map.hpp"

namespace mane::render {

/// Coefficients of the nine real harmonics, in the order Y00, Y1−1, Y10, Y11, Y2−2, Y2−1, Y20,
/// Y21, Y22, as their equation 3 writes them in x, y, z (world axes: any orthonormal frame spans
/// the same bands).
using SphericalHarmonics9 = std::array<glm::vec3, 9>;

/// The nine harmonics at unit `direction`.
[[nodiscard]] std::array<float, 9> harmonicsAt(glm::vec3 direction);

/// Σ radiance × Y × solid angle over every texel of `cube`.
[[nodiscard]] SphericalHarmonics9 projectRadiance(const CubeMap& cube);

/// The irradiance's coefficients from the radiance's: band l scaled by Â_l = π, 2π/3, π/4 (their
/// equation 8).
[[nodiscard]] SphericalHarmonics9 irradianceFromRadiance(const SphericalHarmonics9& radiance);

/// The function's average over the sphere: the band-0 term alone, coefficient × Y00.
[[nodiscard]] glm::vec3 sphereAverage(const SphericalHarmonics9& coefficients);

/// Σ coefficient × Y at unit `direction`.
[[nodiscard]] glm::vec3 evaluate(const SphericalHarmonics9& coefficients, glm::vec3 direction);

}  // namespace mane::render
