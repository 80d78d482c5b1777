#pragma once
// Points bound to a triangle mesh so that they follow it when it deforms: groom roots on a
// skinned, morphing body, or anything else that must stay on (or at a fixed height above) a skin.
//
// At binding each point takes the mesh triangle closest to it, the barycentric weights of its
// projection onto that triangle's plane, and its signed height above the plane. After the mesh
// deforms (same vertices, new positions), the point is rebuilt from the same three numbers on
// the moved triangle, with the triangle's new normal and a tangent along its first edge: a
// local frame that turns with the skin, so a strand's rest shape can turn with it.
//
// A point on the surface binds at height 0 with weights that are all ≥ 0 (its projection is
// its closest point); a point beside an edge keeps weights of its own plane projection (one
// may be negative), so the undeformed mesh gives every point back where it was.
//
// Units: metres. Binding and evaluation are single-threaded and free of data-dependent
// ordering: the same inputs give the same bits.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

/// Where a bound point sits on a triangle mesh: its triangle, barycentric weights of the
/// triangle's three corners, and its height along the triangle's unit normal.
struct SurfacePoint {
  std::uint32_t triangle = 0;          ///< index of the triangle (indices[3·triangle ..])
  glm::vec3 barycentric{1.0f / 3.0f};  ///< weights of corners 0, 1, 2; they sum to 1
  float height = 0.0f;                 ///< metres along the face's unit normal (counter-clockwise winding)
};

class SurfaceBinding {
public:
  /// Binds each of `points` to the closest point of the triangles (`indices`, 3 per triangle) of
  /// `positions` (same space as the points). Deterministic: of triangles at the same distance,
  /// the lowest index wins. Fails on an empty mesh, an index count that is not a multiple of 3,
  /// an index out of range, or a NaN or infinite position or point (naming it). No points is
  /// not an error: the binding is empty.
  /// Degenerate (zero-area) triangles are skipped; fails if all are degenerate.
  /// The search runs over a bounding-volume hierarchy of the triangles (built here, then freed).
  [[nodiscard]] static Result<SurfaceBinding> create(std::span<const glm::vec3> positions,
                                                     std::span<const std::uint32_t> indices,
                                                     std::span<const glm::vec3> points);

  /// One per input point, in input order.
  [[nodiscard]] std::span<const SurfacePoint> points() const noexcept { return points_; }
  /// Number of bound points.
  [[nodiscard]] std::size_t size() const noexcept { return points_.size(); }
  /// Vertex count of the mesh at binding: what `evaluate` expects.
  [[nodiscard]] std::size_t vertexCount() const noexcept { return vertexCount_; }
  /// Largest distance from an input point to the surface at binding time, metres.
  [[nodiscard]] float largestHeight() const noexcept { return largestHeight_; }

  /// The bound points on the mesh deformed to `positions` (same vertex count and order as at
  /// binding): p = Σ b_i·x_i + height·n_face; the unit normal = the barycentric blend of
  /// `vertexNormals` when given (one per vertex) else the face normal; the tangent = the unit
  /// direction of the triangle's first edge (corner 0 → 1) made orthogonal to the normal (a
  /// local frame with the normal). Writes the spans given (`outNormals`/`outTangents` may be
  /// empty to skip them). Fails, writing nothing, on a wrong vertex count or span size.
  ///
  /// Where the deformation collapsed a triangle (no face normal), the point keeps the normal its
  /// triangle had at binding; a zero blend of vertex normals falls back to the face normal; a
  /// first edge along the normal falls back to the second edge, then to any perpendicular. So
  /// every normal and tangent written is of unit length for finite input. NaN or infinite
  /// positions give NaN outputs (HairSystem::setRootTargets rejects them, naming the strand).
  /// Allocation-free; the thread count is irrelevant (one thread, the caller's).
  [[nodiscard]] Result<void> evaluate(std::span<const glm::vec3> positions, std::span<const glm::vec3> vertexNormals,
                                      std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals,
                                      std::span<glm::vec3> outTangents) const;

private:
  SurfaceBinding() = default;

  std::vector<SurfacePoint> points_;
  std::vector<std::uint32_t> corners_;  // per point: its triangle's 3 vertex indices
  std::vector<glm::vec3> restNormals_;  // per point: its triangle's unit normal at binding
  std::size_t vertexCount_ = 0;
  float largestHeight_ = 0.0f;
};

}  // namespace mane::physics
