#include "scenes/mesh.hpp"

#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace mane::scenes {

Bounds Mesh::bounds() const {
  Bounds box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  for (const glm::vec3& p : positions) {
    box.min = glm::min(box.min, p);
    box.max = glm::max(box.max, p);
  }
  return box;
}

void computeSmoothNormals(Mesh& mesh) {
  std::vector<glm::vec3> sums(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t];
    const std::uint32_t b = mesh.indices[t + 1];
    const std::uint32_t c = mesh.indices[t + 2];
    // The cross product's length is twice the triangle's area: that is the weighting.
    const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    sums[a] += n;
    sums[b] += n;
    sums[c] += n;
  }
  for (glm::vec3& n : sums) {
    const float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  mesh.normals = std::move(sums);
}

std::string validate(const Mesh& mesh) {
  if (mesh.indices.size() % 3 != 0) {
    return "index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3";
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    return "has " + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(mesh.positions.size()) +
           " positions";
  }
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
    return "has " + std::to_string(mesh.uvs.size()) + " texture coordinates for " +
           std::to_string(mesh.positions.size()) + " positions";
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= mesh.positions.size()) {
      return "index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) + " but there are only " +
             std::to_string(mesh.positions.size()) + " positions";
    }
  }
  return {};
}

void boxProjectUvs(Mesh& mesh, float uvPerUnit) {
  mesh.uvs.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = mesh.positions[i] * uvPerUnit;
    const glm::vec3 n = glm::abs(mesh.normals[i]);
    mesh.uvs[i] = n.x >= n.y && n.x >= n.z ? glm::vec2(p.z, p.y)
                  : n.y >= n.z             ? glm::vec2(p.x, p.z)
                                           : glm::vec2(p.x, p.y);
  }
}

}  // namespace mane::scenes
