#pragma once
// Solid voxelization of a closed triangle mesh: which cells of an N³ grid over the mesh's
// bounding box have their centre inside the object. The first step of the voxelized thickness
// LUT (render/luts/voxel_thickness.hpp); plain C++ and GLM, no Vulkan.
//
// Inside test: the winding number of each cell centre, counted along a ray in +x. Every grid
// column (j, k) casts one ray through the centres (·, j + ½, k + ½); each triangle whose
// projection on the yz plane covers the ray adds +1 where it is entered (outward normal facing
// −x) and −1 where it is left. A centre is solid when the signed count of crossings before it is
// non-zero. Why this and not parity or the generalised winding number (Jacobson et al. 2013):
//  - Exactness. The projected vertices are rounded once to a fixed-point lattice (2⁻²⁰ cell) and
//    the 2D orientation tests run in 64-bit integers, so they are exact. A ray that meets an edge
//    or a vertex exactly (common: centres and vertices both sit on regular lattices) is decided
//    by the top-left rule, which is the exact answer for the ray through the centre shifted by
//    (0, ε, −ε²) (Edelsbrunner & Mücke's simulation of simplicity). Each crossing is then counted
//    exactly once, and a mesh without holes always gives a whole winding number. Parity along a
//    floating-point ray, by contrast, double-counts or misses edge hits unless it re-casts.
//  - Orientation carries meaning. A hollow is an inner surface wound inward (its normals point
//    into the hollow, away from the material), so its winding number is 0: empty. Two overlapping
//    closed shells count 2 and stay solid, where parity would carve their overlap out.
//  - Cost. One pass over the triangles touches only the columns their projections cover:
//    O(triangles + crossings + N³). The generalised winding number costs triangles × N³ solid
//    angles, about 10⁹ for a 10,000-triangle piece at N = 50.
// Closedness is checked first, on the topology: every directed edge a→b (a, b compared by
// position, so a mesh split at UV seams still counts as closed) must be matched by as many b→a.
// Each ray's crossings must then sum to zero; a ray that does not is reported too.
//
// Grid: the mesh's axis-aligned bounding box divided into N cells per axis, so cells are boxes
// of size extent / N (not cubes when the box is not a cube). Cell (i, j, k) has its centre at
// origin + (i + ½, j + ½, k + ½) · voxelSize; cells are stored x fastest, then y, then z.
// Units: whatever the mesh is in (metres for the engine).

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::render {

/// Solid cells of a closed mesh on an N³ grid over its bounding box. Plain value type.
struct SolidVoxels {
  static constexpr int kMinResolution = 4;    ///< smallest N accepted
  static constexpr int kMaxResolution = 128;  ///< largest N accepted (fixed-point range, memory)

  int resolution = 0;               ///< N, cells per axis
  glm::dvec3 origin{0.0};           ///< bounding box minimum, mesh units
  glm::dvec3 voxelSize{0.0};        ///< cell size per axis (extent / N), mesh units
  std::vector<std::uint8_t> solid;  ///< N³ flags (1 = centre inside), x fastest

  [[nodiscard]] std::size_t cellCount() const noexcept { return solid.size(); }
  /// Linear index of cell (i, j, k); each in [0, N).
  [[nodiscard]] std::size_t index(int i, int j, int k) const noexcept {
    const auto n = static_cast<std::size_t>(resolution);
    return static_cast<std::size_t>(i) + n * (static_cast<std::size_t>(j) + n * static_cast<std::size_t>(k));
  }
  /// Cell coordinates of linear index `cell`.
  [[nodiscard]] glm::ivec3 coordinates(std::size_t cell) const noexcept;
  /// Centre of cell `cell`, mesh units.
  [[nodiscard]] glm::dvec3 centre(std::size_t cell) const noexcept;
  /// The cell that holds `point` (mesh units), clamped into the grid.
  [[nodiscard]] glm::ivec3 cellAt(const glm::dvec3& point) const noexcept;
  [[nodiscard]] bool isSolid(int i, int j, int k) const noexcept { return solid[index(i, j, k)] != 0; }
};

/// Voxelizes the closed mesh (`positions` in any units, `indices` three per triangle, wound
/// counter-clockwise seen from outside the material; an inner hollow's surface is therefore wound
/// inward) on `resolution`³ cells. Errors, each naming the place: `resolution` outside
/// [kMinResolution, kMaxResolution]; no triangles; an index count not a multiple of 3; an index
/// out of range; a NaN or infinite position; a bounding box flat along an axis; a mesh that is
/// not closed (an edge without its opposite, naming the edge and its triangle, or a ray whose
/// crossings do not cancel).
[[nodiscard]] Result<SolidVoxels> voxelizeSolid(std::span<const glm::vec3> positions,
                                                std::span<const std::uint32_t> indices, int resolution);

}  // namespace mane::render
