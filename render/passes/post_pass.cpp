#include "render/passes/post_pass.hpp"

#include <cmath>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#include <glm/gtc/packing.hpp>

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

// Push constants of shaders/post_blur.comp: w[k] = weights[k / 4][k % 4].
struct BlurConstants {
  float weights[12];
};
static_assert(kGlowMaxRadius < 12);

// Push constants of shaders/post_adapt.comp.
struct AdaptConstants {
  float rate;
  float key;
  float exposure;
};

static_assert(sizeof(PostExposure) == 16);

// Push constants of shaders/post_ray_polar.comp and post_ray_unpolar.comp.
struct RayCentreConstants {
  glm::vec2 centre;
  glm::ivec2 extent;
};

// Push constants of shaders/post_ray_blur.comp, which runs one invocation per polar column.
struct RayBlurConstants {
  glm::ivec2 extent;
  float decay;
  float firstWeight;   // w[0] of godRayWeights
  float decayPastEnd;  // decay^kGodRayTaps
};
constexpr std::uint32_t kRayBlurColumns = 32;  // local_size_x of shaders/post_ray_blur.comp

// Push constants of shaders/post_overlay.comp.
struct OverlayConstants {
  float exposure;
  float glowStrength;
  float godRays;
};

// The overlay keeps the gain in full precision (the frame's scale): a float format the output
// pass can filter.
constexpr vk::Format kOverlayFormat = vk::Format::eR32G32B32A32Sfloat;

vk::Extent2D toExtent(glm::uvec2 size) {
  return {size.x, size.y};
}

// A pass's storage writes reach the next pass's reads; its reads finish before the next writes.
void computeToCompute(const vk::raii::CommandBuffer& commands) {
  const vk::MemoryBarrier2 barrier{.srcStageMask = Stage::eComputeShader,
                                   .srcAccessMask = Access::eShaderStorageWrite,
                                   .dstStageMask = Stage::eComputeShader,
                                   .dstAccessMask = Access::eShaderStorageRead | Access::eShaderStorageWrite};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &barrier});
}

// The half-float RGBA texels of `image` (GENERAL, written by compute shaders), widened.
HdrImage readHalfImage(const Device& device, const Image& image) {
  const vk::Extent2D extent = image.extent();
  const std::size_t values = std::size_t(extent.width) * extent.height * 4;
  const Buffer host(device, values * 2, vk::BufferUsageFlagBits::eTransferDst,
                    vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    const vk::MemoryBarrier2 toCopy{.srcStageMask = Stage::eComputeShader,
                                    .srcAccessMask = Access::eShaderStorageWrite,
                                    .dstStageMask = Stage::eCopy,
                                    .dstAccessMask = Access::eTransferRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toCopy});
    commands.copyImageToBuffer(*image.image(), Layout::eGeneral, *host.buffer(),
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                                   .imageExtent = {extent.width, extent.height, 1}});
    const vk::MemoryBarrier2 toHost{.srcStageMask = Stage::eCopy,
                                    .srcAccessMask = Access::eTransferWrite,
                                    .dstStageMask = Stage::eHost,
                                    .dstAccessMask = Access::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
  });
  HdrImage result{extent.width, extent.height, std::vector<glm::vec4>(values / 4)};
  for (std::size_t i = 0; i < values; ++i) {
    std::uint16_t half;
    std::memcpy(&half, host.mapped().data() + 2 * i, 2);
    result.texels[i / 4][int(i % 4)] = glm::unpackHalf1x16(half);
  }
  return result;
}

Result<HdrImage> readOrFail(const Device& device, const Image& image, const char* what) {
  try {
    return readHalfImage(device, image);
  } catch (const std::exception& error) {
    return fail(std::string("post chain: reading the ") + what + " back failed: " + error.what());
  }
}

}  // namespace

