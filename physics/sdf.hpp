#pragma once
// A signed distance field (SDF) of a closed triangle mesh, sampled on a regular grid and built
// once on the CPU, for particle collisions against a head or body.
//
// Build (`SignedDistanceField::build`), after Bridson's SDFGen ("makelevelset3", 2015):
// 1. Narrow band: every triangle visits the grid nodes inside its bounding box grown by
//    `bandCells` cells and offers its exact distance (closest point on a triangle, Ericson 2005,
//    "Real-Time Collision Detection", §5.1.5). Each node keeps the nearest triangle. A node within
//    `bandCells` cells of the mesh therefore holds its exact unsigned distance.
// 2. Sign of the band nodes from angle-weighted pseudo-normals (Bærentzen & Aanæs 2005, "Signed
//    Distance Computation Using the Angle Weighted Pseudonormal", IEEE TVCG 11(3)): with c the
//    closest point on the mesh and n the pseudo-normal of the feature (face, edge or vertex) that
//    holds c, the point p is outside when (p − c)·n > 0. Exact for closed, manifold meshes.
// 3. Fast sweeping (Zhao 2005) in the 8 diagonal orders, twice: each node outside the band tries
//    its upwind neighbours' nearest triangles (exact distance to them) and takes the sign of the
//    neighbour it first learns from. No surface lies between a node outside the band and its
//    neighbour (the band is at least one cell thick), so the sign carried over is right; the
//    distance is the exact distance to a nearby triangle, an upper bound that is exact in
//    practice (Bridson 2015).
//
// Sampling is trilinear between nodes; the gradient is the analytic gradient of that trilinear
// interpolant. A distance function is 1-Lipschitz, so a trilinear sample is within √3·h of the
// exact signed distance to the mesh (h the cell size) — the resolution bound the tests use.
//
// Units: metres, in whatever frame the mesh was given (for a head: head-local space).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

/// How to grid a mesh's signed distance field.
struct SdfSettings {
  /// Grid nodes along the longest axis of the padded bounding box (≥ 4); the cells are cubes,
  /// so shorter axes get proportionally fewer nodes. 64 gives a 64³-class grid.
  int resolution = 64;
  /// Empty cells added around the mesh's bounding box on every side (≥ 1), so the outermost nodes
  /// are outside the mesh and samples near the surface never leave the grid.
  int paddingCells = 2;
  /// Half-width of the exactly computed narrow band, in cells (≥ 1).
  int bandCells = 2;
};

/// A signed distance field on a regular grid: negative inside the mesh, positive outside,
/// metres. Plain value type; immutable after `build`.
class SignedDistanceField {
public:
  /// Builds the field of the closed triangle mesh (`positions` in metres, `indices` three per
  /// triangle, counter-clockwise seen from outside). Fails, naming the triangle or vertex, when
  /// the mesh is empty, an index is out of range, the index count is not a multiple of 3, a
  /// position is NaN or infinite, every triangle is degenerate, or `settings` are out of range.
  /// Degenerate (zero-area) triangles are skipped: their edges belong to their neighbours.
  /// Orientation: faces must wind counter-clockwise seen from outside (glTF, OBJ convention).
  [[nodiscard]] static Result<SignedDistanceField> build(std::span<const glm::vec3> positions,
                                                         std::span<const std::uint32_t> indices,
                                                         const SdfSettings& settings = {});

  /// Signed distance at `p` (metres), trilinear between nodes. Outside the grid: the sample at
  /// the nearest grid point plus the distance to the grid box (positive, an upper bound).
  [[nodiscard]] float sample(const glm::vec3& p) const noexcept;

  /// Signed distance at `p` and the gradient of the trilinear interpolant there (|gradient| ≈ 1
  /// away from the medial axis; not normalised). Outside the grid the gradient points away from
  /// the box.
  [[nodiscard]] float sampleWithGradient(const glm::vec3& p, glm::vec3& gradient) const noexcept;

  /// True when `p` lies inside the grid box, where `sample` interpolates.
  [[nodiscard]] bool insideGrid(const glm::vec3& p) const noexcept;

