#include "render/passes/hair_occlusion_pass.hpp"

#include "render/descriptors.hpp"

namespace mane::render {

namespace {

struct Grid {
  glm::uvec2 tiles;
  std::uint32_t tileSize;
};

constexpr std::uint32_t kWorkgroup = 8;  // local_size_x and _y of shaders/hair_occlusion.glsl

}  // namespace

HairOcclusionPass::HairOcclusionPass(const Device& device, const RenderTarget& target) : target_(&target) {
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

void HairOcclusionPass::declare(FrameGraph::Builder& pass) const {
  pass.read(target_->depth(), ResourceUse::sampled(vk::PipelineStageFlagBits2::eComputeShader));
  pass.write(tiles_, ResourceUse::storageWrite(vk::PipelineStageFlagBits2::eComputeShader));
}

void HairOcclusionPass::execute(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.layout, 0, {*set_}, {});
  commands.pushConstants<Grid>(*pipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0,
                               Grid{.tiles = grid_.tiles, .tileSize = grid_.tileSize});
  commands.dispatch((grid_.tiles.x + kWorkgroup - 1) / kWorkgroup, (grid_.tiles.y + kWorkgroup - 1) / kWorkgroup, 1);
}

}  // namespace mane::render