Result<void> validate(const PostSettings& settings) {
  const auto bad = [](const char* field, float value, const char* expected) {
    return fail(std::string("post settings: ") + field + " is " + std::to_string(value) + ", expected " + expected);
  };
  if (settings.toneMapping != ToneMapping::kLinear && settings.toneMapping != ToneMapping::kReinhard)
    return fail("post settings: unknown tone mapping " + std::to_string(std::uint32_t(settings.toneMapping)));
  if (!(std::isfinite(settings.key) && settings.key > 0.0f)) return bad("key", settings.key, "a finite value > 0");
  if (!(settings.glowStrength >= 0.0f && settings.glowStrength <= 1.0f))
    return bad("glowStrength", settings.glowStrength, "a value from 0 to 1");
  if (!(std::isfinite(settings.adaptationSeconds) && settings.adaptationSeconds >= 0.0f))
    return bad("adaptationSeconds", settings.adaptationSeconds, "a finite time ≥ 0 s");
  if (!(std::isfinite(settings.frameSeconds) && settings.frameSeconds >= 0.0f))
    return bad("frameSeconds", settings.frameSeconds, "a finite time ≥ 0 s");
  if (!(std::isfinite(settings.godRays) && settings.godRays >= 0.0f))
    return bad("godRays", settings.godRays, "a finite strength ≥ 0");
  if (!(std::isfinite(settings.godRayThreshold) && settings.godRayThreshold >= 0.0f))
    return bad("godRayThreshold", settings.godRayThreshold, "a finite luminance ≥ 0");
  if (!(settings.godRayDecay > 0.0f && settings.godRayDecay <= 1.0f))
    return bad("godRayDecay", settings.godRayDecay, "a value in (0, 1]");
  return {};
}

std::optional<glm::vec2> godRayLightUv(const Camera& camera, glm::vec3 direction, float aspect) {
  // A point at infinity: w = 0 before the projection, so only the direction counts.
  const glm::vec4 clip = camera.projection(aspect) * camera.view() * glm::vec4(direction, 0.0f);
  if (!(clip.w > 0.0f)) return std::nullopt;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  if (!(std::abs(ndc.x) <= 1.0f && std::abs(ndc.y) <= 1.0f)) return std::nullopt;
  return 0.5f * ndc + 0.5f;
}

