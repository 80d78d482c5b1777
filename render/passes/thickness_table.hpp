#pragma once
// A mesh's voxelized thickness table (render/luts/voxel_thickness.hpp) on the device, as the
// surface pass reads it (shaders/translucency.glsl): storage buffers rather than textures, so
// the table's side M (the surface voxel count, 14,408 for a cube at N = 50) is not capped by
// maxImageDimension2D, and a 1D lookup needs no filtering.
//  - `nearest`: N³ uint32, every cell's nearest surface voxel, x fastest;
//  - `table`: M × M half floats, two per uint32, row-major;
//  - `grid`: a uniform block with the grid's placement and the table's scale.

#include <glm/glm.hpp>

#include "render/luts/voxel_thickness.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// Mirrors `ThicknessGrid` in shaders/translucency.glsl (std140).
struct ThicknessGridUniforms {
  glm::vec4 origin{0.0f};        ///< xyz: the grid's minimum corner, mesh units
  glm::vec4 inverseVoxel{0.0f};  ///< xyz: cells per mesh unit along each axis
  glm::uvec4 size{0u};           ///< x: N, y: M
  glm::vec4 scale{0.0f};         ///< x: mesh units per table unit (VoxelThicknessLut::thicknessScale)
};

class ThicknessTable {
public:
  /// Uploads `lut`. Throws vk::SystemError when the device runs out of memory.
  ThicknessTable(const Device& device, const VoxelThicknessLut& lut);

  [[nodiscard]] const Buffer& nearest() const { return nearest_; }
  [[nodiscard]] const Buffer& table() const { return table_; }
  [[nodiscard]] const Buffer& grid() const { return grid_; }

private:
  Buffer nearest_;
  Buffer table_;
  Buffer grid_;
};

}  // namespace mane::render
