// SkinDiffusionPass's maps to and from the host (render/passes/skin_diffusion_pass.hpp): setMaps and
// the read-backs, for tests and tools. Between frames; each call waits for the GPU.

#include <cmath>
#include <cstring>
#include <exception>
#include <string>

#include <glm/gtc/packing.hpp>

#include "render/passes/skin_diffusion_pass.hpp"

namespace mane::render {
namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

constexpr vk::PipelineStageFlags2 kReaders = Stage::eFragmentShader | Stage::eComputeShader;
constexpr vk::AccessFlags2 kReads = Access::eShaderSampledRead | Access::eShaderStorageRead;

// The half-float texels of `image` (in `layout` before and after), `channels` per texel.
std::vector<float> readHalfTexels(const Device& device, const Image& image, Layout layout, std::uint32_t channels) {
  const vk::Extent2D extent = image.extent();
  const std::size_t values = std::size_t(extent.width) * extent.height * channels;
  const Buffer host(device, values * 2, vk::BufferUsageFlagBits::eTransferDst,
                    vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    transition(commands, image, layout, Layout::eTransferSrcOptimal, kReaders, Access::eShaderWrite, Stage::eCopy,
               Access::eTransferRead);
    commands.copyImageToBuffer(*image.image(), Layout::eTransferSrcOptimal, *host.buffer(),
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                                   .imageExtent = {extent.width, extent.height, 1}});
    transition(commands, image, Layout::eTransferSrcOptimal, layout, Stage::eCopy, Access::eTransferRead, kReaders,
               kReads);
    const vk::MemoryBarrier2 toHost{.srcStageMask = Stage::eCopy,
                                    .srcAccessMask = Access::eTransferWrite,
                                    .dstStageMask = Stage::eHost,
                                    .dstAccessMask = Access::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
  });
  std::vector<float> result(values);
  for (std::size_t i = 0; i < values; ++i) {
    std::uint16_t half;
    std::memcpy(&half, host.mapped().data() + 2 * i, 2);
    result[i] = glm::unpackHalf1x16(half);
  }
  return result;
}

// Replaces `image` (in `layout` afterwards) with half-float texels.
void writeHalfTexels(const Device& device, const Image& image, Layout layout, std::span<const float> values) {
  const Buffer staging(device, values.size() * 2, vk::BufferUsageFlagBits::eTransferSrc,
                       vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::uint16_t half = glm::packHalf1x16(values[i]);
    std::memcpy(staging.mapped().data() + 2 * i, &half, 2);
  }
  const vk::Extent2D extent = image.extent();
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    transition(commands, image, Layout::eUndefined, Layout::eTransferDstOptimal, kReaders, Access::eNone, Stage::eCopy,
               Access::eTransferWrite);
    commands.copyBufferToImage(*staging.buffer(), *image.image(), Layout::eTransferDstOptimal,
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                                   .imageExtent = {extent.width, extent.height, 1}});
    transition(commands, image, Layout::eTransferDstOptimal, layout, Stage::eCopy, Access::eTransferWrite, kReaders,
               kReads);
  });
}

template <class Texel>
Result<void> checkTexels(std::span<const Texel> texels, std::size_t expected, const char* name) {
  if (texels.size() != expected)
    return fail(std::string("skin diffusion: the ") + name + " map has " + std::to_string(texels.size()) +
                " texels, expected size² = " + std::to_string(expected));
  for (std::size_t i = 0; i < texels.size(); ++i)
    for (int c = 0; c < Texel::length(); ++c)
      if (!std::isfinite(texels[i][c]))
        return fail(std::string("skin diffusion: the ") + name + " map's texel " + std::to_string(i) +
                    " is not finite");
  return {};
}

template <class Texel>
Result<std::vector<Texel>> readTexels(const Device& device, const Image& image, Layout layout, const char* name) {
  try {
    const std::vector<float> values = readHalfTexels(device, image, layout, Texel::length());
    std::vector<Texel> texels(values.size() / Texel::length());
    std::memcpy(texels.data(), values.data(), values.size() * sizeof(float));
    return texels;
  } catch (const std::exception& error) {
    return fail(std::string("skin diffusion: reading the ") + name + " map back failed: " + error.what());
  }
}

}  // namespace

Result<void> SkinDiffusionPass::setMaps(std::span<const glm::vec4> irradiance, std::span<const glm::vec2> stretch) {
  const std::size_t texels = std::size_t(settings_.size) * settings_.size;
  if (auto ok = checkTexels(irradiance, texels, "irradiance"); !ok) return ok;
  if (auto ok = checkTexels(stretch, texels, "stretch"); !ok) return ok;
  try {
    writeHalfTexels(*device_, irradiance_, Layout::eGeneral, {&irradiance.front().x, 4 * texels});
    writeHalfTexels(*device_, stretch_, Layout::eShaderReadOnlyOptimal, {&stretch.front().x, 2 * texels});
  } catch (const std::exception& error) {
    return fail(std::string("skin diffusion: uploading the maps failed: ") + error.what());
  }
  uncoveredStretch_ = skinUncoveredStretch(stretch);
  return {};
}

Result<std::vector<glm::vec4>> SkinDiffusionPass::readIrradiance() const {
  return readTexels<glm::vec4>(*device_, irradiance_, Layout::eGeneral, "irradiance");
}

Result<std::vector<glm::vec2>> SkinDiffusionPass::readStretch() const {
  return readTexels<glm::vec2>(*device_, stretch_, Layout::eShaderReadOnlyOptimal, "stretch");
}

Result<std::vector<glm::vec4>> SkinDiffusionPass::readDiffusedIrradiance() const {
  return readTexels<glm::vec4>(*device_, accumulated_, Layout::eShaderReadOnlyOptimal, "diffused irradiance");
}

}  // namespace mane::render
