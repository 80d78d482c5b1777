#include "physics/cloth_wind.hpp"

#include <cmath>
#include <string>

#include "physics/detail/hair_math.hpp"

namespace mane::physics {
namespace {

float dot(const glm::vec3& a, const glm::vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

}  // namespace

Result<ClothWindLoad> ClothWindLoad::create(const ClothWind& wind, std::span<const std::uint32_t> triangles,
                                            std::span<const glm::vec3> rest) {
  if (!detail::isFinite(wind.velocity)) return fail("ClothSettings.wind.velocity must be finite");
  if (!(std::isfinite(wind.arealDensity) && wind.arealDensity > 0.0f))
    return fail("ClothSettings.wind.arealDensity must be positive (kg/m²), got " + std::to_string(wind.arealDensity));
  if (!(std::isfinite(wind.dragCoefficient) && wind.dragCoefficient >= 0.0f))
    return fail("ClothSettings.wind.dragCoefficient must be ≥ 0, got " + std::to_string(wind.dragCoefficient));
  ClothWindLoad load;
  load.wind_ = wind;
  load.triangles_.assign(triangles.begin(), triangles.end());
  const std::size_t vertices = rest.size();
  std::vector<float> mass(vertices, 0.0f);
  load.vertexTriangleStarts_.assign(vertices + 1, 0);
  for (std::uint32_t v : triangles) ++load.vertexTriangleStarts_[v + 1];
  for (std::size_t v = 0; v < vertices; ++v) load.vertexTriangleStarts_[v + 1] += load.vertexTriangleStarts_[v];
  load.vertexTriangles_.resize(triangles.size());
  std::vector<std::uint32_t> filled(load.vertexTriangleStarts_.begin(), load.vertexTriangleStarts_.end() - 1);
  for (std::size_t t = 0; t < triangles.size() / 3; ++t) {
    const std::uint32_t* corner = &triangles[3 * t];
    const float area =
        0.5f * std::sqrt(dot(detail::cross(rest[corner[1]] - rest[corner[0]], rest[corner[2]] - rest[corner[0]]),
                             detail::cross(rest[corner[1]] - rest[corner[0]], rest[corner[2]] - rest[corner[0]])));
    for (int i = 0; i < 3; ++i) {
      mass[corner[i]] += wind.arealDensity * area / 3.0f;
      load.vertexTriangles_[filled[corner[i]]++] = static_cast<std::uint32_t>(t);
    }
  }
  load.inverseMass_.resize(vertices);
  for (std::size_t v = 0; v < vertices; ++v) load.inverseMass_[v] = mass[v] > 0.0f ? 1.0f / mass[v] : 0.0f;
  load.cornerForce_.assign(triangles.size() / 3, glm::vec3(0.0f));
  return load;
}

Result<void> ClothWindLoad::setVelocity(const glm::vec3& velocity) {
  if (!detail::isFinite(velocity)) return fail("cloth wind: the velocity must be finite");
  wind_.velocity = velocity;
  return {};
}

void ClothWindLoad::computeForces(std::span<const glm::vec3> positions, std::span<const glm::vec3> previous, float step,
                                  std::size_t first, std::size_t end) {
  const float pressure = 0.5f * kClothAirDensity * wind_.dragCoefficient;
  for (std::size_t t = first; t < end; ++t) {
    const std::uint32_t a = triangles_[3 * t], b = triangles_[3 * t + 1], c = triangles_[3 * t + 2];
    const glm::vec3 moved = (positions[a] - previous[a]) + (positions[b] - previous[b]) + (positions[c] - previous[c]);
    const glm::vec3 air = wind_.velocity - moved / (3.0f * step);
    // |cross| = 2A: the area-weighted normal.
    const glm::vec3 doubleAreaNormal = detail::cross(positions[b] - positions[a], positions[c] - positions[a]);
    const float doubleArea = std::sqrt(dot(doubleAreaNormal, doubleAreaNormal));
    if (doubleArea <= 0.0f) {
      cornerForce_[t] = glm::vec3(0.0f);
      continue;
    }
    const glm::vec3 normal = doubleAreaNormal / doubleArea;
    const float across = dot(air, normal);
    // ½ ρ C A (u·n)|u·n| n, a third per corner: A/3 = doubleArea/6.
    cornerForce_[t] = (pressure * doubleArea / 6.0f * across * std::abs(across)) * normal;
  }
}

glm::vec3 ClothWindLoad::acceleration(std::uint32_t v) const {
  glm::vec3 force(0.0f);
  for (std::uint32_t i = vertexTriangleStarts_[v]; i < vertexTriangleStarts_[v + 1]; ++i)
    force += cornerForce_[vertexTriangles_[i]];
  return force * inverseMass_[v];
}

WindPush ClothWindLoad::total(std::span<const glm::vec3> positions, const glm::vec3& about) const {
  WindPush push;
  for (std::size_t t = 0; t < cornerForce_.size(); ++t) {
    const std::uint32_t a = triangles_[3 * t], b = triangles_[3 * t + 1], c = triangles_[3 * t + 2];
    const glm::vec3 force = 3.0f * cornerForce_[t];
    const glm::vec3 centroid = (positions[a] + positions[b] + positions[c]) / 3.0f;
    push.force += force;
    push.moment += detail::cross(centroid - about, force);
  }
  return push;
}

}  // namespace mane::physics
