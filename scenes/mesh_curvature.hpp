#pragma once
// Per-vertex curvature of a triangle mesh (Meyer, Desbrun, Schröder & Barr 2003, "Discrete
// Differential-Geometry Operators for Triangulated 2-Manifolds"), and the curvature input of
// Penner's pre-integrated skin: a per-vertex 1/r and its lookup-table coordinate.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/error.hpp"
#include "scenes/mesh.hpp"

namespace mane::scenes {

/// Why a vertex has no curvature of its own (its values are 0). Bits of `VertexCurvature::flags`.
enum CurvatureFlag : std::uint8_t {
  kCurvatureBoundary = 1,     ///< on an edge that only one (kept) triangle uses: the one-ring is open
  kCurvatureNonManifold = 2,  ///< on an edge used by 3+ triangles, or its triangles form 2+ fans
  kCurvatureDegenerate = 4,   ///< uses a skipped zero-area triangle (see `computeVertexCurvature`)
  kCurvatureUnused = 8,       ///< no triangle uses it
};

/// How `computeVertexCurvature` reads the mesh.
struct CurvatureSettings {
  /// Vertices closer together than this fraction of the bounds' diagonal are one surface
  /// point. glTF and OBJ exports split vertices along UV and normal seams; without welding,
  /// every seam would read as a boundary. 0 welds only bit-identical positions.
  float relativeWeldTolerance = 1e-6f;
};

/// Curvatures per vertex of the mesh they were computed from, structure-of-arrays, all in
/// the mesh's length unit (1/unit, 1/unit²). Signs follow the vertex normal: H > 0 where the
/// surface bends away from its normal (a sphere with outward normals has H = 1/R). Vertices
/// with a non-zero `flags` entry have 0 in every value.
struct VertexCurvature {
  std::vector<float> meanCurvature;      ///< H, 1/unit
  std::vector<float> gaussianCurvature;  ///< K, 1/unit²
  std::vector<float> maxCurvature;       ///< κ1 = H + sqrt(max(H² − K, 0)), 1/unit
  std::vector<float> minCurvature;       ///< κ2 = H − sqrt(max(H² − K, 0)), 1/unit
  std::vector<float> mixedArea;          ///< Meyer's A_mixed (the vertex's share of the surface), unit²
  std::vector<std::uint8_t> flags;       ///< `CurvatureFlag` bits; 0 = valid
  /// The lowest-numbered vertex at this one's (welded) position: vertices with the same
  /// entry are one surface point and carry the same values.
  std::vector<std::uint32_t> weldedVertex;
  std::size_t skippedTriangles = 0;  ///< zero-area triangles left out

  [[nodiscard]] std::size_t vertexCount() const { return meanCurvature.size(); }
};

/// Mean curvature from the cotangent Laplace–Beltrami operator,
///   2·H·n = 1/(2·A_mixed) · Σ_j (cot α_ij + cot β_ij) (x_i − x_j)        (Meyer eq. 8)
/// with H = |that vector| / 2 signed by the vertex normal (the mesh's normals summed over
/// welded copies; area-weighted face normals when the mesh has none); Gaussian curvature
/// from the angle deficit K = (2π − Σ θ_j) / A_mixed (Meyer eq. 9); A_mixed is the Voronoi
/// area for non-obtuse triangles and area/2 (at the obtuse corner) or area/4 (elsewhere)
/// for obtuse ones (Meyer fig. 4). Principal curvatures κ1,2 = H ± sqrt(max(H² − K, 0)).
///
/// Boundary, non-manifold and unused vertices get 0 and a flag: these operators assume a
/// closed one-ring, and a guess from half a ring is worse than an honest "unknown" that
/// `skinInverseRadius` fills from the neighbours. Zero-area triangles (doubled indices,
/// collinear corners: twice the area ≤ 1e-10 × longest edge²) are skipped: their cotangents
/// are undefined. They count in `skippedTriangles`; their vertices are flagged degenerate.
///
/// Errors (naming the triangle or vertex): an index count that is not a multiple of 3, an
/// index past the vertex count, a non-finite position that a triangle uses, or a normal
/// count that differs from the position count. Double precision inside; O(n log n).
[[nodiscard]] Result<VertexCurvature> computeVertexCurvature(const Mesh& mesh, const CurvatureSettings& settings = {});

/// Which curvature magnitude stands for 1/r in the skin lookup.
enum class SkinCurvatureMeasure {
  /// |H|: the average of the normal curvature over all tangent directions (Euler's
  /// theorem), i.e. the expected curvature across a light direction not known in advance;
  /// exactly 1/r on the sphere Penner's LUT is integrated for; linear in the cotangent
  /// Laplacian, so less noisy than κ1,2 (which go through sqrt(H² − K)). Half the ridge
  /// curvature on a cylinder, about 0 on saddles.
  meanAbsolute,
  /// max(|κ1|, |κ2|): the tightest bend; the full 1/r across ridges (nose bridge, ear rims,
  /// lips) and on saddles, at the price of more noise and of overstating the bend for light
  /// running along a ridge.
  maxPrincipalAbsolute,
};

/// How `skinInverseRadius` turns curvature into the skin shader's 1/r.
struct SkinCurvatureSettings {
  SkinCurvatureMeasure measure = SkinCurvatureMeasure::meanAbsolute;
  /// Passes of one-ring averaging (each vertex becomes the mean of itself and its welded
  /// neighbours). Scanned meshes are noisy; each pass widens the footprint by one ring.
  int smoothingPasses = 2;
};

/// Per-vertex 1/r ≥ 0 in 1/unit for the pre-integrated skin LUT. Flagged vertices first take
/// the mean of their already-known one-ring neighbours, repeated outward until every vertex
/// connected to a valid one has a value (others stay 0); then the smoothing passes run.
/// Errors when `curvature` was not computed from a mesh with this vertex count.
[[nodiscard]] Result<std::vector<float>> skinInverseRadius(const Mesh& mesh, const VertexCurvature& curvature,
                                                           const SkinCurvatureSettings& settings = {});

/// The 1/r axis of the skin LUT. On the LeePerrySmith head at 25 mm per unit (|H|, 2 passes;
/// tests/scenes/mesh_curvature_tests.cpp prints the table) half the skin area is below
/// 0.022 mm⁻¹ and 99 % below 0.38 mm⁻¹; per vertex (the scan is densest at eyes, nostrils
/// and ears) 95 % lie below 0.96 mm⁻¹: [0, 1] mm⁻¹ clamps only creases with r < 1 mm.
struct SkinLutCurvatureRange {
  float millimetresPerUnit = 1000.0f;  ///< world scale: mesh unit in mm (nalu.json's head: 25)
  float minInverseRadius = 0.0f;       ///< 1/mm at LUT coordinate 0
  float maxInverseRadius = 1.0f;       ///< 1/mm at LUT coordinate 1; > `minInverseRadius`
};

/// 1/r in 1/mm from a curvature in 1/unit.
[[nodiscard]] inline float inverseRadiusPerMillimetre(float inverseRadiusPerUnit, float millimetresPerUnit) {
  return inverseRadiusPerUnit / millimetresPerUnit;
}

/// The LUT's 1/r coordinate in [0, 1]: linear in 1/r over the range, clamped at both ends.
[[nodiscard]] float skinLutCoordinate(float inverseRadiusPerUnit, const SkinLutCurvatureRange& range);

}  // namespace mane::scenes