PostPass::PostPass(const Device& device, const Image& frame)
    : device_(&device), frame_(&frame), frameSize_(frame.extent()), kernel_(glowKernel()) {
  using Usage = vk::ImageUsageFlagBits;
  const glm::uvec2 quarter = postQuarterSize({frameSize_.width, frameSize_.height});
  const auto image = [&](glm::uvec2 size, vk::ImageUsageFlags usage) {
    return Image(device, ImageSettings{.extent = toExtent(size), .format = kFormat, .usage = usage});
  };
  const vk::ImageUsageFlags common = Usage::eStorage | Usage::eTransferSrc | Usage::eTransferDst;
  downsampled_ = image(quarter, common);
  across_ = image(quarter, common);
  glow_ = image(quarter, common);
  tiny_ = image(postTinySize(quarter), common);
  rayBright_ = image(quarter, common);
  polar_ = image(godRayPolarSize(quarter), common);
  polarBlurred_ = image(godRayPolarSize(quarter), common);
  godRays_ = image(quarter, common);
  if (!(device.physicalDevice().getFormatProperties(kOverlayFormat).optimalTilingFeatures &
        vk::FormatFeatureFlagBits::eSampledImageFilterLinear))
    throw std::runtime_error("post chain: the device cannot filter R32G32B32A32_SFLOAT images, the overlay's format");
  overlay_ = Image(device, ImageSettings{.extent = toExtent(quarter),
                                         .format = kOverlayFormat,
                                         .usage = Usage::eStorage | Usage::eSampled | Usage::eTransferDst});
  exposure_ = Buffer(device, sizeof(PostExposure), vk::BufferUsageFlagBits::eStorageBuffer,
                     vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  resetExposure();
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);

  using ShaderStage = vk::ShaderStageFlagBits;
  const vk::ShaderStageFlags compute = ShaderStage::eCompute;
  const std::pair storage{vk::DescriptorType::eStorageImage, compute};
  sampledLayout_ = makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, compute}, storage});
  storageLayout_ = makeSetLayout(device, {storage, storage});
  adaptLayout_ = makeSetLayout(device, {storage, {vk::DescriptorType::eStorageBuffer, compute}});
  overlayLayout_ = makeSetLayout(device, {storage, storage, {vk::DescriptorType::eStorageBuffer, compute}, storage});

  const auto radius = std::uint32_t(kernel_.size() - 1);
  downsamplePipeline_ = makeComputePipeline(device, "post_downsample.comp", sampledLayout_);
  for (std::uint32_t axis = 0; axis < 2; ++axis)
    blurPipelines_[axis] =
        makeComputePipeline(device, "post_blur.comp", storageLayout_, sizeof(BlurConstants), {radius, axis});
  tinyPipeline_ = makeComputePipeline(device, "post_tiny.comp", storageLayout_, 0, {postTinyBlock(quarter)});
  adaptPipeline_ = makeComputePipeline(device, "post_adapt.comp", adaptLayout_, sizeof(AdaptConstants));
  rayBrightPipeline_ = makeComputePipeline(device, "post_ray_bright.comp", storageLayout_, sizeof(float));
  rayPolarPipeline_ = makeComputePipeline(device, "post_ray_polar.comp", storageLayout_, sizeof(RayCentreConstants));
  rayBlurPipeline_ = makeComputePipeline(device, "post_ray_blur.comp", storageLayout_, sizeof(RayBlurConstants),
                                         {std::uint32_t(kGodRayTaps), std::uint32_t(kGodRayStep)});
  rayUnpolarPipeline_ =
      makeComputePipeline(device, "post_ray_unpolar.comp", storageLayout_, sizeof(RayCentreConstants));

  pool_ = makeDescriptorPool(device, 12,
                             {{vk::DescriptorType::eCombinedImageSampler, 1},
                              {vk::DescriptorType::eStorageImage, 24},
                              {vk::DescriptorType::eStorageBuffer, 2}});
  downsampleSet_ = allocateSet(device, pool_, sampledLayout_);
  writeSampledImage(device, downsampleSet_, 0, frame, sampler_);
  writeStorageImage(device, downsampleSet_, 1, downsampled_.view());
  const auto pair = [&](const Image& source, const Image& destination) {
    vk::raii::DescriptorSet set = allocateSet(device, pool_, storageLayout_);
    writeStorageImage(device, set, 0, source.view());
    writeStorageImage(device, set, 1, destination.view());
    return set;
  };
  acrossSets_[0] = pair(downsampled_, across_);
  acrossSets_[1] = pair(glow_, across_);
  downSet_ = pair(across_, glow_);
  tinySet_ = pair(downsampled_, tiny_);
  adaptSet_ = allocateSet(device, pool_, adaptLayout_);
  writeStorageImage(device, adaptSet_, 0, tiny_.view());
  writeStorageBuffer(device, adaptSet_, 1, exposure_);
  rayBrightSet_ = pair(downsampled_, rayBright_);
  rayPolarSet_ = pair(rayBright_, polar_);
  rayBlurSet_ = pair(polar_, polarBlurred_);
  rayUnpolarSets_[0] = pair(polar_, godRays_);
  rayUnpolarSets_[1] = pair(polarBlurred_, godRays_);
  overlaySet_ = allocateSet(device, pool_, overlayLayout_);
  writeStorageImage(device, overlaySet_, 0, glow_.view());
  writeStorageImage(device, overlaySet_, 1, godRays_.view());
  writeStorageBuffer(device, overlaySet_, 2, exposure_);
  writeStorageImage(device, overlaySet_, 3, overlay_.view());
  initialiseImages();
}

// GENERAL from the start, and black.
void PostPass::initialiseImages() {
  device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    for (const Image* image :
         {&downsampled_, &across_, &glow_, &tiny_, &rayBright_, &polar_, &polarBlurred_, &godRays_, &overlay_}) {
      transition(commands, *image, Layout::eUndefined, Layout::eGeneral, Stage::eNone, Access::eNone, Stage::eClear,
                 Access::eTransferWrite);
      commands.clearColorImage(*image->image(), Layout::eGeneral,
                               vk::ClearColorValue(std::array{0.0f, 0.0f, 0.0f, 0.0f}),
                               vk::ImageSubresourceRange{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1});
    }
    const vk::MemoryBarrier2 cleared{
        .srcStageMask = Stage::eClear,
        .srcAccessMask = Access::eTransferWrite,
        .dstStageMask = Stage::eComputeShader | Stage::eFragmentShader,
        .dstAccessMask = Access::eShaderStorageRead | Access::eShaderStorageWrite | Access::eShaderSampledRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &cleared});
  });
}

void PostPass::resetExposure() {
  const PostExposure fresh{};
  std::memcpy(exposure_.mapped().data(), &fresh, sizeof(fresh));
}

PostExposure PostPass::readExposure() const {
  PostExposure state;
  std::memcpy(&state, exposure_.mapped().data(), sizeof(state));
  return state;
}

