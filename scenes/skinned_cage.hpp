#pragma once
// A Catmull-Clark cage that a skeleton bends, drawn as its limit surface: each pose morphs and
// skins the cage's vertices on the CPU (physics::SkinnedMesh, the cage's vertices being the
// skinned vertices), moves the limit surface onto them (LimitSurface::updatePositions) and
// tessellates it again for the view (Bunnell's screen-space error, subdiv/tessellator.hpp), so
// that a bending elbow gets the triangles its new curvature needs and loses them when it
// straightens.
//
// When to tessellate again. The tessellator can keep its triangles and only move their vertices
// (updateVertices), and can tell whether kept triangles still meet the target after the camera
// moved (keepsTarget), but it does not measure a change of shape: a bend raises the curvature at
// the elbow, so the straight pose's cells there miss the target, and a straightening leaves
// cells finer than needed. Measuring would mean evaluating the moved surface at every kept
// cell's midpoints, which is the work tessellate's refinement does anyway, and would still not
// find the cells that became too fine. So a pose that moved any cage vertex is always followed
// by a full tessellation; a pose that left the cage where it was (a held frame) keeps the
// triangles while keepsTarget holds for the new view. The triangles then depend on the pose and
// the view alone, never on the poses before: going back to a pose gives its mesh again.
//
// Deterministic: the same cage, skin, pose and view give the same mesh, bit for bit, whatever
// the thread count (skinning is single-threaded; the limit update and tessellation do not
// depend on it).

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "common/error.hpp"
#include "physics/skinning.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"
#include "subdiv/cage.hpp"
#include "subdiv/limit.hpp"
#include "subdiv/tessellator.hpp"

namespace mane::scenes {

/// What a SkinnedCage keeps beyond what a scene's `subdivision` block says.
struct SkinnedCageOptions {
  /// Keep each triangle's ptex face and its corners' ptex (u, v) (tessellation()), so that a
  /// test or tool can evaluate the limit surface under them; off for rendering.
  bool keepPtexCoordinates = false;
};

/// A skinned, morphing Catmull-Clark cage and its view-dependent tessellation. Neither copied
/// nor moved (the tessellator points at the limit surface): held by `std::unique_ptr`.
class SkinnedCage {
public:
  /// Builds the skin of `cage`'s vertices and the limit surface of its bind pose (isolation
  /// `subdivision.isolation`, Gregory end caps, holes closed with `capHoles`) with its
  /// tessellator (`maxPixelError`, `maxDepth`); `coarseCage` does not apply to a given cage. `skinning` describes the
  /// cage's vertices, in the cage's order: its joint influences, joint count, morph targets (position deltas only) and
  /// method. Its `positions` are either empty (the cage's positions are the bind pose) or the bind pose itself, one per
  /// cage vertex, which then replaces the cage's positions. Its normals, tangents, triangles and
  /// the targets' normal and tangent deltas are dropped: the limit surface has normals of its
  /// own. Errors, each prefixed "skinned cage: ": a vertex count that does not match the cage's,
  /// what physics::SkinnedMesh::create says about the skin, and what validateCage or OpenSubdiv
  /// say about the cage.
  [[nodiscard]] static Result<std::unique_ptr<SkinnedCage>> create(subdiv::Cage cage, physics::SkinnedMeshData skinning,
                                                                   const Subdivision& subdivision,
                                                                   const SkinnedCageOptions& options = {});

  SkinnedCage(const SkinnedCage&) = delete;
  SkinnedCage& operator=(const SkinnedCage&) = delete;

  /// Morphs the bind pose by `morphWeights` (one per morph target) and skins it by
  /// `jointMatrices` (one per joint: the joint's world matrix times its inverse bind matrix, in
  /// the cage's space, metres), then moves the limit surface there on `threads` ≥ 1 workers
  /// (0 counts as 1). Returns whether any cage vertex moved, which makes the next tessellate
  /// call tessellate again. Errors (the surface is then left as it was): what
  /// physics::SkinnedMesh::deform says (a wrong count of matrices or weights, a non-finite
  /// value, a mirroring joint under DQS), and a non-finite skinned position.
  [[nodiscard]] Result<bool> pose(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights,
                                  unsigned threads);

  /// Tessellates the posed limit surface so that no triangle strays more than the target number
  /// of pixels from it as seen through `modelViewProjection` (cage space → clip space) on a
  /// `viewport`-pixel image, and writes it into `mesh` (positions, limit normals, the cage's UVs,
  /// triangles; its name is kept) and `inverseRadius` (per vertex |H|, the limit surface's mean
  /// curvature in 1/metre, for the skin shader). Returns whether they were written: always after
  /// a pose that moved the cage (see the header comment) or on the first call; otherwise only
  /// when the last triangles no longer keep within the target for this view
  /// (AdaptiveTessellator::keepsTarget). `threads` ≥ 1 workers (0 counts as 1); the mesh does
  /// not depend on it.
  bool tessellate(const glm::mat4& modelViewProjection, glm::vec2 viewport, Mesh& mesh,
                  std::vector<float>& inverseRadius, unsigned threads);

  /// The skin as created (renormalised weights, the bind pose as its positions).
  [[nodiscard]] const physics::SkinnedMesh& skin() const { return skin_; }
  /// The limit surface as last posed; its cage holds the posed positions.
  [[nodiscard]] const subdiv::LimitSurface& limit() const { return surface_; }
  /// The last tessellation as the tessellator made it (ptex coordinates with
  /// SkinnedCageOptions::keepPtexCoordinates).
  [[nodiscard]] const subdiv::TessellatedMesh& tessellation() const { return tessellation_; }
  /// What the last tessellation did (cells, evaluations).
  [[nodiscard]] const subdiv::TessellationStatistics& statistics() const { return tessellator_->statistics(); }

private:
  SkinnedCage(physics::SkinnedMesh skin, subdiv::LimitSurface surface)
      : skin_(std::move(skin)), surface_(std::move(surface)) {}

  physics::SkinnedMesh skin_;
  subdiv::LimitSurface surface_;
  std::unique_ptr<subdiv::AdaptiveTessellator> tessellator_;
  physics::DeformedSurface posed_;  ///< reused storage of the skinned cage positions
  subdiv::TessellatedMesh tessellation_;
  bool shapeChanged_ = true;  ///< the cage moved since the last tessellation (or there is none)
};

}  // namespace mane::scenes
