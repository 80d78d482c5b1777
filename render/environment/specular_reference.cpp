#include "render/environment/specular_reference.hpp"

#include <numbers>

#include <glm/geometric.hpp>

namespace mane::render {

double ggxDistribution(double cosine, double roughness) {
  const double alpha2 = roughness * roughness * roughness * roughness;
  const double d = cosine * cosine * (alpha2 - 1.0) + 1.0;
  return alpha2 / (std::numbers::pi * d * d);
}

glm::vec3 prefilteredRadianceReference(const CubeMap& source, glm::vec3 direction, float roughness) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(direction));
  glm::dvec3 sum(0.0);
  double weights = 0.0;
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < source.size; ++row)
      for (int column = 0; column < source.size; ++column) {
        const glm::dvec3 l = glm::dvec3(cubeDirection(
            face, {(float(column) + 0.5f) / float(source.size), (float(row) + 0.5f) / float(source.size)}));
        const double cosine = glm::dot(n, l);
        if (cosine <= 0.0) continue;
        const glm::dvec3 h = glm::normalize(n + l);
        const double weight =
            ggxDistribution(glm::dot(n, h), roughness) * cosine * cubeTexelSolidAngle(source.size, column, row);
        sum += glm::dvec3(source.at(face, column, row)) * weight;
        weights += weight;
      }
  return glm::vec3(sum / weights);
}

}  // namespace mane::render
