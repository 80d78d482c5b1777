#include "render/environment/specular_chain.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "render/descriptors.hpp"
#include "render/pipelines.hpp"

namespace mane::render {
namespace {

// Mirrors the push constants of shaders/environment_prefilter.comp.
struct PrefilterConstants {
  glm::uvec4 sizes;     // x: this level's size, y: samples, z: the source's size
  glm::vec4 roughness;  // x
};

constexpr std::uint32_t kWorkgroupSize = 8;  // local_size_x and _y of the shader
constexpr vk::Format kFormat = vk::Format::eR16G16B16A16Sfloat;

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

vk::ImageSubresourceRange levels(std::uint32_t first, std::uint32_t count) {
  return {vk::ImageAspectFlagBits::eColor, first, count, 0, 6};
}

std::vector<std::uint16_t> halfTexels(const CubeMap& cube) {
  std::vector<std::uint16_t> halves;
  halves.reserve(std::size_t(cube.size) * std::size_t(cube.size) * 6 * 4);
  for (const std::vector<glm::vec3>& face : cube.faces)
    for (const glm::vec3& texel : face) {
      const glm::vec3 clamped = glm::min(texel, glm::vec3(65504.0f));
      for (int c = 0; c < 3; ++c) halves.push_back(glm::packHalf1x16(clamped[c]));
      halves.push_back(glm::packHalf1x16(1.0f));
    }
  return halves;
}

}  // namespace

Image uploadCubeWithMips(const Device& device, const CubeMap& cube) {
  const auto size = static_cast<std::uint32_t>(cube.size);
  const auto mipLevels = static_cast<std::uint32_t>(std::bit_width(size));
  Image image(device, ImageSettings{.extent = {size, size},
                                    .format = kFormat,
                                    .usage = vk::ImageUsageFlagBits::eSampled | vk::ImageUsageFlagBits::eTransferDst |
                                             vk::ImageUsageFlagBits::eTransferSrc,
                                    .mipLevels = mipLevels,
                                    .layers = 6,
                                    .cube = true});
  const std::vector<std::uint16_t> halves = halfTexels(cube);
  const std::span<const std::byte> bytes = std::as_bytes(std::span(halves));
  Buffer staging(device, bytes.size(), vk::BufferUsageFlagBits::eTransferSrc,
                 vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  std::memcpy(staging.mapped().data(), bytes.data(), bytes.size());
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    const vk::Image handle = *image.image();
    imageBarrier(commands, handle, levels(0, mipLevels), Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone,
                 Access::eNone, Stage::eTransfer, Access::eTransferWrite);
    // The faces lie one after the other in the staging buffer, as the six layers.
    commands.copyBufferToImage(*staging.buffer(), handle, Layout::eTransferDstOptimal,
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 6},
                                                   .imageExtent = {size, size, 1}});
    auto side = static_cast<std::int32_t>(size);
    for (std::uint32_t level = 1; level < mipLevels; ++level) {
      imageBarrier(commands, handle, levels(level - 1, 1), Layout::eTransferDstOptimal, Layout::eTransferSrcOptimal,
                   Stage::eTransfer, Access::eTransferWrite, Stage::eBlit, Access::eTransferRead);
      const std::int32_t next = std::max(side / 2, 1);
      const vk::ImageBlit blit{.srcSubresource = {vk::ImageAspectFlagBits::eColor, level - 1, 0, 6},
                               .srcOffsets = std::array{vk::Offset3D{0, 0, 0}, vk::Offset3D{side, side, 1}},
                               .dstSubresource = {vk::ImageAspectFlagBits::eColor, level, 0, 6},
                               .dstOffsets = std::array{vk::Offset3D{0, 0, 0}, vk::Offset3D{next, next, 1}}};
      commands.blitImage(handle, Layout::eTransferSrcOptimal, handle, Layout::eTransferDstOptimal, blit,
                         vk::Filter::eLinear);
      side = next;
    }
    if (mipLevels > 1)
      imageBarrier(commands, handle, levels(0, mipLevels - 1), Layout::eTransferSrcOptimal,
                   Layout::eShaderReadOnlyOptimal, Stage::eBlit, Access::eTransferRead,
                   Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
    imageBarrier(commands, handle, levels(mipLevels - 1, 1), Layout::eTransferDstOptimal,
                 Layout::eShaderReadOnlyOptimal, Stage::eTransfer | Stage::eBlit, Access::eTransferWrite,
                 Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
  });
  return image;
}

