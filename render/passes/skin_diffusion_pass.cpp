#include "render/passes/skin_diffusion_pass.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

#include "render/descriptors.hpp"
#include "render/passes/skin_uv_seams.hpp"

namespace mane::render {
namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;
using Usage = vk::ImageUsageFlagBits;

// std140 mirror of the uniform block in shaders/skin_irradiance.glsl.
struct IrradianceUniforms {
  glm::mat4 model;
  glm::mat4 normalMatrix;
  glm::vec4 ambient;
  glm::vec4 lightDirection[SkinDiffusionPass::kMaxLights];
  glm::vec4 lightRadiance[SkinDiffusionPass::kMaxLights];
  glm::ivec4 counts;  // x lights, y normal map
  glm::vec4 scales;   // x millimetres per world unit
  HairShadowUniforms hairShadows;
  SurfaceShadowUniforms surfaceShadow;  // all 0 where the frame draws no surface shadows
};
static_assert(sizeof(IrradianceUniforms) == 304 + sizeof(HairShadowUniforms) + sizeof(SurfaceShadowUniforms));

// Where the hair shadow descriptors start in the irradiance set (shaders/skin_irradiance.glsl),
// and the surfaces' shadow map after them, read as depths and compared.
constexpr std::uint32_t kFirstShadowBinding = 2;
constexpr std::uint32_t kSurfaceShadowBinding = kFirstShadowBinding + HairShadowPass::kBindings;
static_assert(kSurfaceShadowBinding == 10, "shaders/skin_irradiance.glsl binds the surface shadow map at 10 and 11");

// Push constants of shaders/skin_diffusion_blur.comp.
struct BlurConstants {
  glm::vec4 stage;   // x σ (mm), y stretch off the mesh (mm per texel)
  glm::vec4 weight;  // rgb
  glm::ivec4 mode;   // x axis
};

constexpr std::uint32_t kWorkgroupSize = 8;  // local_size_x/y of the blur shader

Result<void> checkDevice(const Device& device, std::uint32_t size) {
  const vk::PhysicalDeviceLimits& limits = device.limits();
  const std::uint32_t largest =
      std::min({limits.maxImageDimension2D, limits.maxFramebufferWidth, limits.maxFramebufferHeight});
  if (size > largest)
    return fail("skin diffusion: size " + std::to_string(size) + " is past " + device.info().name + "'s limit of " +
                std::to_string(largest) + " texels per side");
  const auto check = [&](vk::Format format, vk::FormatFeatureFlags needed) -> Result<void> {
    const vk::FormatFeatureFlags present = device.physicalDevice().getFormatProperties(format).optimalTilingFeatures;
    if ((present & needed) != needed)
      return fail("skin diffusion: " + device.info().name + " lacks " + vk::to_string(needed & ~present) + " for " +
                  vk::to_string(format) + " images");
    return {};
  };
  using Feature = vk::FormatFeatureFlagBits;
  const vk::FormatFeatureFlags transfers = Feature::eTransferSrc | Feature::eTransferDst;
  if (auto ok = check(SkinDiffusionPass::kIrradianceFormat, Feature::eColorAttachment | Feature::eStorageImage |
                                                                Feature::eSampledImage |
                                                                Feature::eSampledImageFilterLinear | transfers);
      !ok)
    return ok;
  if (auto ok =
          check(SkinDiffusionPass::kStretchFormat, Feature::eColorAttachment | Feature::eSampledImage | transfers);
      !ok)
    return ok;
  return check(SkinDiffusionPass::kSeamDepthFormat, Feature::eDepthStencilAttachment);
}

void writeImage(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                vk::DescriptorType type, const Image& image, Layout layout, const vk::raii::Sampler& sampler) {
  const vk::DescriptorImageInfo info{
      .sampler = type == vk::DescriptorType::eCombinedImageSampler ? *sampler : vk::Sampler{},
      .imageView = *image.view(),
      .imageLayout = layout};
  device.device().updateDescriptorSets(
      vk::WriteDescriptorSet{
          .dstSet = *set, .dstBinding = binding, .descriptorCount = 1, .descriptorType = type, .pImageInfo = &info},
      {});
}

// Every blur's writes reach the next blur's reads; its reads finish before the next one writes.
void blurBarrier(const vk::raii::CommandBuffer& commands) {
  const vk::MemoryBarrier2 barrier{
      .srcStageMask = Stage::eComputeShader,
      .srcAccessMask = Access::eShaderStorageWrite,
      .dstStageMask = Stage::eComputeShader,
      .dstAccessMask = Access::eShaderSampledRead | Access::eShaderStorageRead | Access::eShaderStorageWrite};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &barrier});
}

}  // namespace

