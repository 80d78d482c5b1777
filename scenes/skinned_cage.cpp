#include "scenes/skinned_cage.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "scenes/subdivided_mesh.hpp"

namespace mane::scenes {
namespace {

constexpr const char* kPrefix = "skinned cage: ";

std::unexpected<Error> failWith(const Error& error) {
  return fail(kPrefix + error.message);
}

}  // namespace

Result<std::unique_ptr<SkinnedCage>> SkinnedCage::create(subdiv::Cage cage, physics::SkinnedMeshData skinning,
                                                         const Subdivision& subdivision,
                                                         const SkinnedCageOptions& options) {
  if (skinning.positions.empty()) {
    skinning.positions = cage.positions;
  } else if (skinning.positions.size() != cage.positions.size()) {
    return fail(std::string(kPrefix) + "the skin has " + std::to_string(skinning.positions.size()) +
                " bind positions; the cage has " + std::to_string(cage.positions.size()) + " vertices");
  } else {
    cage.positions = skinning.positions;
  }
  if (subdivision.capHoles) capBoundaryLoops(cage);  // new faces only: the skin's vertices stay the cage's
  // The limit surface derives its own normals; skinning the cage's would be wasted work.
  skinning.normals.clear();
  skinning.tangents.clear();
  skinning.indices.clear();
  for (physics::MorphTarget& target : skinning.morphTargets) {
    target.normalDeltas.clear();
    target.tangentDeltas.clear();
  }
  auto skin = physics::SkinnedMesh::create(std::move(skinning));
  if (!skin) return failWith(skin.error());
  auto surface = subdiv::LimitSurface::create(cage, {.maxIsolationLevel = subdivision.isolation});
  if (!surface) return failWith(surface.error());
  std::unique_ptr<SkinnedCage> result(new SkinnedCage(std::move(*skin), std::move(*surface)));
  auto tessellator =
      subdiv::AdaptiveTessellator::create(result->surface_, {.maxPixelError = subdivision.maxPixelError,
                                                             .maxDepth = subdivision.maxDepth,
                                                             .keepPtexCoordinates = options.keepPtexCoordinates});
  if (!tessellator) return failWith(tessellator.error());
  result->tessellator_ = std::make_unique<subdiv::AdaptiveTessellator>(std::move(*tessellator));
  return result;
}

Result<bool> SkinnedCage::pose(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights,
                               unsigned threads) {
  if (auto deformed = skin_.deform(jointMatrices, morphWeights, posed_, threads); !deformed) return failWith(deformed.error());
  const std::vector<glm::vec3>& current = surface_.cage().positions;
  // Exact equality: a held frame gives the same floats, and any other change is a new shape.
  if (std::equal(posed_.positions.begin(), posed_.positions.end(), current.begin(), current.end())) return false;
  if (auto moved = surface_.updatePositions(posed_.positions, threads); !moved) return failWith(moved.error());
  shapeChanged_ = true;
  return true;
}

bool SkinnedCage::tessellate(const glm::mat4& modelViewProjection, glm::vec2 viewport, Mesh& mesh,
                             std::vector<float>& inverseRadius, unsigned threads) {
  const subdiv::ScreenView view{modelViewProjection, viewport};
  // A still cage keeps its triangles while they meet the target in this view; a moved one is
  // tessellated again, since keepsTarget does not see the change of shape (header comment).
  if (!shapeChanged_ && tessellator_->keepsTarget(view)) return false;
  tessellator_->tessellate(view, tessellation_, threads);
  shapeChanged_ = false;
  mesh.positions.assign(tessellation_.positions.begin(), tessellation_.positions.end());
  mesh.normals.assign(tessellation_.normals.begin(), tessellation_.normals.end());
  mesh.uvs.assign(tessellation_.uvs.begin(), tessellation_.uvs.end());
  mesh.indices.assign(tessellation_.indices.begin(), tessellation_.indices.end());
  inverseRadius.resize(tessellation_.meanCurvature.size());
  std::transform(tessellation_.meanCurvature.begin(), tessellation_.meanCurvature.end(), inverseRadius.begin(),
                 [](float h) { return std::abs(h); });
  return true;
}

}  // namespace mane::scenes