glm::vec2 PostPass::overlayUvScale() const {
  const vk::Extent2D quarter = glow_.extent();
  return {float(frameSize_.width) / float(kPostDownsampleFactor * quarter.width),
          float(frameSize_.height) / float(kPostDownsampleFactor * quarter.height)};
}

glm::vec2 PostPass::godRayCentre(glm::vec2 lightUv) const {
  return lightUv * glm::vec2(float(frameSize_.width), float(frameSize_.height)) / float(kPostDownsampleFactor);
}

void PostPass::dispatch(const vk::raii::CommandBuffer& commands, const Pipeline& pipeline,
                        const vk::raii::DescriptorSet& set, vk::Extent2D size, vk::Extent2D workgroup) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, {*set}, {});
  commands.dispatch((size.width + workgroup.width - 1) / workgroup.width,
                    (size.height + workgroup.height - 1) / workgroup.height, 1);
}

void PostPass::record(const vk::raii::CommandBuffer& commands, const PostSettings& settings, float exposure,
                      std::optional<glm::vec2> godRayLight) {
  if (!runs(settings)) return;
  recordDownsample(commands);
  if (settings.autoGain) recordAutoGain(commands, settings, exposure);
  if (settings.glowStrength > 0.0f) recordGlow(commands);
  if (settings.godRays > 0.0f && godRayLight) recordGodRays(commands, settings, *godRayLight);
  recordHandOff(commands, settings, exposure);
}

void PostPass::recordDownsample(const vk::raii::CommandBuffer& commands) {
  godRaysRecorded_ = false;
  // Last frame's readers of these images (the output pass, the blurs, the adaptation) finish
  // before this frame overwrites them.
  const vk::MemoryBarrier2 previousFrame{.srcStageMask = Stage::eComputeShader | Stage::eFragmentShader,
                                         .srcAccessMask = Access::eShaderStorageWrite,
                                         .dstStageMask = Stage::eComputeShader,
                                         .dstAccessMask = Access::eShaderStorageRead | Access::eShaderStorageWrite};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &previousFrame});
  dispatch(commands, downsamplePipeline_, downsampleSet_, downsampled_.extent());
  computeToCompute(commands);
}

void PostPass::declareDownsample(FrameGraph::Builder& pass) const {
  pass.read(*frame_, ResourceUse::sampled(Stage::eComputeShader));
}

void PostPass::recordAutoGain(const vk::raii::CommandBuffer& commands, const PostSettings& settings, float exposure) {
  dispatch(commands, tinyPipeline_, tinySet_, tiny_.extent());
  computeToCompute(commands);
  const double rate =
      settings.resetAdaptation ? 1.0 : adaptationRate(settings.frameSeconds, settings.adaptationSeconds);
  const AdaptConstants constants{.rate = float(rate), .key = settings.key, .exposure = exposure};
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *adaptPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *adaptPipeline_.layout, 0, {*adaptSet_}, {});
  commands.pushConstants<AdaptConstants>(*adaptPipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
  commands.dispatch(1, 1, 1);  // one workgroup: a fixed reduction order
}

void PostPass::recordGlow(const vk::raii::CommandBuffer& commands) const {
  BlurConstants constants{};
  for (std::size_t k = 0; k < kernel_.size(); ++k) constants.weights[k] = kernel_[k];
  for (int pass = 0; pass < 2; ++pass) {
    for (int axis = 0; axis < 2; ++axis) {
      const Pipeline& pipeline = blurPipelines_[axis];
      commands.pushConstants<BlurConstants>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
      dispatch(commands, pipeline, axis == 0 ? acrossSets_[pass] : downSet_, glow_.extent());
      const bool last = pass == 1 && axis == 1;  // recordHandOff's barrier follows it
      if (!last) computeToCompute(commands);
    }
  }
}