Result<void> validate(const SkinDiffusionSettings& settings) {
  if (settings.size < SkinDiffusionSettings::kMinSize || settings.size > SkinDiffusionSettings::kMaxSize ||
      settings.size % 8 != 0)
    return fail("skin diffusion settings: size is " + std::to_string(settings.size) +
                ", expected a multiple of 8 from " + std::to_string(SkinDiffusionSettings::kMinSize) + " to " +
                std::to_string(SkinDiffusionSettings::kMaxSize) + " texels per side (1024 or 2048 are usual)");
  if (auto valid = validate(settings.profile); !valid) return fail("skin diffusion settings: " + valid.error().message);
  return {};
}

Result<SkinDiffusionPass> SkinDiffusionPass::create(const Device& device, const SkinDiffusionSettings& settings,
                                                    const HairShadowPass* shadows,
                                                    const SurfaceShadowPass* surfaceShadows) {
  if (auto valid = validate(settings); !valid) return std::unexpected(valid.error());
  if (auto ok = checkDevice(device, settings.size); !ok) return std::unexpected(ok.error());
  SkinDiffusionPass pass;
  pass.device_ = &device;
  pass.settings_ = settings;
  pass.stages_ = skinDiffusionStages(settings.profile);
  pass.shadows_ = shadows;
  if (!shadows) {
    auto empty = HairShadowPass::create(device);
    if (!empty) return std::unexpected(empty.error());
    pass.noShadows_ = std::move(*empty);
    pass.shadows_ = pass.noShadows_.get();
  }
  pass.surfaceShadows_ = surfaceShadows;
  try {
    if (!surfaceShadows) {
      pass.noSurfaceShadows_ = std::make_unique<SurfaceShadowPass>(device, sizeof(glm::vec3));
      pass.surfaceShadows_ = pass.noSurfaceShadows_.get();
    }
    pass.createResources();
  } catch (const std::exception& error) {
    return fail(std::string("skin diffusion: creating the pass failed: ") + error.what());
  }
  return pass;
}