  /// Position of node (0, 0, 0), metres.
  [[nodiscard]] const glm::vec3& origin() const noexcept { return origin_; }
  /// Edge length of a (cubic) cell, metres.
  [[nodiscard]] float cellSize() const noexcept { return cellSize_; }
  /// 1 / cellSize() as `sample` uses it, 1/metres.
  [[nodiscard]] float inverseCellSize() const noexcept { return inverseCellSize_; }
  /// Node counts along x, y, z.
  [[nodiscard]] const glm::ivec3& dimensions() const noexcept { return dims_; }
  /// Far corner of the grid box (the last node), metres.
  [[nodiscard]] glm::vec3 upperCorner() const noexcept;
  /// Node values, x fastest, then y, then z.
  [[nodiscard]] std::span<const float> values() const noexcept { return values_; }

  /// A box (metres) outside which `sample` is at least `contactLevel()`: it holds every cell
  /// with a node value below that level, grown by one cell so that rounding of the grid
  /// coordinates cannot move a point into such a cell. Empty (lower > upper) when no node is
  /// below the level; when such cells reach the grid's boundary there is no such box and
  /// `contactLevel()` is −∞.
  [[nodiscard]] const glm::vec3& contactLower() const noexcept { return contactLower_; }
  [[nodiscard]] const glm::vec3& contactUpper() const noexcept { return contactUpper_; }
  /// The level of the contact box: half a cell (or −∞, see above), metres.
  [[nodiscard]] float contactLevel() const noexcept { return contactLevel_; }
  /// One bit per cell, set when a node of the cell lies below `contactLevel()`: a sample
  /// elsewhere is a convex combination of nodes at or above that level. Bit n (word n / 32,
  /// bit n % 32) belongs to the cell whose lowest node is values()[n]. Empty when
  /// `contactLevel()` is −∞.
  [[nodiscard]] std::span<const std::uint32_t> contactCells() const noexcept { return contactCells_; }
  /// False only when `sample(p)` is certainly ≥ `level`: `level` is below `contactLevel()` by
  /// more than trilinear rounding, and p lies outside the contact box or in a cell with no node
  /// below `contactLevel()`. A cheap cull for collisions; it never changes a result.
  [[nodiscard]] bool mayBeBelow(const glm::vec3& p, float level) const noexcept {
    if (!(level < contactLevel_ - 1e-6f)) return true;
    if (!(p.x >= contactLower_.x && p.y >= contactLower_.y && p.z >= contactLower_.z && p.x <= contactUpper_.x &&
          p.y <= contactUpper_.y && p.z <= contactUpper_.z))
      return false;
    const std::size_t cell = cellOf((p - origin_) * inverseCellSize_);
    return (contactCells_[cell / 32] >> (cell % 32) & 1u) != 0;
  }

private:
  SignedDistanceField() = default;
  // Signed distance (and optionally gradient) at `p`, inside or outside the box.
  float evaluate(const glm::vec3& p, glm::vec3* gradient) const noexcept;
  // Trilinear value (and optionally gradient) at grid coordinates inside the box.
  float interpolate(const glm::vec3& p, glm::vec3* gradient) const noexcept;
  // Index of the lowest node of the cell that `evaluate` interpolates in at grid coordinates u
  // (not NaN).
  std::size_t cellOf(const glm::vec3& u) const noexcept;

  glm::vec3 origin_{0.0f};
  float cellSize_ = 1.0f;
  float inverseCellSize_ = 1.0f;
  glm::ivec3 dims_{0};
  std::vector<float> values_;
  glm::vec3 contactLower_{0.0f};
  glm::vec3 contactUpper_{0.0f};
  float contactLevel_ = -std::numeric_limits<float>::infinity();
  std::vector<std::uint32_t> contactCells_;
  void findContactBox();
};

inline std::size_t SignedDistanceField::cellOf(const glm::vec3& u) const noexcept {
  // The clamp and the cell of `evaluate` and `interpolate`, operation for operation.
  const glm::vec3 top(dims_ - 1);
  const int i = std::min(static_cast<int>(std::clamp(u.x, 0.0f, top.x)), dims_.x - 2);
  const int j = std::min(static_cast<int>(std::clamp(u.y, 0.0f, top.y)), dims_.y - 2);
  const int k = std::min(static_cast<int>(std::clamp(u.z, 0.0f, top.z)), dims_.z - 2);
  return static_cast<std::size_t>(i) +
         static_cast<std::size_t>(dims_.x) *
             (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims_.y) * static_cast<std::size_t>(k));
}

