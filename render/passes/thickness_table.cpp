#include "render/passes/thickness_table.hpp"

#include <cstring>

namespace mane::render {
namespace {

// Two halves per word; an odd count leaves the last word's high half zero.
std::vector<std::uint32_t> packHalves(std::span<const std::uint16_t> halves) {
  std::vector<std::uint32_t> words((halves.size() + 1) / 2, 0u);
  for (std::size_t i = 0; i < halves.size(); ++i) words[i / 2] |= std::uint32_t(halves[i]) << (16 * (i % 2));
  return words;
}

}  // namespace

ThicknessTable::ThicknessTable(const Device& device, const VoxelThicknessLut& lut) {
  const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
  nearest_ = Buffer::withData(device, std::as_bytes(lut.nearestMap()), storage);
  const std::vector<std::uint32_t> words = packHalves(lut.texels());
  table_ = Buffer::withData(device, std::as_bytes(std::span(words)), storage);
  const SolidVoxels& voxels = lut.voxels();
  const ThicknessGridUniforms uniforms{
      .origin = glm::vec4(glm::vec3(voxels.origin), 0.0f),
      .inverseVoxel = glm::vec4(glm::vec3(1.0 / voxels.voxelSize), 0.0f),
      .size = glm::uvec4(std::uint32_t(voxels.resolution), lut.surfaceVoxelCount(), 0u, 0u),
      .scale = glm::vec4(lut.thicknessScale(), 0.0f, 0.0f, 0.0f)};
  grid_ = Buffer::withData(device, std::as_bytes(std::span(&uniforms, 1)), vk::BufferUsageFlagBits::eUniformBuffer);
}

}  // namespace mane::render