void SkinDiffusionPass::createResources() {
  const Device& device = *device_;
  const vk::Extent2D extent{settings_.size, settings_.size};
  const auto image = [&](vk::Format format, vk::ImageUsageFlags usage) {
    return Image(device, ImageSettings{.extent = extent, .format = format, .usage = usage});
  };
  const vk::ImageUsageFlags transfers = Usage::eTransferSrc | Usage::eTransferDst;
  irradiance_ = image(kIrradianceFormat, Usage::eColorAttachment | Usage::eStorage | transfers);
  stretch_ = image(kStretchFormat, Usage::eColorAttachment | Usage::eSampled | transfers);
  seamDepth_ = Image(device, ImageSettings{.extent = extent,
                                           .format = kSeamDepthFormat,
                                           .usage = Usage::eDepthStencilAttachment,
                                           .aspect = vk::ImageAspectFlagBits::eDepth});
  across_ = image(kIrradianceFormat, Usage::eStorage);
  blurred_ = image(kIrradianceFormat, Usage::eStorage);
  accumulated_ = image(kIrradianceFormat, Usage::eStorage | Usage::eSampled | transfers);
  coverage_ = image(kIrradianceFormat, Usage::eStorage);
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);

  uniforms_ = Buffer(device, sizeof(IrradianceUniforms),
                     vk::BufferUsageFlagBits::eUniformBuffer | vk::BufferUsageFlagBits::eTransferDst,
                     vk::MemoryPropertyFlagBits::eDeviceLocal);
  static constexpr std::uint8_t kFlatNormal[4] = {128, 128, 255, 255};
  flatNormal_ = Image::texture(device, 1, 1, kFlatNormal, vk::Format::eR8G8B8A8Unorm);
  normalSampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eRepeat, 1.0f);

  using ShaderStage = vk::ShaderStageFlagBits;
  // Uniforms, normal map, then the hair shadows (kFirstShadowBinding; 2 × 4 maps), then the
  // surfaces' shadow map twice (kSurfaceShadowBinding).
  const std::pair shadow{vk::DescriptorType::eCombinedImageSampler, vk::ShaderStageFlags(ShaderStage::eFragment)};
  irradianceLayout_ =
      makeSetLayout(device, {{vk::DescriptorType::eUniformBuffer, ShaderStage::eVertex | ShaderStage::eFragment},
                             {vk::DescriptorType::eCombinedImageSampler, ShaderStage::eFragment},
                             shadow,
                             shadow,
                             shadow,
                             shadow,
                             shadow,
                             shadow,
                             shadow,
                             shadow,
                             shadow,
                             shadow});
  static_assert(HairShadowPass::kBindings == 8);
  const std::pair sampled{vk::DescriptorType::eCombinedImageSampler, vk::ShaderStageFlags(ShaderStage::eCompute)};
  const std::pair storage{vk::DescriptorType::eStorageImage, vk::ShaderStageFlags(ShaderStage::eCompute)};
  blurLayout_ = makeSetLayout(device, {storage, sampled, storage, storage, storage});

  meshVerticesLayout_ = SkinDiffusionMesh::makeVerticesLayout(device);
  irradiancePipeline_ = makeGraphicsPipeline(
      device,
      GraphicsPipelineSettings{.vertexShader = "skin_irradiance.vert",
                               .fragmentShader = "skin_irradiance.frag",
                               .vertexBindings = {{.binding = 0,
                                                   .stride = sizeof(SkinDrawVertex),
                                                   .inputRate = vk::VertexInputRate::eVertex}},
                               .vertexAttributes = {{0, 0, vk::Format::eR32Uint, offsetof(SkinDrawVertex, source)},
                                                    {1, 0, vk::Format::eR32Sfloat, offsetof(SkinDrawVertex, depth)},
                                                    {2, 0, vk::Format::eR32G32Sfloat, offsetof(SkinDrawVertex, uv)}},
                               // UV layouts mirror islands freely: both windings are the surface.
                               .cullMode = vk::CullModeFlagBits::eNone,
                               .colorFormats = {kIrradianceFormat, kStretchFormat},
                               // The mesh's own triangles (depth 0) over any skirt; the nearest seam's skirt
                               // over the others; among equals the later, as without a depth test.
                               .depthFormat = kSeamDepthFormat,
                               .depthTest = true,
                               .depthWrite = true,
                               .depthCompare = vk::CompareOp::eLessOrEqual,
                               .setLayouts = {*irradianceLayout_, *meshVerticesLayout_},
                               .constants = shadows_->shaderConstants()});
  // The blur pipelines the stages use: specialised for their tap count and what they add up.
  for (std::size_t i = 0; i < stages_.size(); ++i)
    for (const Accumulate accumulate : {Accumulate::kNone, accumulation(i)}) {
      Pipeline& pipeline = blurPipelines_[stages_[i].halfTaps == kSkinBlurDenseHalfTaps][int(accumulate)];
      if (!*pipeline.pipeline)
        pipeline = makeComputePipeline(device, "skin_diffusion_blur.comp", blurLayout_, sizeof(BlurConstants),
                                       {std::uint32_t(stages_[i].halfTaps), std::uint32_t(accumulate)});
    }

  pool_ = makeDescriptorPool(device, 4,
                             {{vk::DescriptorType::eUniformBuffer, 1},
                              {vk::DescriptorType::eCombinedImageSampler, 6 + HairShadowPass::kBindings},
                              {vk::DescriptorType::eStorageImage, 12}});
  irradianceSet_ = allocateSet(device, pool_, irradianceLayout_);
  writeUniformBuffer(device, irradianceSet_, 0, uniforms_);
  writeSampledImage(device, irradianceSet_, 1, flatNormal_, normalSampler_);
  writeSampledImage(device, irradianceSet_, kSurfaceShadowBinding, surfaceShadows_->image().view(),
                    surfaceShadows_->depthSampler());
  writeSampledImage(device, irradianceSet_, kSurfaceShadowBinding + 1, surfaceShadows_->image().view(),
                    surfaceShadows_->compareSampler());
  refreshShadows();

  // The blurs: source, stretch, destination, sums of E·c, sums of c.
  const auto blurSet = [&](const Image& source, const Image& destination) {
    vk::raii::DescriptorSet set = allocateSet(device, pool_, blurLayout_);
    writeImage(device, set, 0, vk::DescriptorType::eStorageImage, source, Layout::eGeneral, sampler_);
    writeImage(device, set, 1, vk::DescriptorType::eCombinedImageSampler, stretch_, Layout::eShaderReadOnlyOptimal,
               sampler_);
    writeImage(device, set, 2, vk::DescriptorType::eStorageImage, destination, Layout::eGeneral, sampler_);
    writeImage(device, set, 3, vk::DescriptorType::eStorageImage, accumulated_, Layout::eGeneral, sampler_);
    writeImage(device, set, 4, vk::DescriptorType::eStorageImage, coverage_, Layout::eGeneral, sampler_);
    return set;
  };
  firstAcross_ = blurSet(irradiance_, across_);
  laterAcross_ = blurSet(blurred_, across_);
  down_ = blurSet(across_, blurred_);

  // The maps a final pass or a read-back may see before the first frame: cleared, in the layouts
  // they keep between frames (the irradiance GENERAL: the blurs load it as a storage image).
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    for (const Image* cleared : {&irradiance_, &stretch_, &accumulated_}) {
      const Layout steady = cleared == &irradiance_ ? Layout::eGeneral : Layout::eShaderReadOnlyOptimal;
      transition(commands, *cleared, Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone, Access::eNone,
                 Stage::eClear, Access::eTransferWrite);
      commands.clearColorImage(*cleared->image(), Layout::eTransferDstOptimal,
                               vk::ClearColorValue(std::array{0.0f, 0.0f, 0.0f, 0.0f}),
                               vk::ImageSubresourceRange{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1});
      transition(commands, *cleared, Layout::eTransferDstOptimal, steady, Stage::eClear, Access::eTransferWrite,
                 Stage::eFragmentShader | Stage::eComputeShader,
                 Access::eShaderSampledRead | Access::eShaderStorageRead);
    }
  });
}

