#pragma once
// A scene mesh drawn as its Catmull-Clark limit surface (issue 6, items 4–5): the mesh's
// polygons become a subdivision cage, and the limit surface is tessellated for one camera
// (Bunnell's screen-space error, subdiv/tessellator.hpp) into the triangles the renderer draws.

#include <cstddef>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "common/error.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"
#include "subdiv/cage.hpp"

namespace mane::scenes {

/// A triangle mesh as a cage: vertices with bit-identical positions become one cage vertex
/// (files and the procedural meshes split them at UV seams and poles), the mesh's per-vertex
/// UVs become face-varying UVs, and triangles that collapse once welded are dropped.
[[nodiscard]] subdiv::Cage cageFromTriangles(const Mesh& mesh);

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

/// Builds the limit surface of `cage` (isolation `subdivision.isolation`, Gregory end caps) and
/// tessellates it so that no triangle strays more than `subdivision.maxPixelError` pixels from
/// it as seen through `modelViewProjection` (model units → clip space) on a `viewport`-pixel
/// image. Errors: what validateCage or OpenSubdiv say about the cage.
[[nodiscard]] Result<SubdividedMesh> tessellateForCamera(const subdiv::Cage& cage, const Subdivision& subdivision,
                                                         const glm::mat4& modelViewProjection, glm::vec2 viewport);

}  // namespace mane::scenes
