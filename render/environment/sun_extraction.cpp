#include "render/environment/sun_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace mane::render {
namespace {

double luminance(glm::dvec3 radiance) {
  return glm::dot(radiance, glm::dvec3(0.2126, 0.7152, 0.0722));  // Rec. 709
}

/// Calls visit(face, column, row, direction) for every texel of `cube`.
template <class Visit>
void eachTexel(const CubeMap& cube, Visit visit) {
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < cube.size; ++row)
      for (int column = 0; column < cube.size; ++column)
        visit(face, column, row,
              cubeDirection(face, {(float(column) + 0.5f) / float(cube.size), (float(row) + 0.5f) / float(cube.size)}));
}

glm::vec3& texelOf(CubeMap& cube, int face, int column, int row) {
  return cube.faces[std::size_t(face)][std::size_t(row) * std::size_t(cube.size) + std::size_t(column)];
}

}  // namespace

SunExtraction extractSun(CubeMap cube) {
  SunExtraction result;
  glm::vec3 brightest(0.0f);
  double brightestLuminance = -1.0;
  eachTexel(cube, [&](int face, int column, int row, glm::vec3 direction) {
    const double y = luminance(cube.at(face, column, row));
    if (y > brightestLuminance) brightestLuminance = y, brightest = direction;
  });
  const double cosCore = std::cos(kCoreDegrees * std::numbers::pi / 180.0);
  const double cosRing = std::cos(kRingDegrees * std::numbers::pi / 180.0);
  glm::dvec3 ringSum(0.0);
  double ringSolidAngle = 0.0;
  eachTexel(cube, [&](int face, int column, int row, glm::vec3 direction) {
    const double cosine = glm::dot(direction, brightest);
    if (cosine > cosCore || cosine < cosRing) return;
    const double solidAngle = cubeTexelSolidAngle(cube.size, column, row);
    ringSum += glm::dvec3(cube.at(face, column, row)) * solidAngle;
    ringSolidAngle += solidAngle;
  });
  if (ringSolidAngle <= 0.0) {
    result.radiance = std::move(cube);
    return result;
  }
  const glm::dvec3 sky = ringSum / ringSolidAngle;
  if (!(brightestLuminance > kSunContrast * luminance(sky))) {
    result.radiance = std::move(cube);
    return result;
  }
  glm::dvec3 given(0.0), weightedDirection(0.0);
  eachTexel(cube, [&](int face, int column, int row, glm::vec3 direction) {
    if (glm::dot(direction, brightest) < cosCore) return;
    glm::vec3& texel = texelOf(cube, face, column, row);
    if (!(luminance(texel) > kAboveSky * luminance(sky))) return;
    const double solidAngle = cubeTexelSolidAngle(cube.size, column, row);
    const glm::dvec3 excess = glm::max(glm::dvec3(texel) - sky, glm::dvec3(0.0));
    texel = glm::vec3(glm::dvec3(texel) - excess);
    given += excess * solidAngle;
    weightedDirection += glm::dvec3(direction) * (luminance(excess) * solidAngle);
    result.solidAngle += solidAngle;
  });
  const double strongest = std::max({given.x, given.y, given.z});
  if (strongest > 0.0 && glm::length(weightedDirection) > 0.0) {
    const glm::vec3 color(given / strongest);
    result.sun = DirectionalLight{.direction = glm::vec3(glm::normalize(weightedDirection)),
                                  .color = color,
                                  .intensity = float(strongest),
                                  .discRadius = float(std::sqrt(result.solidAngle / std::numbers::pi)),
                                  .discRadiance = float(strongest / result.solidAngle)};
  }
  result.radiance = std::move(cube);
  return result;
}

}  // namespace mane::render
