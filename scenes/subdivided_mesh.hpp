#pragma once
// A scene mesh drawn as its Catmull-Clark limit surface: the mesh's
// polygons become a subdivision cage, and the limit surface is tessellated for one camera
// (Bunnell's screen-space error, subdiv/tessellator.hpp) into the triangles the renderer draws.

#include <cstddef>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "common/error.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"
#include "subdiv/cage.hpp"
#include "subdiv/limit.hpp"
#include "subdiv/tessellator.hpp"

namespace mane::scenes {

/// A triangle mesh as a cage: vertices with bit-identical positions become one cage vertex
/// (files and the procedural meshes split them at UV seams and poles), the mesh's per-vertex
/// UVs become face-varying UVs, and triangles that collapse once welded are dropped.
[[nodiscard]] subdiv::Cage cageFromTriangles(const Mesh& mesh);

/// What coarseCageFromTriangles made.
struct CoarseCage {
  subdiv::Cage cage;
  std::size_t quads = 0;      ///< faces made by pairing two triangles
  std::size_t triangles = 0;  ///< triangles left unpaired
};

/// A quad-dominant cage for a dense triangle mesh (a scan), in two repeatable steps:
/// simplifyMesh to `simplification` (meshoptimizer's quadric edge collapse, uv seams kept), then
/// cageFromTriangles and pairTrianglesIntoQuads (subdiv/quad_pairing.hpp). The cage's vertices
/// stay on the scan; the limit surface, an average of them, lies slightly inside where the scan
/// is convex. (Moving the vertices until the limit surface interpolates them would not help: it
/// amplifies the simplified mesh's small-scale noise into ridges between the vertices.)
/// Errors: the simplifier's.
[[nodiscard]] Result<CoarseCage> coarseCageFromTriangles(const Mesh& mesh, const MeshSimplification& simplification);

/// Turns a cage's UVs from OBJ's convention (v up from the bottom) to `Mesh`'s (glTF: v down).
void flipCageUvsToTopLeft(subdiv::Cage& cage);

/// Closes every hole of `cage` with one polygon per boundary loop (wound to match its
/// neighbours), its edges infinitely sharp creases so that the rim keeps the edge the open
/// cage's boundary had: the OpenSubdiv chess pieces are open at their flat bases, and the
/// voxelized thickness table needs closed meshes. A loop through a vertex with more than one
/// boundary edge out is left open. Cap corners share one new UV (0, 0) when the cage has UVs.
/// Returns the number of loops closed.
std::size_t capBoundaryLoops(subdiv::Cage& cage);

/// The tessellated limit surface, in the cage's (model) units.
struct SubdividedMesh {
  /// Limit positions, unit limit normals (∂u × ∂v), the cage's UVs on the limit surface; split
  /// at UV seams like a loaded file (equal positions and normals on both sides).
  Mesh mesh;
  /// Per vertex, the skin shader's 1/r ≥ 0 in 1/unit: |H|, the limit surface's mean curvature
  /// from its second derivatives — `SkinCurvatureMeasure::meanAbsolute` without the smoothing
  /// passes a triangle mesh's discrete estimate needs, since the limit surface is smooth.
  std::vector<float> inverseRadius;
  std::size_t cageFaces = 0;
  std::size_t ptexFaces = 0;
};

/// A mesh's limit surface and its tessellator, built once from the cage and kept, so that the
/// mesh can be tessellated again whenever the camera (or the mesh's placement) changes without
/// refining the cage again. Neither copied nor moved (the tessellator points at the surface):
/// held by `std::unique_ptr`.
class SubdividedSurface {
public:
  /// Builds the limit surface of `cage` (isolation `subdivision.isolation`, Gregory end caps)
  /// and its tessellator (`subdivision.maxPixelError`, `maxDepth`). Errors: what validateCage
  /// or OpenSubdiv say about the cage.
  [[nodiscard]] static Result<std::unique_ptr<SubdividedSurface>> create(const subdiv::Cage& cage,
                                                                         const Subdivision& subdivision);

  SubdividedSurface(const SubdividedSurface&) = delete;
  SubdividedSurface& operator=(const SubdividedSurface&) = delete;

  /// Tessellates the surface so that no triangle strays more than the target number of pixels
  /// from it as seen through `modelViewProjection` (model units → clip space) on a
  /// `viewport`-pixel image, and writes the result into `mesh` (positions, normals, UVs,
  /// triangles; its name is kept) and `inverseRadius` (as SubdividedMesh's). Returns whether
  /// they changed: a view in which the last triangles still keep within the target
  /// (AdaptiveTessellator::keepsTarget: the mesh turned, or the camera moved a little) costs
  /// almost nothing and changes nothing, and the next triangles are prepared on a thread of
  /// their own before these stop keeping within it (AdaptiveTessellator::update). `threads` ≥ 1
  /// workers (0 counts as 1); the triangles do not depend on it.
  bool tessellate(const glm::mat4& modelViewProjection, glm::vec2 viewport, Mesh& mesh,
                  std::vector<float>& inverseRadius, unsigned threads);

  [[nodiscard]] const subdiv::LimitSurface& limit() const { return surface_; }
  /// What the last tessellation did (cells, evaluations).
  [[nodiscard]] const subdiv::TessellationStatistics& statistics() const { return tessellator_->statistics(); }

private:
  explicit SubdividedSurface(subdiv::LimitSurface surface) : surface_(std::move(surface)) {}

  subdiv::LimitSurface surface_;
  std::unique_ptr<subdiv::AdaptiveTessellator> tessellator_;
  subdiv::TessellatedMesh scratch_;  ///< reused storage of the last tessellation
};

/// Builds the limit surface of `cage` (isolation `subdivision.isolation`, Gregory end caps) and
/// tessellates it so that no triangle strays more than `subdivision.maxPixelError` pixels from
/// it as seen through `modelViewProjection` (model units → clip space) on a `viewport`-pixel
/// image. Errors: what validateCage or OpenSubdiv say about the cage.
[[nodiscard]] Result<SubdividedMesh> tessellateForCamera(const subdiv::Cage& cage, const Subdivision& subdivision,
                                                         const glm::mat4& modelViewProjection, glm::vec2 viewport);

}  // namespace mane::scenes
