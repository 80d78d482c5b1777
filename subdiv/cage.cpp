#include "subdiv/cage.hpp"

#include <cmath>
#include <map>
#include <string>

#include <glm/geometric.hpp>

namespace mane::subdiv {
namespace {

std::string edgeName(std::uint32_t a, std::uint32_t b) {
  return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

}  // namespace

Result<void> validateCage(const Cage& cage) {
  for (std::size_t v = 0; v < cage.positions.size(); ++v) {
    const glm::vec3& p = cage.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return fail("vertex " + std::to_string(v) + " has a non-finite position");
  }
  // Directed edge → number of faces that use it in that direction; undirected → face count.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> undirected;
  std::size_t offset = 0;
  for (std::size_t face = 0; face < cage.faceSizes.size(); ++face) {
    const std::uint32_t size = cage.faceSizes[face];
    const std::string faceName = "face " + std::to_string(face);
    if (size < 3) return fail(faceName + " has " + std::to_string(size) + " vertices; at least 3 are needed");
    if (offset + size > cage.faceVertices.size()) return fail(faceName + " runs past the end of the face-vertex list");
    glm::vec3 areaVector(0.0f);
    for (std::uint32_t corner = 0; corner < size; ++corner) {
      const std::uint32_t a = cage.faceVertices[offset + corner];
      const std::uint32_t b = cage.faceVertices[offset + (corner + 1) % size];
      if (a >= cage.positions.size())
        return fail(faceName + " uses vertex " + std::to_string(a) + " but the cage has " +
                    std::to_string(cage.positions.size()) + " vertices");
      for (std::uint32_t other = corner + 1; other < size; ++other)
        if (cage.faceVertices[offset + other] == a)
          return fail(faceName + " uses vertex " + std::to_string(a) + " twice");
      if (b < cage.positions.size()) areaVector += glm::cross(cage.positions[a], cage.positions[b]);
      if (++undirected[{std::min(a, b), std::max(a, b)}] > 2)
        return fail(edgeName(std::min(a, b), std::max(a, b)) +
                    " is shared by more than two faces (non-manifold), "
                    "the third being " +
                    faceName);
      if (++directed[{a, b}] > 1)
        return fail(edgeName(a, b) +
                    " is traversed in the same direction by two faces (inconsistent winding), "
                    "the second being " +
                    faceName);
    }
    // Newell's area vector of the polygon: zero for a degenerate face.
    if (glm::length(areaVector) <= 0.0f) return fail(faceName + " has zero area");
    offset += size;
  }
  if (offset != cage.faceVertices.size())
    return fail("the face-vertex list holds " + std::to_string(cage.faceVertices.size()) +
                " indices but the faces use " + std::to_string(offset));
  for (const Crease& crease : cage.creases)
    if (!undirected.contains({std::min(crease.a, crease.b), std::max(crease.a, crease.b)}))
      return fail("a crease names " + edgeName(crease.a, crease.b) + ", which no face has");
  return {};
}

}  // namespace mane::subdiv