void PostPass::recordGodRays(const vk::raii::CommandBuffer& commands, const PostSettings& settings, glm::vec2 lightUv,
                             bool blur) {
  const vk::ShaderStageFlags compute = vk::ShaderStageFlagBits::eCompute;
  commands.pushConstants<float>(*rayBrightPipeline_.layout, compute, 0, settings.godRayThreshold);
  dispatch(commands, rayBrightPipeline_, rayBrightSet_, rayBright_.extent());
  computeToCompute(commands);
  // Only the angles and radii this light reaches: a quarter of the image for a light at the centre.
  const glm::vec2 centre = godRayCentre(lightUv);
  const glm::uvec2 used = godRayPolarExtent({rayBright_.extent().width, rayBright_.extent().height}, centre);
  const RayCentreConstants polarConstants{.centre = centre, .extent = glm::ivec2(used)};
  commands.pushConstants<RayCentreConstants>(*rayPolarPipeline_.layout, compute, 0, polarConstants);
  dispatch(commands, rayPolarPipeline_, rayPolarSet_, {used.x, used.y});
  computeToCompute(commands);
  if (blur) {
    const RayBlurConstants constants{.extent = glm::ivec2(used),
                                     .decay = settings.godRayDecay,
                                     .firstWeight = godRayWeights(settings.godRayDecay)[0],
                                     .decayPastEnd = float(std::pow(double(settings.godRayDecay), kGodRayTaps))};
    commands.pushConstants<RayBlurConstants>(*rayBlurPipeline_.layout, compute, 0, constants);
    dispatch(commands, rayBlurPipeline_, rayBlurSet_, {used.x, 1}, {kRayBlurColumns, 1});
    computeToCompute(commands);
  }
  commands.pushConstants<RayCentreConstants>(*rayUnpolarPipeline_.layout, compute, 0, polarConstants);
  dispatch(commands, rayUnpolarPipeline_, rayUnpolarSets_[blur ? 1 : 0], godRays_.extent());
  godRaysRecorded_ = true;
}

void PostPass::recordHandOff(const vk::raii::CommandBuffer& commands, const PostSettings& settings, float exposure) {
  const bool glows = settings.glowStrength > 0.0f;
  const bool godRays = settings.godRays > 0.0f && godRaysRecorded_;
  overlayUse_ = glows || godRays ? OverlayUse::kFiltered : settings.autoGain ? OverlayUse::kScale : OverlayUse::kNone;
  if (overlayUse_ != OverlayUse::kNone) {
    computeToCompute(commands);  // the steps before wrote what this reads
    Pipeline& pipeline =
        overlayPipelines_[4 * std::size_t(settings.autoGain) + 2 * std::size_t(glows) + std::size_t(godRays)];
    if (!*pipeline.pipeline)
      pipeline = makeComputePipeline(*device_, "post_overlay.comp", overlayLayout_, sizeof(OverlayConstants),
                                     {std::uint32_t(settings.autoGain), std::uint32_t(glows), std::uint32_t(godRays)});
    const OverlayConstants constants{
        .exposure = exposure, .glowStrength = settings.glowStrength, .godRays = godRays ? settings.godRays : 0.0f};
    commands.pushConstants<OverlayConstants>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
    dispatch(commands, pipeline, overlaySet_, overlay_.extent());
  }
  const vk::MemoryBarrier2 toReaders{
      .srcStageMask = Stage::eComputeShader,
      .srcAccessMask = Access::eShaderStorageWrite,
      .dstStageMask = Stage::eFragmentShader | Stage::eComputeShader | Stage::eHost,
      .dstAccessMask = Access::eShaderSampledRead | Access::eShaderStorageRead | Access::eHostRead};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toReaders});
}

void PostPass::declareHandOff(FrameGraph::Builder& pass) const {
  pass.produce(overlay_,
               {Stage::eFragmentShader | Stage::eComputeShader | Stage::eHost,
                Access::eShaderSampledRead | Access::eShaderStorageRead | Access::eHostRead, Layout::eGeneral});
}

Result<HdrImage> PostPass::readDownsampled() const {
  return readOrFail(*device_, downsampled_, "downsampled copy");
}

Result<HdrImage> PostPass::readGlow() const {
  return readOrFail(*device_, glow_, "glow");
}

Result<HdrImage> PostPass::readTiny() const {
  return readOrFail(*device_, tiny_, "tiny image");
}

Result<HdrImage> PostPass::readGodRayBright() const {
  return readOrFail(*device_, rayBright_, "god rays' bright image");
}

Result<HdrImage> PostPass::readGodRayPolar() const {
  return readOrFail(*device_, polar_, "god rays' polar image");
}

Result<HdrImage> PostPass::readGodRayPolarBlurred() const {
  return readOrFail(*device_, polarBlurred_, "god rays' blurred polar image");
}

Result<HdrImage> PostPass::readGodRays() const {
  return readOrFail(*device_, godRays_, "god rays");
}

}  // namespace mane::render