Result<SpecularChain> SpecularChain::bake(const Device& device, const Image& source, const vk::raii::Sampler& sampler,
                                          std::uint32_t baseSize) {
  if (baseSize < (1u << (kLevels - 1)) || !std::has_single_bit(baseSize))
    return fail("environment: the specular chain's base size " + std::to_string(baseSize) +
                " is not a power of two of at least " + std::to_string(1u << (kLevels - 1)));
  SpecularChain chain;
  try {
    chain.image_ =
        Image(device, ImageSettings{.extent = {baseSize, baseSize},
                                    .format = kFormat,
                                    .usage = vk::ImageUsageFlagBits::eStorage | vk::ImageUsageFlagBits::eSampled |
                                             vk::ImageUsageFlagBits::eTransferSrc,
                                    .mipLevels = kLevels,
                                    .layers = 6,
                                    .cube = true});
    // The pipeline, the per-level storage views and their sets live only for the bake.
    const vk::raii::DescriptorSetLayout setLayout =
        makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, vk::ShaderStageFlagBits::eCompute},
                               {vk::DescriptorType::eStorageImage, vk::ShaderStageFlagBits::eCompute}});
    const Pipeline pipeline =
        makeComputePipeline(device, "environment_prefilter.comp", setLayout, sizeof(PrefilterConstants));
    const vk::raii::DescriptorPool pool = makeDescriptorPool(
        device, kLevels,
        {{vk::DescriptorType::eCombinedImageSampler, kLevels}, {vk::DescriptorType::eStorageImage, kLevels}});
    std::vector<vk::raii::ImageView> views;
    std::vector<vk::raii::DescriptorSet> sets;
    for (std::uint32_t level = 0; level < kLevels; ++level) {
      views.emplace_back(device.device(), vk::ImageViewCreateInfo{.image = *chain.image_.image(),
                                                                  .viewType = vk::ImageViewType::e2DArray,
                                                                  .format = kFormat,
                                                                  .subresourceRange = levels(level, 1)});
      sets.push_back(allocateSet(device, pool, setLayout));
      writeSampledImage(device, sets.back(), 0, source.view(), sampler);
      const vk::DescriptorImageInfo storage{.imageView = *views.back(), .imageLayout = Layout::eGeneral};
      device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *sets.back(),
                                                                  .dstBinding = 1,
                                                                  .descriptorCount = 1,
                                                                  .descriptorType = vk::DescriptorType::eStorageImage,
                                                                  .pImageInfo = &storage},
                                           {});
    }
    device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      imageBarrier(commands, *chain.image_.image(), levels(0, kLevels), Layout::eUndefined, Layout::eGeneral,
                   Stage::eNone, Access::eNone, Stage::eComputeShader, Access::eShaderStorageWrite);
      commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
      for (std::uint32_t level = 0; level < kLevels; ++level) {
        const std::uint32_t size = baseSize >> level;
        const PrefilterConstants constants{.sizes = {size, samplesOf(level), source.extent().width, 0},
                                           .roughness = {roughnessOf(level), 0.0f, 0.0f, 0.0f}};
        commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, {*sets[level]}, {});
        commands.pushConstants<PrefilterConstants>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
        const std::uint32_t groups = (size + kWorkgroupSize - 1) / kWorkgroupSize;
        commands.dispatch(groups, groups, 6);
      }
      imageBarrier(commands, *chain.image_.image(), levels(0, kLevels), Layout::eGeneral,
                   Layout::eShaderReadOnlyOptimal, Stage::eComputeShader, Access::eShaderStorageWrite,
                   Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
    });
  } catch (const std::exception& error) {
    return fail(std::string("environment: baking the specular chain failed: ") + error.what());
  }
  return chain;
}

CubeMap SpecularChain::readLevel(const Device& device, std::uint32_t level) const {
  const std::uint32_t size = std::max(image_.extent().width >> level, 1u);
  const vk::DeviceSize bytes = vk::DeviceSize(size) * size * 6 * 4 * sizeof(std::uint16_t);
  Buffer host(device, bytes, vk::BufferUsageFlagBits::eTransferDst,
              vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    imageBarrier(commands, *image_.image(), levels(level, 1), Layout::eShaderReadOnlyOptimal,
                 Layout::eTransferSrcOptimal, Stage::eFragmentShader | Stage::eComputeShader,
                 Access::eShaderSampledRead, Stage::eTransfer, Access::eTransferRead);
    commands.copyImageToBuffer(*image_.image(), Layout::eTransferSrcOptimal, *host.buffer(),
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, level, 0, 6},
                                                   .imageExtent = {size, size, 1}});
    imageBarrier(commands, *image_.image(), levels(level, 1), Layout::eTransferSrcOptimal,
                 Layout::eShaderReadOnlyOptimal, Stage::eTransfer, Access::eTransferRead,
                 Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
    const vk::BufferMemoryBarrier2 toHost{.srcStageMask = Stage::eTransfer,
                                          .srcAccessMask = Access::eTransferWrite,
                                          .dstStageMask = Stage::eHost,
                                          .dstAccessMask = Access::eHostRead,
                                          .buffer = *host.buffer(),
                                          .size = VK_WHOLE_SIZE};
    commands.pipelineBarrier2(vk::DependencyInfo{.bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &toHost});
  });
  CubeMap cube{.size = int(size)};
  const auto* halves = reinterpret_cast<const std::uint16_t*>(host.mapped().data());
  for (std::size_t face = 0; face < 6; ++face)
    for (std::size_t i = 0; i < std::size_t(size) * size; ++i) {
      const std::uint16_t* texel = halves + (face * size * size + i) * 4;
      cube.faces[face].push_back(
          {glm::unpackHalf1x16(texel[0]), glm::unpackHalf1x16(texel[1]), glm::unpackHalf1x16(texel[2])});
    }
  return cube;
}

}  // namespace mane::render