// Sampling is inline: it runs several times per particle contact in the hair step.
inline float SignedDistanceField::interpolate(const glm::vec3& u, glm::vec3* gradient) const noexcept {
  // `u` in grid units, inside [0, dims − 1] on every axis.
  const int i = std::min(static_cast<int>(u.x), dims_.x - 2);
  const int j = std::min(static_cast<int>(u.y), dims_.y - 2);
  const int k = std::min(static_cast<int>(u.z), dims_.z - 2);
  const float fx = u.x - static_cast<float>(i), fy = u.y - static_cast<float>(j), fz = u.z - static_cast<float>(k);
  const std::size_t sx = 1, sy = static_cast<std::size_t>(dims_.x), sz = sy * static_cast<std::size_t>(dims_.y);
  const float* v = values_.data() + static_cast<std::size_t>(i) + sy * static_cast<std::size_t>(j) +
                   sz * static_cast<std::size_t>(k);
  const float v000 = v[0], v100 = v[sx], v010 = v[sy], v110 = v[sx + sy];
  const float v001 = v[sz], v101 = v[sx + sz], v011 = v[sy + sz], v111 = v[sx + sy + sz];
  const float c00 = v000 + (v100 - v000) * fx, c10 = v010 + (v110 - v010) * fx;
  const float c01 = v001 + (v101 - v001) * fx, c11 = v011 + (v111 - v011) * fx;
  const float c0 = c00 + (c10 - c00) * fy, c1 = c01 + (c11 - c01) * fy;
  if (gradient) {
    // ∂/∂fx, ∂/∂fy, ∂/∂fz of the trilinear interpolant, scaled to metres.
    const float dx0 = (v100 - v000) + ((v110 - v010) - (v100 - v000)) * fy;
    const float dx1 = (v101 - v001) + ((v111 - v011) - (v101 - v001)) * fy;
    const float dy0 = c10 - c00, dy1 = c11 - c01;
    gradient->x = (dx0 + (dx1 - dx0) * fz) * inverseCellSize_;
    gradient->y = (dy0 + (dy1 - dy0) * fz) * inverseCellSize_;
    gradient->z = (c1 - c0) * inverseCellSize_;
  }
  return c0 + (c1 - c0) * fz;
}

inline float SignedDistanceField::evaluate(const glm::vec3& p, glm::vec3* gradient) const noexcept {
  const glm::vec3 u = (p - origin_) * inverseCellSize_;
  if (!(u.x == u.x && u.y == u.y && u.z == u.z)) return u.x + u.y + u.z;  // NaN in, NaN out
  const glm::vec3 top(dims_ - 1);
  const glm::vec3 clamped(std::clamp(u.x, 0.0f, top.x), std::clamp(u.y, 0.0f, top.y), std::clamp(u.z, 0.0f, top.z));
  if (clamped == u) return interpolate(u, gradient);
  // Outside the box: the nearest grid point's value plus the way there.
  const glm::vec3 outward = (u - clamped) * cellSize_;
  const float gap = std::sqrt(outward.x * outward.x + outward.y * outward.y + outward.z * outward.z);
  if (gradient) *gradient = outward / gap;
  return interpolate(clamped, nullptr) + gap;
}

inline float SignedDistanceField::sample(const glm::vec3& p) const noexcept {
  return evaluate(p, nullptr);
}

inline float SignedDistanceField::sampleWithGradient(const glm::vec3& p, glm::vec3& gradient) const noexcept {
  return evaluate(p, &gradient);
}

/// A triangle mesh held in memory: positions (metres) and three indices per triangle.
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

/// A closed sphere mesh of `radius` metres around the origin: the regular icosahedron (vertices
/// from the golden ratio) with every triangle split into 4 `subdivisions` times, new vertices
/// pushed onto the sphere; 20·4ⁿ triangles wound counter-clockwise seen from outside. Built-in
/// content for tests, benchmarks and a default head collider (5 subdivisions: 20,480 triangles,
/// about the size of the LeePerrySmith head scan).
[[nodiscard]] TriangleMesh makeIcosphere(float radius, int subdivisions);

/// Exact closest point to `p` on triangle (a, b, c) (Ericson 2005, §5.1.5, computed in double
/// precision). Also reports the Voronoi feature that holds it: 0, 1, 2 for the vertices a, b, c;
/// 3, 4, 5 for the edges ab, bc, ca; 6 for the face interior.
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                  int& feature) noexcept;

}  // namespace mane::physics