Result<void> SkinDiffusionPass::setNormalMap(const std::optional<TextureData>& normalMap) {
  if (!normalMap) {
    writeSampledImage(*device_, irradianceSet_, 1, flatNormal_, normalSampler_);
    normalMap_ = Image();
    hasNormalMap_ = false;
    return {};
  }
  const TextureData& map = *normalMap;
  if (map.width == 0 || map.height == 0 || map.rgba.size() != std::size_t(map.width) * map.height * 4)
    return fail("skin diffusion: the normal map has " + std::to_string(map.rgba.size()) + " bytes for " +
                std::to_string(map.width) + "×" + std::to_string(map.height) + " texels, expected 4 per texel");
  try {
    Image uploaded = Image::texture(*device_, map.width, map.height, map.rgba, vk::Format::eR8G8B8A8Unorm);
    writeSampledImage(*device_, irradianceSet_, 1, uploaded, normalSampler_);
    normalMap_ = std::move(uploaded);
  } catch (const std::exception& error) {
    return fail(std::string("skin diffusion: uploading the normal map failed: ") + error.what());
  }
  hasNormalMap_ = true;
  return {};
}

void SkinDiffusionPass::refreshShadows() {
  shadows_->writeDescriptors(irradianceSet_, kFirstShadowBinding);
}

