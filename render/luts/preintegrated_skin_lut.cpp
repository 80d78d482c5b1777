#include "render/luts/preintegrated_skin_lut.hpp"

#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include <glm/gtc/packing.hpp>

#include "render/descriptors.hpp"
#include "render/gpu_timer.hpp"
#include "render/pipelines.hpp"

namespace mane::render {

namespace {

// Mirrors the uniform block of shaders/preintegrated_skin.comp (std140: every member a vec4).
struct BakeUniforms {
  std::array<glm::vec4, kSkinGaussianCount> gaussians;  // x variance (mm²), yzw RGB weight
  std::array<glm::vec4, kSkinQuadratureNodes> nodes;    // x position, y weight
  glm::uvec4 sizes;                                     // x size, y range
  glm::vec4 scales;                                     // x maxCurvature, y maxRoughness, z reach
};
static_assert(sizeof(BakeUniforms) == 16 * (kSkinGaussianCount + kSkinQuadratureNodes + 2));

constexpr std::uint32_t kWorkgroupSize = 8;  // local_size_x/y of the shader

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

Result<void> checkFormat(const Device& device) {
  const vk::FormatFeatureFlags needed =
      vk::FormatFeatureFlagBits::eStorageImage | vk::FormatFeatureFlagBits::eSampledImage |
      vk::FormatFeatureFlagBits::eSampledImageFilterLinear | vk::FormatFeatureFlagBits::eTransferSrc;
  const vk::FormatFeatureFlags present =
      device.physicalDevice().getFormatProperties(PreintegratedSkinLut::kFormat).optimalTilingFeatures;
  if ((present & needed) != needed)
    return fail("pre-integrated skin table: " + device.info().name + " cannot store and linearly filter " +
                vk::to_string(PreintegratedSkinLut::kFormat) + " images (has " + vk::to_string(present) + ")");
  return {};
}

BakeUniforms bakeUniforms(const PreintegratedSkinSettings& settings) {
  BakeUniforms u{};
  for (std::size_t i = 0; i < kSkinGaussianCount; ++i) {
    const SkinGaussian& g = settings.profile.gaussians[i];
    u.gaussians[i] = glm::vec4(float(g.variance), glm::vec3(g.weight));
  }
  for (std::size_t i = 0; i < kSkinQuadratureNodes; ++i)
    u.nodes[i] = glm::vec4(float(skinQuadratureRule()[i].position), float(skinQuadratureRule()[i].weight), 0.0f, 0.0f);
  u.sizes = glm::uvec4(settings.size, static_cast<std::uint32_t>(settings.range), 0u, 0u);
  u.scales = glm::vec4(float(settings.maxCurvature), float(kMaxSkinRoughness), float(kProfileReach), 0.0f);
  return u;
}

}  // namespace

Result<PreintegratedSkinLut> PreintegratedSkinLut::create(const Device& device,
                                                          const PreintegratedSkinSettings& settings) {
  if (auto valid = validate(settings); !valid) return std::unexpected(valid.error());
  if (auto ok = checkFormat(device); !ok) return std::unexpected(ok.error());
  PreintegratedSkinLut lut;
  lut.device_ = &device;
  lut.settings_ = settings;
  try {
    lut.table_ =
        Image(device, ImageSettings{.extent = {settings.size, settings.size},
                                    .format = kFormat,
                                    .usage = vk::ImageUsageFlagBits::eStorage | vk::ImageUsageFlagBits::eSampled |
                                             vk::ImageUsageFlagBits::eTransferSrc,
                                    .layers = kLayers});
    lut.sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
    lut.bake();
  } catch (const std::exception& error) {
    return fail(std::string("pre-integrated skin table: baking failed: ") + error.what());
  }
  return lut;
}

void PreintegratedSkinLut::bake() {
  const Device& device = *device_;
  // The pipeline, descriptors and uniforms live only for the bake.
  const vk::raii::DescriptorSetLayout setLayout =
      makeSetLayout(device, {{vk::DescriptorType::eStorageImage, vk::ShaderStageFlagBits::eCompute},
                             {vk::DescriptorType::eUniformBuffer, vk::ShaderStageFlagBits::eCompute}});
  const Pipeline pipeline = makeComputePipeline(device, "preintegrated_skin.comp", setLayout);
  const vk::raii::DescriptorPool pool =
      makeDescriptorPool(device, 1, {{vk::DescriptorType::eStorageImage, 1}, {vk::DescriptorType::eUniformBuffer, 1}});
  const vk::raii::DescriptorSet set = allocateSet(device, pool, setLayout);

  const BakeUniforms uniforms = bakeUniforms(settings_);
  const Buffer uniformBuffer(device, sizeof(uniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                             vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  std::memcpy(uniformBuffer.mapped().data(), &uniforms, sizeof(uniforms));
  writeUniformBuffer(device, set, 1, uniformBuffer);
  const vk::DescriptorImageInfo storage{.imageView = *table_.view(), .imageLayout = Layout::eGeneral};
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set,
                                                              .dstBinding = 0,
                                                              .descriptorCount = 1,
                                                              .descriptorType = vk::DescriptorType::eStorageImage,
                                                              .pImageInfo = &storage},
                                       {});

  GpuTimer timer(device, 1);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    timer.reset(commands);
    transition(commands, table_, Layout::eUndefined, Layout::eGeneral, Stage::eNone, Access::eNone,
               Stage::eComputeShader, Access::eShaderStorageWrite);
    commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, *set, {});
    const std::uint32_t groups = (settings_.size + kWorkgroupSize - 1) / kWorkgroupSize;
    timer.begin(commands, PassName("preintegrated skin"));
    commands.dispatch(groups, groups, 1);
    timer.end(commands);
    transition(commands, table_, Layout::eGeneral, Layout::eShaderReadOnlyOptimal, Stage::eComputeShader,
               Access::eShaderStorageWrite, Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
  });
  timings_ = timer.results();
}

