#include "scenes/subdivided_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <thread>
#include <tuple>

#include "scenes/mesh_simplify.hpp"
#include "subdiv/limit.hpp"
#include "subdiv/quad_pairing.hpp"
#include "subdiv/tessellator.hpp"

namespace mane::scenes {

subdiv::Cage cageFromTriangles(const Mesh& mesh) {
  subdiv::Cage cage;
  std::map<std::tuple<float, float, float>, std::uint32_t> welded;
  std::vector<std::uint32_t> remap;
  remap.reserve(mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) {
    const auto [it, inserted] = welded.try_emplace({p.x, p.y, p.z}, std::uint32_t(cage.positions.size()));
    if (inserted) cage.positions.push_back(p);
    remap.push_back(it->second);
  }
  const bool uvs = !mesh.uvs.empty();
  if (uvs) cage.uvs = mesh.uvs;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = remap[mesh.indices[t]], b = remap[mesh.indices[t + 1]], c = remap[mesh.indices[t + 2]];
    if (a == b || b == c || a == c) continue;
    cage.faceSizes.push_back(3);
    cage.faceVertices.insert(cage.faceVertices.end(), {a, b, c});
    if (uvs)
      cage.faceUvIndices.insert(cage.faceUvIndices.end(), {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]});
  }
  return cage;
}

Result<CoarseCage> coarseCageFromTriangles(const Mesh& mesh, const MeshSimplification& simplification) {
  auto simplified = simplifyMesh(mesh, {.targetTriangles = std::size_t(simplification.triangles),
                                        .maxRelativeError = simplification.maxRelativeError});
  if (!simplified) return fail("coarse cage: " + simplified.error().message);
  subdiv::QuadPairing paired = subdiv::pairTrianglesIntoQuads(cageFromTriangles(simplified->mesh));
  return CoarseCage{.cage = std::move(paired.cage), .quads = paired.quads, .triangles = paired.triangles};
}

void flipCageUvsToTopLeft(subdiv::Cage& cage) {
  for (glm::vec2& uv : cage.uvs) uv.y = 1.0f - uv.y;
}

std::size_t capBoundaryLoops(subdiv::Cage& cage) {
  // OpenSubdiv's sharpness at which a crease is infinitely sharp.
  constexpr float kInfinitelySharp = 10.0f;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::size_t offset = 0;
  for (const std::uint32_t size : cage.faceSizes) {
    for (std::uint32_t k = 0; k < size; ++k)
      ++directed[{cage.faceVertices[offset + k], cage.faceVertices[offset + (k + 1) % size]}];
    offset += size;
  }
  // A boundary edge a → b has no b → a; the cap runs b → a, so from b it goes on to a.
  std::map<std::uint32_t, std::uint32_t> capNext;
  std::map<std::uint32_t, int> outgoing;
  for (const auto& [edge, count] : directed)
    if (!directed.contains({edge.second, edge.first})) {
      capNext[edge.second] = edge.first;
      ++outgoing[edge.second];
    }
  std::size_t capped = 0;
  std::map<std::uint32_t, bool> visited;
  for (const auto& [start, unused] : capNext) {
    if (visited[start]) continue;
    std::vector<std::uint32_t> loop;
    bool usable = true;
    for (std::uint32_t v = start;;) {
      visited[v] = true;
      usable = usable && outgoing[v] == 1;
      loop.push_back(v);
      const auto next = capNext.find(v);
      if (next == capNext.end()) {
        usable = false;
        break;
      }
      v = next->second;
      if (v == start) break;
      if (visited[v] || loop.size() > capNext.size()) {
        usable = false;
        break;
      }
    }
    if (!usable || loop.size() < 3) continue;
    cage.faceSizes.push_back(std::uint32_t(loop.size()));
    cage.faceVertices.insert(cage.faceVertices.end(), loop.begin(), loop.end());
    if (cage.hasUvs()) {
      cage.uvs.emplace_back(0.0f);
      cage.faceUvIndices.insert(cage.faceUvIndices.end(), loop.size(), std::uint32_t(cage.uvs.size() - 1));
    }
    for (std::size_t k = 0; k < loop.size(); ++k)
      cage.creases.push_back({loop[k], loop[(k + 1) % loop.size()], kInfinitelySharp});
    ++capped;
  }
  return capped;
}

Result<std::unique_ptr<SubdividedSurface>> SubdividedSurface::create(const subdiv::Cage& cage,
                                                                     const Subdivision& subdivision) {
  auto surface = subdiv::LimitSurface::create(cage, {.maxIsolationLevel = subdivision.isolation});
  if (!surface) return std::unexpected(surface.error());
  std::unique_ptr<SubdividedSurface> result(new SubdividedSurface(std::move(*surface)));
  auto tessellator = subdiv::AdaptiveTessellator::create(
      result->surface_, {.maxPixelError = subdivision.maxPixelError, .maxDepth = subdivision.maxDepth});
  if (!tessellator) return std::unexpected(tessellator.error());
  result->tessellator_ = std::make_unique<subdiv::AdaptiveTessellator>(std::move(*tessellator));
  return result;
}

bool SubdividedSurface::tessellate(const glm::mat4& modelViewProjection, glm::vec2 viewport, Mesh& mesh,
                                   std::vector<float>& inverseRadius, unsigned threads) {
  const subdiv::ScreenView view{modelViewProjection, viewport};
  // The cage does not move here, so kept triangles keep their vertices too.
  const auto update = tessellator_->update(view, scratch_, threads);
  if (update && (*update == subdiv::FrameUpdate::kKept || *update == subdiv::FrameUpdate::kPrepared)) return false;
  if (!update) tessellator_->tessellate(view, scratch_, threads);  // scratch_ was not the last mesh: start anew
  mesh.positions.assign(scratch_.positions.begin(), scratch_.positions.end());
  mesh.normals.assign(scratch_.normals.begin(), scratch_.normals.end());
  mesh.uvs.assign(scratch_.uvs.begin(), scratch_.uvs.end());
  mesh.indices.assign(scratch_.indices.begin(), scratch_.indices.end());
  inverseRadius.resize(scratch_.meanCurvature.size());
  for (std::size_t v = 0; v < scratch_.meanCurvature.size(); ++v)
    inverseRadius[v] = std::abs(scratch_.meanCurvature[v]);
  return true;
}

Result<SubdividedMesh> tessellateForCamera(const subdiv::Cage& cage, const Subdivision& subdivision,
                                           const glm::mat4& modelViewProjection, glm::vec2 viewport) {
  auto surface = SubdividedSurface::create(cage, subdivision);
  if (!surface) return std::unexpected(surface.error());
  SubdividedMesh result;
  result.cageFaces = cage.faceSizes.size();
  result.ptexFaces = (*surface)->limit().ptexFaceCount();
  // Load time: use the machine; the mesh does not depend on the thread count.
  (*surface)->tessellate(modelViewProjection, viewport, result.mesh, result.inverseRadius,
                         std::max(1u, std::thread::hardware_concurrency()));
  return result;
}

}  // namespace mane::scenes
