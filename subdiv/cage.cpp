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

bool usableSharpness(float sharpness) {
  return std::isfinite(sharpness) && sharpness >= 0.0f;
}

CageProblem faceProblem(std::size_t face, std::string message) {
  return CageProblem{.message = std::move(message), .face = face, .crease = {}, .corner = {}};
}

}  // namespace

std::optional<CageProblem> findCageProblem(const Cage& cage) {
  for (std::size_t v = 0; v < cage.positions.size(); ++v) {
    const glm::vec3& p = cage.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return CageProblem{.message = "vertex " + std::to_string(v) + " has a non-finite position"};
  }
  for (std::size_t t = 0; t < cage.uvs.size(); ++t)
    if (!std::isfinite(cage.uvs[t].x) || !std::isfinite(cage.uvs[t].y))
      return CageProblem{.message = "texture coordinate " + std::to_string(t) + " is not finite"};
  if (cage.hasUvs() && cage.faceUvIndices.size() != cage.faceVertices.size())
    return CageProblem{.message = "the cage has " + std::to_string(cage.faceUvIndices.size()) +
                                  " face UV indices for " + std::to_string(cage.faceVertices.size()) +
                                  " face vertices; they must match one to one"};

  // Directed edge → number of faces that use it in that direction; undirected → face count.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> undirected;
  std::size_t offset = 0;
  for (std::size_t face = 0; face < cage.faceSizes.size(); ++face) {
    const std::uint32_t size = cage.faceSizes[face];
    const std::string faceName = "face " + std::to_string(face);
    if (size < 3)
      return faceProblem(face, faceName + " has " + std::to_string(size) + " vertices; at least 3 are needed");
    if (offset + size > cage.faceVertices.size())
      return faceProblem(face, faceName + " runs past the end of the face-vertex list");
    glm::vec3 areaVector(0.0f);
    for (std::uint32_t corner = 0; corner < size; ++corner) {
      const std::uint32_t a = cage.faceVertices[offset + corner];
      const std::uint32_t b = cage.faceVertices[offset + (corner + 1) % size];
      if (a >= cage.positions.size())
        return faceProblem(face, faceName + " uses vertex " + std::to_string(a) + " but the cage has " +
                                     std::to_string(cage.positions.size()) + " vertices");
      if (cage.hasUvs() && cage.faceUvIndices[offset + corner] >= cage.uvs.size())
        return faceProblem(face, faceName + " uses texture coordinate " +
                                     std::to_string(cage.faceUvIndices[offset + corner]) + " but the cage has " +
                                     std::to_string(cage.uvs.size()));
      for (std::uint32_t other = corner + 1; other < size; ++other)
        if (cage.faceVertices[offset + other] == a)
          return faceProblem(face, faceName + " uses vertex " + std::to_string(a) + " twice");
      if (b < cage.positions.size()) areaVector += glm::cross(cage.positions[a], cage.positions[b]);
      if (++undirected[{std::min(a, b), std::max(a, b)}] > 2)
        return faceProblem(face, edgeName(std::min(a, b), std::max(a, b)) +
                                     " is shared by more than two faces (non-manifold), the third being " + faceName);
      if (++directed[{a, b}] > 1)
        return faceProblem(face, edgeName(a, b) +
                                     " is traversed in the same direction by two faces (inconsistent winding), "
                                     "the second being " +
                                     faceName);
    }
    // Newell's area vector of the polygon: zero for a degenerate face.
    if (glm::length(areaVector) <= 0.0f) return faceProblem(face, faceName + " has zero area");
    offset += size;
  }
  if (offset != cage.faceVertices.size())
    return CageProblem{.message = "the face-vertex list holds " + std::to_string(cage.faceVertices.size()) +
                                  " indices but the faces use " + std::to_string(offset)};
  for (std::size_t c = 0; c < cage.creases.size(); ++c) {
    const Crease& crease = cage.creases[c];
    if (!undirected.contains({std::min(crease.a, crease.b), std::max(crease.a, crease.b)}))
      return CageProblem{.message = "a crease names " + edgeName(crease.a, crease.b) + ", which no face has",
                         .crease = c};
    if (!usableSharpness(crease.sharpness))
      return CageProblem{.message = "the crease on " + edgeName(crease.a, crease.b) + " has sharpness " +
                                    std::to_string(crease.sharpness) + "; it must be finite and at least 0",
                         .crease = c};
  }
  for (std::size_t c = 0; c < cage.corners.size(); ++c) {
    const Corner& corner = cage.corners[c];
    if (corner.vertex >= cage.positions.size())
      return CageProblem{.message = "a corner names vertex " + std::to_string(corner.vertex) + " but the cage has " +
                                    std::to_string(cage.positions.size()) + " vertices",
                         .corner = c};
    if (!usableSharpness(corner.sharpness))
      return CageProblem{.message = "the corner at vertex " + std::to_string(corner.vertex) + " has sharpness " +
                                    std::to_string(corner.sharpness) + "; it must be finite and at least 0",
                         .corner = c};
  }
  return std::nullopt;
}

Result<void> validateCage(const Cage& cage) {
  if (auto problem = findCageProblem(cage)) return fail(problem->message);
  return {};
}

}  // namespace mane::subdiv