Result<std::vector<glm::vec4>> PreintegratedSkinLut::readTexels() const {
  const vk::Extent2D extent = table_.extent();
  const std::size_t texels = std::size_t(extent.width) * extent.height;
  const vk::DeviceSize bytes = texels * kLayers * 2;  // a half float per layer
  try {
    const Buffer host(*device_, bytes, vk::BufferUsageFlagBits::eTransferDst,
                      vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      transition(commands, table_, Layout::eShaderReadOnlyOptimal, Layout::eTransferSrcOptimal,
                 Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead, Stage::eCopy,
                 Access::eTransferRead);
      commands.copyImageToBuffer(
          *table_.image(), Layout::eTransferSrcOptimal, *host.buffer(),
          vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, kLayers},
                              .imageExtent = {extent.width, extent.height, 1}});
      transition(commands, table_, Layout::eTransferSrcOptimal, Layout::eShaderReadOnlyOptimal, Stage::eCopy,
                 Access::eTransferRead, Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
      const vk::MemoryBarrier2 toHost{.srcStageMask = Stage::eCopy,
                                      .srcAccessMask = Access::eTransferWrite,
                                      .dstStageMask = Stage::eHost,
                                      .dstAccessMask = Access::eHostRead};
      commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
    });
    std::vector<glm::vec4> result(texels);
    const std::byte* data = host.mapped().data();
    // The layers one after another, each texel by texel.
    for (std::size_t layer = 0; layer < kLayers; ++layer)
      for (std::size_t i = 0; i < texels; ++i) {
        std::uint16_t h;
        std::memcpy(&h, data + 2 * (layer * texels + i), sizeof(h));
        result[i][int(layer)] = glm::unpackHalf1x16(h);
      }
    return result;
  } catch (const std::exception& error) {
    return fail(std::string("pre-integrated skin table: read-back failed: ") + error.what());
  }
}

}  // namespace mane::render
