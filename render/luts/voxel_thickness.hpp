#pragma once
// The voxelized thickness LUT of the voxelized-translucency paper (docs/design.md#sources),
// CPU side: for every pair of surface voxels of a closed mesh, how much of the straight segment
// between their centres lies inside the object. A translucent shade then needs no depth map: the
// light's entry point and the shaded point each find their surface voxel, one LUT read gives the
// thickness d between them, and the light arriving is I = I0·exp(−σ·d) per RGB channel.
//
// Build:
// 1. Solid voxelization on N³ cells over the bounding box (render/luts/solid_voxels.hpp:
//    winding number along exact rays; hollows wound inward come out empty).
// 2. Surface voxels numbered, and every cell's nearest one (render/luts/surface_voxels.hpp).
// 3. For each pair (a, b), a < b, an exact integer 3D DDA walks the cells from centre a to
//    centre b and adds the segment's length in each solid cell, so an empty hollow on the way is
//    subtracted (render/luts/solid_segments.hpp). The entry (b, a) is a copy of (a, b), so the
//    table is exactly symmetric, and (a, a) = 0.
//
// Storage: a dense M × M table (M surface voxels) of half floats, row-major, as the GPU reads it
// (render/passes/thickness_table.hpp, two halves per uint32 of a storage buffer):
// entry = d / thicknessScale(), where the scale is the bounding box's diagonal, so
// entries lie in [0, 1] whatever the mesh's units and half precision costs at most 2⁻¹² of the
// diagonal (a 128-cell voxel is ~4.5·10⁻³ of it). Memory is 2·M² bytes and M grows as N² (the
// surface area), so the table grows as N⁴: a cube at N = 30, 40, 50 has M = 5,048, 9,128,
// 14,408 and needs 51, 167, 415 MB; a device caps one storage buffer's range
// (maxStorageBufferRange: 128 MiB on lavapipe, docs/lavapipe.md#features).
//
// Threads: rows are dealt round-robin to `threads` workers; each entry is a pure function of
// its pair, so the table is bit-identical for any thread count.
//
// Units: the mesh's (metres for the engine); σ is per the same unit.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "render/luts/solid_voxels.hpp"
#include "render/luts/surface_voxels.hpp"

namespace mane::render {

/// How to build a VoxelThicknessLut.
struct VoxelThicknessSettings {
  /// N, cells per axis of the grid over the mesh's bounding box, in
  /// [SolidVoxels::kMinResolution, SolidVoxels::kMaxResolution]. The paper uses 30 to 50.
  int resolution = 32;
  /// Worker threads for the pair table; 0 = std::thread::hardware_concurrency(). Results do not
  /// depend on it.
  unsigned threads = 0;
  /// The largest table accepted, bytes (2·M²); a larger one fails before allocating.
  std::size_t maxTableBytes = std::size_t{1} << 30;
};

class VoxelThicknessLut {
public:
  /// Builds the LUT of the closed mesh (see solid_voxels.hpp for what the mesh must be). Errors:
  /// those of voxelizeSolid and findSurfaceVoxels, and a table over settings.maxTableBytes.
  [[nodiscard]] static Result<VoxelThicknessLut> build(std::span<const glm::vec3> positions,
                                                       std::span<const std::uint32_t> indices,
                                                       const VoxelThicknessSettings& settings = {});

  /// Bytes of the M × M half-float table for M surface voxels.
  [[nodiscard]] static std::size_t tableBytes(std::size_t surfaceVoxels) noexcept {
    return surfaceVoxels * surfaceVoxels * sizeof(std::uint16_t);
  }

  /// M, the number of surface voxels: rows and columns of the table.
  [[nodiscard]] std::uint32_t surfaceVoxelCount() const noexcept {
    return static_cast<std::uint32_t>(surface_.cells.size());
  }
  /// Centre of surface voxel `m`, mesh units.
  [[nodiscard]] glm::dvec3 surfaceVoxelCentre(std::uint32_t m) const noexcept {
    return voxels_.centre(surface_.cells[m]);
  }
  /// The surface voxel nearest the centre of the cell that holds `point` (clamped into the grid):
  /// the shader's texelFetch of nearestMap() at that cell.
  [[nodiscard]] std::uint32_t surfaceVoxelAt(const glm::vec3& point) const noexcept;
  /// Thickness between surface voxels `a` and `b`, mesh units, as stored (half precision).
  [[nodiscard]] float thickness(std::uint32_t a, std::uint32_t b) const noexcept;
  /// Thickness between the surface voxels of two points (surfaceVoxelAt of each), mesh units.
  [[nodiscard]] float thicknessBetween(const glm::vec3& from, const glm::vec3& to) const noexcept {
    return thickness(surfaceVoxelAt(from), surfaceVoxelAt(to));
  }

  /// The table, M × M half floats (glm::packHalf1x16 bits), row-major; entry × thicknessScale()
  /// is the thickness in mesh units.
  [[nodiscard]] std::span<const std::uint16_t> texels() const noexcept { return table_; }
  /// Mesh units per table unit: the bounding box's diagonal.
  [[nodiscard]] float thicknessScale() const noexcept { return scale_; }
  /// N³ surface voxel numbers, x fastest (an R32UI 3D texture).
  [[nodiscard]] std::span<const std::uint32_t> nearestMap() const noexcept { return surface_.nearest; }
  [[nodiscard]] const SolidVoxels& voxels() const noexcept { return voxels_; }
  [[nodiscard]] const SurfaceVoxels& surface() const noexcept { return surface_; }

private:
  VoxelThicknessLut() = default;

  SolidVoxels voxels_;
  SurfaceVoxels surface_;
  std::vector<std::uint16_t> table_;
  float scale_ = 0.0f;
};

/// Light through `thickness` of material: I0·exp(−σ·d) per RGB channel (Beer–Lambert), with
/// `extinction` σ per mesh unit. The translucency shader mirrors this.
[[nodiscard]] glm::vec3 transmittedIntensity(const glm::vec3& incident, const glm::vec3& extinction,
                                             float thickness) noexcept;

}  // namespace mane::render