void SkinDiffusionPass::declare(FrameGraph::Builder& pass) const {
  shadows_->declareReads(pass, Stage::eFragmentShader);
  pass.produce(accumulated_, ResourceUse::sampled(Stage::eFragmentShader | Stage::eComputeShader));
}

void SkinDiffusionPass::declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const {
  pass.read(accumulated_, ResourceUse::sampled(stages));
}

void SkinDiffusionPass::recordIrradiance(const vk::raii::CommandBuffer& commands, const SkinDiffusionMesh& mesh,
                                         const SkinIrradianceInput& input) {
  IrradianceUniforms uniforms{};
  uniforms.model = input.model;
  uniforms.normalMatrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(input.model))));
  uniforms.ambient = glm::vec4(input.ambient, 0.0f);
  int lights = 0;
  for (const DirectionalLight& light : input.lights) {
    const float length = glm::length(light.direction);
    if (lights == int(kMaxLights)) break;
    if (!(length > 0.0f)) continue;  // no direction: no light
    uniforms.lightDirection[lights] = glm::vec4(light.direction / length, 0.0f);
    uniforms.lightRadiance[lights] = glm::vec4(light.color * light.intensity, 0.0f);
    ++lights;
  }
  uniforms.counts = glm::ivec4(lights, hasNormalMap_ ? 1 : 0, 0, 0);
  uniforms.scales = glm::vec4(float(settings_.profile.millimetresPerUnit), 0.0f, 0.0f, 0.0f);
  uniforms.hairShadows = shadows_->uniforms();
  if (input.surfaceShadows) uniforms.surfaceShadow = surfaceShadows_->uniforms();

  // A uniform scale of the model (the cube root of its determinant) scales the mesh's uv stretch.
  const double modelScale = std::cbrt(std::abs(double(glm::determinant(glm::mat3(input.model)))));
  const double offMesh = mesh.uvScale() * modelScale * settings_.profile.millimetresPerUnit / settings_.size;
  uncoveredStretch_ = std::isfinite(offMesh) && offMesh > 0.0 ? offMesh : 1.0;

  const vk::BufferMemoryBarrier2 beforeUpdate{.srcStageMask = Stage::eVertexShader | Stage::eFragmentShader,
                                              .srcAccessMask = Access::eUniformRead,
                                              .dstStageMask = Stage::eTransfer,
                                              .dstAccessMask = Access::eTransferWrite,
                                              .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                              .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                              .buffer = *uniforms_.buffer(),
                                              .size = VK_WHOLE_SIZE};
  commands.pipelineBarrier2(vk::DependencyInfo{.bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &beforeUpdate});
  commands.updateBuffer<IrradianceUniforms>(*uniforms_.buffer(), 0, uniforms);
  vk::BufferMemoryBarrier2 afterUpdate = beforeUpdate;
  std::swap(afterUpdate.srcStageMask, afterUpdate.dstStageMask);
  std::swap(afterUpdate.srcAccessMask, afterUpdate.dstAccessMask);
  commands.pipelineBarrier2(vk::DependencyInfo{.bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &afterUpdate});

  // The maps' previous contents (last frame's, read by its blurs or a read-back) are dropped.
  for (const Image* target : {&irradiance_, &stretch_})
    transition(commands, *target, Layout::eUndefined, Layout::eColorAttachmentOptimal,
               Stage::eComputeShader | Stage::eFragmentShader | Stage::eTransfer, Access::eNone,
               Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
  const auto attachment = [](const Image& image) {
    return vk::RenderingAttachmentInfo{.imageView = *image.view(),
                                       .imageLayout = Layout::eColorAttachmentOptimal,
                                       .loadOp = vk::AttachmentLoadOp::eClear,
                                       .storeOp = vk::AttachmentStoreOp::eStore,
                                       .clearValue = {.color = {.float32 = std::array{0.0f, 0.0f, 0.0f, 0.0f}}}};
  };
  const std::array attachments{attachment(irradiance_), attachment(stretch_)};
  transition(commands, seamDepth_, Layout::eUndefined, Layout::eDepthAttachmentOptimal,
             Stage::eEarlyFragmentTests | Stage::eLateFragmentTests, Access::eNone,
             Stage::eEarlyFragmentTests | Stage::eLateFragmentTests,
             Access::eDepthStencilAttachmentRead | Access::eDepthStencilAttachmentWrite);
  const vk::RenderingAttachmentInfo depth{.imageView = *seamDepth_.view(),
                                          .imageLayout = Layout::eDepthAttachmentOptimal,
                                          .loadOp = vk::AttachmentLoadOp::eClear,
                                          .storeOp = vk::AttachmentStoreOp::eDontCare,
                                          .clearValue = {.depthStencil = {.depth = 1.0f}}};
  const vk::Extent2D extent{settings_.size, settings_.size};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = extent},
                                            .layerCount = 1,
                                            .colorAttachmentCount = attachments.size(),
                                            .pColorAttachments = attachments.data(),
                                            .pDepthAttachment = &depth});
  setViewportAndScissor(commands, extent);
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *irradiancePipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *irradiancePipeline_.layout, 0,
                              {*irradianceSet_, *mesh.verticesSet()}, {});
  commands.bindVertexBuffers(0, {*mesh.drawList().buffer()}, {vk::DeviceSize{0}});
  commands.draw(mesh.drawCount(), 1, 0, 0);
  commands.endRendering();
  transition(commands, irradiance_, Layout::eColorAttachmentOptimal, Layout::eGeneral, Stage::eColorAttachmentOutput,
             Access::eColorAttachmentWrite, Stage::eComputeShader, Access::eShaderStorageRead);
  transition(commands, stretch_, Layout::eColorAttachmentOptimal, Layout::eShaderReadOnlyOptimal,
             Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eComputeShader,
             Access::eShaderSampledRead);
}

