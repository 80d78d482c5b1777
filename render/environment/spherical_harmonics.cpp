#include "render/environment/spherical_harmonics.hpp"

#include <cstddef>
#include <numbers>

#include <glm/vec3.hpp>

namespace mane::render {

namespace {

// Y00, the constant harmonic: √(1/4π).
constexpr float kY00 = 0.282094792f;

}  // namespace

std::array<float, 9> harmonicsAt(glm::vec3 d) {
  // The real harmonics' normalisations: √(1/4π), √(3/4π), √(15/4π), √(5/16π), √(15/16π).
  constexpr float k0 = kY00, k1 = 0.488602512f, k2 = 1.092548431f, k20 = 0.315391565f, k22 = 0.546274215f;
  return {k0,
          k1 * d.y,
          k1 * d.z,
          k1 * d.x,
          k2 * d.x * d.y,
          k2 * d.y * d.z,
          k20 * (3.0f * d.z * d.z - 1.0f),
          k2 * d.x * d.z,
          k22 * (d.x * d.x - d.y * d.y)};
}

SphericalHarmonics9 projectRadiance(const CubeMap& cube) {
  // Summed in double: a 256-texel cube has 393,216 terms.
  std::array<glm::dvec3, 9> sum{};
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < cube.size; ++row)
      for (int column = 0; column < cube.size; ++column) {
        const glm::vec3 direction =
            cubeDirection(face, {(float(column) + 0.5f) / float(cube.size), (float(row) + 0.5f) / float(cube.size)});
        const std::array<float, 9> y = harmonicsAt(direction);
        const glm::dvec3 weighted =
            glm::dvec3(cube.at(face, column, row)) * cubeTexelSolidAngle(cube.size, column, row);
        for (std::size_t i = 0; i < 9; ++i) sum[i] += weighted * double(y[i]);
      }
  SphericalHarmonics9 result;
  for (std::size_t i = 0; i < 9; ++i) result[i] = glm::vec3(sum[i]);
  return result;
}

SphericalHarmonics9 irradianceFromRadiance(const SphericalHarmonics9& radiance) {
  constexpr float kPi = std::numbers::pi_v<float>;
  constexpr std::array<float, 9> kBand = {kPi,        2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f,
                                          kPi / 4.0f, kPi / 4.0f,        kPi / 4.0f,        kPi / 4.0f,
                                          kPi / 4.0f};
  SphericalHarmonics9 result;
  for (std::size_t i = 0; i < 9; ++i) result[i] = radiance[i] * kBand[i];
  return result;
}

glm::vec3 sphereAverage(const SphericalHarmonics9& coefficients) {
  return coefficients[0] * kY00;
}

glm::vec3 evaluate(const SphericalHarmonics9& coefficients, glm::vec3 direction) {
  const std::array<float, 9> y = harmonicsAt(direction);
  glm::vec3 sum(0.0f);
  for (std::size_t i = 0; i < 9; ++i) sum += coefficients[i] * y[i];
  return sum;
}

}  // namespace mane::render
