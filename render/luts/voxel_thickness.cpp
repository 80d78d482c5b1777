#include "render/luts/voxel_thickness.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <thread>

#include <glm/gtc/packing.hpp>

#include "render/luts/solid_segments.hpp"

namespace mane::render {

Result<VoxelThicknessLut> VoxelThicknessLut::build(std::span<const glm::vec3> positions,
                                                   std::span<const std::uint32_t> indices,
                                                   const VoxelThicknessSettings& settings) {
  auto voxels = voxelizeSolid(positions, indices, settings.resolution);
  if (!voxels) return std::unexpected(voxels.error());
  auto surface = findSurfaceVoxels(*voxels);
  if (!surface) return std::unexpected(surface.error());

  VoxelThicknessLut lut;
  lut.voxels_ = std::move(*voxels);
  lut.surface_ = std::move(*surface);
  const std::size_t m = lut.surface_.cells.size();
  if (tableBytes(m) > settings.maxTableBytes) {
    return fail("VoxelThicknessLut: " + std::to_string(m) + " surface voxels at resolution " +
                std::to_string(settings.resolution) + " need a " + std::to_string(tableBytes(m)) +
                "-byte table, over the limit of " + std::to_string(settings.maxTableBytes) +
                " bytes (lower the resolution or raise maxTableBytes).");
  }
  const glm::dvec3 extent = lut.voxels_.voxelSize * static_cast<double>(lut.voxels_.resolution);
  const double diagonal = std::sqrt(extent.x * extent.x + extent.y * extent.y + extent.z * extent.z);
  lut.scale_ = static_cast<float>(diagonal);
  lut.table_.assign(m * m, 0);

  const SolidSegmentWalker walker(lut.voxels_);
  std::vector<glm::ivec3> cells(m);
  for (std::size_t i = 0; i < m; ++i) cells[i] = lut.voxels_.coordinates(lut.surface_.cells[i]);
  const auto fillRows = [&](std::size_t firstRow, std::size_t rowStep) {
    for (std::size_t a = firstRow; a < m; a += rowStep) {
      for (std::size_t b = a + 1; b < m; ++b) {
        const double d =
            walker.solidFraction(cells[a], cells[b]) * distanceBetweenCells(lut.voxels_, cells[a], cells[b]);
        const std::uint16_t half = glm::packHalf1x16(static_cast<float>(d / diagonal));
        lut.table_[a * m + b] = half;
        lut.table_[b * m + a] = half;  // distinct elements per thread: no data race
      }
    }
  };
  std::size_t threads = settings.threads != 0 ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(m, 1));
  {
    std::vector<std::jthread> workers;  // joined at the end of this block, before `lut` moves out
    for (std::size_t w = 1; w < threads; ++w) workers.emplace_back(fillRows, w, threads);
    fillRows(0, threads);
  }
  return lut;
}

std::uint32_t VoxelThicknessLut::surfaceVoxelAt(const glm::vec3& point) const noexcept {
  const glm::ivec3 c = voxels_.cellAt(glm::dvec3(point));
  return surface_.nearest[voxels_.index(c.x, c.y, c.z)];
}

float VoxelThicknessLut::thickness(std::uint32_t a, std::uint32_t b) const noexcept {
  return glm::unpackHalf1x16(table_[static_cast<std::size_t>(a) * surface_.cells.size() + b]) * scale_;
}

glm::vec3 transmittedIntensity(const glm::vec3& incident, const glm::vec3& extinction, float thickness) noexcept {
  return {incident.x * std::exp(-extinction.x * thickness), incident.y * std::exp(-extinction.y * thickness),
          incident.z * std::exp(-extinction.z * thickness)};
}

}  // namespace mane::render
