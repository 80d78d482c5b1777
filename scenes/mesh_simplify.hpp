#pragma once
// Fewer triangles for a mesh drawn small: meshoptimizer's edge-collapse simplifier
// (meshopt_simplify, quadric error, topology kept; vertices that share a position across a uv
// seam collapse only along the seam), then the vertices no triangle uses are dropped. A level of
// detail for scene meshes (`MeshInstance::simplify`): the fur shells draw their mesh 15 times, and
// nalu's bunny, 69,451 triangles over about 150 × 150 pixels, is far finer than its pixels.

#include <cstddef>

#include "common/error.hpp"
#include "scenes/mesh.hpp"

namespace mane::scenes {

struct SimplifySettings {
  std::size_t targetTriangles = 0;  ///< at most this many triangles, ≥ 1
  /// Largest deviation allowed, as a fraction of the mesh's extent (meshopt_simplifyScale: its
  /// largest bounding-box side); the simplifier stops short of `targetTriangles` rather than
  /// exceed it. In (0, 1].
  float maxRelativeError = 0.01f;
};

/// What the simplification did.
struct SimplifiedMesh {
  Mesh mesh;  ///< surviving vertices keep their position, normal and uv; the name is kept
  /// The deviation meshoptimizer reached, metres (or the mesh's units): its relative error × the extent.
  float error = 0.0f;
};

/// `mesh` with at most `settings.targetTriangles` triangles where the error bound allows; a
/// mesh already at or under the target comes back as it is (unused vertices dropped). Errors
/// (the caller names the mesh): a target of 0, an error bound outside (0, 1], attribute arrays
/// whose sizes do not match the positions, or an index out of range.
[[nodiscard]] Result<SimplifiedMesh> simplifyMesh(const Mesh& mesh, const SimplifySettings& settings);

}  // namespace mane::scenes
