#include "render/passes/hair_occlusion.hpp"

#include "render/descriptors.hpp"

namespace mane::render {

namespace {

struct Grid {
  glm::uvec2 tiles;
  std::uint32_t tileSize;
};

constexpr std::uint32_t kWorkgroup = 8;  // local_size_x and _y of shaders/hair_occlusion.glsl

}  // namespace

HairOcclusion::HairOcclusion(const Device& device, const RenderTarget& target) : target_(&target) {
  using Type = vk::DescriptorType;
  const auto compute = vk::ShaderStageFlags(vk::ShaderStageFlagBits::eCompute);
  const vk::Extent2D extent = target.extent();
  grid_ = {.tiles = {(extent.width + kTileSize - 1) / kTileSize, (extent.height + kTileSize - 1) / kTileSize},
           .tileSize = kTileSize};
  tiles_ = Buffer(device, vk::DeviceSize(grid_.tiles.x) * grid_.tiles.y * sizeof(float),
                  vk::BufferUsageFlagBits::eStorageBuffer, vk::MemoryPropertyFlagBits::eDeviceLocal);
  sampler_ =
      vk::raii::Sampler(device.device(), vk::SamplerCreateInfo{.magFilter = vk::Filter::eNearest,
                                                               .minFilter = vk::Filter::eNearest,
                                                               .mipmapMode = vk::SamplerMipmapMode::eNearest,
                                                               .addressModeU = vk::SamplerAddressMode::eClampToEdge,
                                                               .addressModeV = vk::SamplerAddressMode::eClampToEdge,
                                                               .addressModeW = vk::SamplerAddressMode::eClampToEdge});
  setLayout_ = makeSetLayout(device, {{Type::eCombinedImageSampler, compute}, {Type::eStorageBuffer, compute}});
  pipeline_ = makeComputePipeline(device, target.multisampled() ? "hair_occlusion_msaa.comp" : "hair_occlusion.comp",
                                  setLayout_, sizeof(Grid));
  pool_ = makeDescriptorPool(device, 1, {{Type::eCombinedImageSampler, 1}, {Type::eStorageBuffer, 1}});
  set_ = allocateSet(device, pool_, setLayout_);
  writeSampledImage(device, set_, 0, target.depth().view(), sampler_);
  writeStorageBuffer(device, set_, 1, tiles_);
}

void HairOcclusion::record(const vk::raii::CommandBuffer& commands) const {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  const vk::Image depth = *target_->depth().image();
  const vk::ImageSubresourceRange range{vk::ImageAspectFlagBits::eDepth, 0, 1, 0, 1};
  // The previous frame's hair choice read the tiles before they are written again.
  const vk::MemoryBarrier2 tilesRead{.srcStageMask = Stage::eComputeShader,
                                     .srcAccessMask = Access::eShaderStorageRead,
                                     .dstStageMask = Stage::eComputeShader,
                                     .dstAccessMask = Access::eShaderStorageWrite};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &tilesRead});
  imageBarrier(commands, depth, range, Layout::eDepthAttachmentOptimal, Layout::eShaderReadOnlyOptimal,
               Stage::eEarlyFragmentTests | Stage::eLateFragmentTests, Access::eDepthStencilAttachmentWrite,
               Stage::eComputeShader, Access::eShaderSampledRead);
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.layout, 0, {*set_}, {});
  commands.pushConstants<Grid>(*pipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0,
                               Grid{.tiles = grid_.tiles, .tileSize = grid_.tileSize});
  commands.dispatch((grid_.tiles.x + kWorkgroup - 1) / kWorkgroup, (grid_.tiles.y + kWorkgroup - 1) / kWorkgroup, 1);
  imageBarrier(commands, depth, range, Layout::eShaderReadOnlyOptimal, Layout::eDepthAttachmentOptimal,
               Stage::eComputeShader, Access::eShaderSampledRead,
               Stage::eEarlyFragmentTests | Stage::eLateFragmentTests,
               Access::eDepthStencilAttachmentRead | Access::eDepthStencilAttachmentWrite);
  const vk::MemoryBarrier2 tilesWritten{.srcStageMask = Stage::eComputeShader,
                                        .srcAccessMask = Access::eShaderStorageWrite,
                                        .dstStageMask = Stage::eComputeShader,
                                        .dstAccessMask = Access::eShaderStorageRead};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &tilesWritten});
}

}  // namespace mane::render
