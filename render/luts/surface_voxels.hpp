#pragma once
// The surface voxels of a solid voxelization, numbered, and the map from every cell to its
// nearest surface voxel: the rows and columns of the voxelized thickness LUT
// (render/luts/voxel_thickness.hpp) and how a shaded point finds its row.
//
// Which voxels: solid cells with at least one 6-neighbour in the exterior, where the exterior is
// everything outside the grid plus the empty cells 6-connected to it (a flood fill from the
// grid's faces). Why solid cells and not the cells the surface passes through: a LUT entry is
// measured between two centres, and a solid centre is inside the object, so the segment starts
// and ends in material. Why exterior only: the walls of an enclosed hollow are surfaces no light
// can reach from outside and no shaded point lies on, yet numbering them would grow the LUT
// quadratically (the cube [−1, 1]³ with a hollow ball of radius 0.5 at N = 30: 632 more rows on
// 5,048, 27 % more memory) and could pull the nearest-voxel lookup of a point on a thin outer
// wall onto the inner wall.
//
// Order: increasing linear cell index (x fastest, then y, then z), so the numbering depends only
// on the solid flags.
//
// Nearest surface voxel of a cell: the surface voxel whose centre is closest (Euclidean, in mesh
// units, so anisotropic cells are measured correctly) to the cell's centre, by the exact
// separable distance transform of Felzenszwalb & Huttenlocher ("Distance Transforms of Sampled
// Functions", Theory of Computing 8, 2012), carrying the argmin along: O(N³). Equidistant
// candidates are settled by the fixed order of the passes (x, then y, then z), so the map is the
// same every run. A shader mirrors the lookup with one read of this map, stored as a storage
// buffer of uint32 (render/passes/thickness_table.hpp, shaders/translucency.glsl).

#include <cstdint>
#include <vector>

#include "render/luts/solid_voxels.hpp"

namespace mane::render {

/// Surface voxels of a SolidVoxels grid and every cell's nearest one. Plain value type.
struct SurfaceVoxels {
  /// Linear cell index of surface voxel m (m = the LUT row), increasing.
  std::vector<std::uint32_t> cells;
  /// For each of the N³ cells (x fastest), the number of its nearest surface voxel.
  std::vector<std::uint32_t> nearest;
};

/// Numbers the surface voxels of `voxels` and maps every cell to its nearest one. Fails when the
/// grid has no solid cell (nothing to number).
[[nodiscard]] Result<SurfaceVoxels> findSurfaceVoxels(const SolidVoxels& voxels);

/// Only the cells of the surface voxels, in LUT order, without the nearest map: enough to size a
/// LUT (its memory is M² entries for M surface voxels) at a resolution too large to build.
[[nodiscard]] std::vector<std::uint32_t> numberSurfaceVoxels(const SolidVoxels& voxels);

}  // namespace mane::render