void SkinDiffusionPass::recordBlurs(const vk::raii::CommandBuffer& commands) const {
  // Scratch and sums start each frame anew: their old contents are dropped.
  for (const Image* scratch : {&across_, &blurred_, &coverage_, &accumulated_})
    transition(commands, *scratch, Layout::eUndefined, Layout::eGeneral,
               Stage::eComputeShader | Stage::eFragmentShader | Stage::eTransfer, Access::eNone, Stage::eComputeShader,
               Access::eShaderStorageWrite | Access::eShaderStorageRead | Access::eShaderSampledRead);
  const std::uint32_t groups = settings_.size / kWorkgroupSize;  // validate() asks for a multiple
  const auto dispatch = [&](const Pipeline& pipeline, const vk::raii::DescriptorSet& set,
                            const BlurConstants& constants) {
    commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, {*set}, {});
    commands.pushConstants<BlurConstants>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
    commands.dispatch(groups, groups, 1);
  };
  for (std::size_t i = 0; i < stages_.size(); ++i) {
    const SkinDiffusionStage& stage = stages_[i];
    const auto& pipelines = blurPipelines_[stage.halfTaps == kSkinBlurDenseHalfTaps];
    const glm::vec4 width(float(stage.sigma), float(uncoveredStretch_), 0.0f, 0.0f);
    dispatch(pipelines[int(Accumulate::kNone)], i == 0 ? firstAcross_ : laterAcross_,
             {width, glm::vec4(0.0f), glm::ivec4(0)});
    blurBarrier(commands);
    dispatch(pipelines[int(accumulation(i))], down_,
             {width, glm::vec4(glm::vec3(stage.weight), 0.0f), glm::ivec4(1, 0, 0, 0)});
    if (i + 1 < stages_.size()) blurBarrier(commands);
  }
  transition(commands, accumulated_, Layout::eGeneral, Layout::eShaderReadOnlyOptimal, Stage::eComputeShader,
             Access::eShaderStorageWrite, Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
}

}  // namespace mane::render
