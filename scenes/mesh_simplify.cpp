#include "scenes/mesh_simplify.hpp"

#include <string>
#include <vector>

#include <meshoptimizer.h>

namespace mane::scenes {
namespace {

// The elements of `values` that `remap` keeps, at their new places (meshoptimizer's remap:
// old index → new index, ~0u for a dropped vertex).
template <typename T>
std::vector<T> remapped(const std::vector<T>& values, const std::vector<unsigned int>& remap, std::size_t kept) {
  if (values.empty()) return {};
  std::vector<T> result(kept);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (remap[i] != ~0u) result[remap[i]] = values[i];
  return result;
}

}  // namespace

Result<SimplifiedMesh> simplifyMesh(const Mesh& mesh, const SimplifySettings& settings) {
  if (settings.targetTriangles == 0) return fail("simplifying to 0 triangles");
  if (!(settings.maxRelativeError > 0.0f && settings.maxRelativeError <= 1.0f))
    return fail("the simplification's error bound must be in (0, 1], got " + std::to_string(settings.maxRelativeError));
  const std::size_t vertices = mesh.positions.size();
  if ((!mesh.normals.empty() && mesh.normals.size() != vertices) || (!mesh.uvs.empty() && mesh.uvs.size() != vertices))
    return fail("simplifying: normals or uvs do not match the " + std::to_string(vertices) + " positions");
  if (mesh.indices.size() % 3 != 0) return fail("simplifying: the index count is not a multiple of 3");
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= vertices)
      return fail("simplifying: index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) + ", past the " +
                  std::to_string(vertices) + " vertices");

  const float* positions = vertices > 0 ? &mesh.positions[0].x : nullptr;
  constexpr std::size_t kStride = sizeof(glm::vec3);
  std::vector<unsigned int> indices(mesh.indices.begin(), mesh.indices.end());
  float relativeError = 0.0f;
  if (mesh.triangleCount() > settings.targetTriangles) {
    std::vector<unsigned int> simplified(indices.size());  // meshoptimizer's worst case: all of them
    simplified.resize(meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions, vertices, kStride,
                                       3 * settings.targetTriangles, settings.maxRelativeError, 0, &relativeError));
    indices = std::move(simplified);
  }

  // Drop the vertices no triangle uses any more, keeping the order of first use.
  std::vector<unsigned int> remap(vertices);
  const std::size_t kept = meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), vertices);
  SimplifiedMesh result;
  result.mesh.name = mesh.name;
  result.mesh.positions = remapped(mesh.positions, remap, kept);
  result.mesh.normals = remapped(mesh.normals, remap, kept);
  result.mesh.uvs = remapped(mesh.uvs, remap, kept);
  result.mesh.indices.resize(indices.size());
  for (std::size_t i = 0; i < indices.size(); ++i) result.mesh.indices[i] = remap[indices[i]];
  result.error = relativeError * (vertices > 0 ? meshopt_simplifyScale(positions, vertices, kStride) : 0.0f);
  return result;
}

}  // namespace mane::scenes
