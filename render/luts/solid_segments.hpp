#pragma once
// How much of the straight segment between two cell centres of a SolidVoxels grid lies in solid
// cells: one entry of the voxelized thickness LUT (render/luts/voxel_thickness.hpp).
//
// The walk is a 3D DDA (Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm") in exact
// integers. Both ends are cell centres, so along an axis with cell offset Δ ≠ 0 the segment
// crosses cell boundaries at t = (2m + 1)/(2|Δ|), m = 0 … |Δ| − 1. Over the common denominator
// D = 2·∏|Δ| (nonzero offsets; ≤ 2·127³ at N = 128) each crossing is an integer, so the walk
// compares integers, steps every axis that ties at once (a segment through an edge or a corner
// spends no length in the cells that only touch it there), and sums the solid cells' share of D
// exactly. The result is that integer over D, rounded once: a pure function of the two cells.
//
// SolidSegmentWalker skips runs: it keeps, per cell, the Chebyshev distance k to the nearest
// cell of the other kind (solid vs empty), found by a 26-connected breadth-first search from the
// cells that touch the other kind. Every cell within k − 1 of the current one is alike, so the
// segment can jump to where it leaves that cube (its (k)-th next crossing along the axis that
// gets there first) and add the whole stretch at once. The sums are the same integers as the
// plain walk's, so both give identical bits; the test holds them to that.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "render/luts/solid_voxels.hpp"

namespace mane::render {

/// The fraction of the segment from the centre of cell `from` to the centre of cell `to` that
/// lies in solid cells (0 when from = to), by the plain walk: the reference.
[[nodiscard]] double solidFractionBetweenCells(const SolidVoxels& voxels, const glm::ivec3& from,
                                               const glm::ivec3& to) noexcept;

/// |to − from| in mesh units, between the two cells' centres.
[[nodiscard]] double distanceBetweenCells(const SolidVoxels& voxels, const glm::ivec3& from,
                                          const glm::ivec3& to) noexcept;

/// The same fraction, skipping runs of alike cells. Holds a reference to `voxels`, which must
/// outlive it; const and safe to share between threads.
class SolidSegmentWalker {
public:
  explicit SolidSegmentWalker(const SolidVoxels& voxels);

  /// Bit-identical to solidFractionBetweenCells(voxels, from, to).
  [[nodiscard]] double solidFraction(const glm::ivec3& from, const glm::ivec3& to) const noexcept;

private:
  const SolidVoxels* voxels_;
  std::vector<std::uint8_t> reach_;  // Chebyshev distance to the other kind, capped at 255
};

}  // namespace mane::render
