#include "render/passes/opacity_shadow_map_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/mat4x4.hpp>

#include "render/descriptors.hpp"

namespace mane::render {

namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

// Who reads a built map: shaders receiving the shadows, and read-backs.
constexpr vk::PipelineStageFlags2 kMapReaders = Stage::eFragmentShader | Stage::eComputeShader | Stage::eCopy;

constexpr std::uint32_t kSplatGroup = 64;   // local_size_x of opacity_shadow_splat.comp
constexpr std::uint32_t kResolveGroup = 8;  // local_size_x/y of opacity_shadow_resolve.comp
constexpr std::uint32_t kMinResolution = 16;
constexpr std::uint32_t kMaxResolution = 4096;
constexpr float kUnitTolerance = 1e-3f;

// Mirrors the push constants of shaders/opacity_shadow_build.glsl.
struct BuildConstants {
  glm::mat4 lightFromWorld;
  glm::vec4 weights;  // x α·2r/s, y rectangular lines, z resolution, w deep layer spacing (z units)
  glm::uvec4 counts;  // x strands, y vertices per strand, z segments
};
static_assert(sizeof(BuildConstants) == 96);

constexpr vk::ShaderStageFlags kGraphicsStages = vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment;

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool positiveFinite(float value) {
  return std::isfinite(value) && value > 0.0f;
}

Result<void> checkFormat(const Device& device, vk::Format format, vk::FormatFeatureFlags needed, const char* what) {
  const vk::FormatFeatureFlags present = device.physicalDevice().getFormatProperties(format).optimalTilingFeatures;
  if ((present & needed) != needed)
    return fail(std::string("Opacity shadow map: ") + device.info().name + " cannot use " + vk::to_string(format) +
                " for " + what + " (needs " + vk::to_string(needed) + ", has " + vk::to_string(present) + ").");
  return {};
}

Result<void> validate(const Device& device, const OpacityShadowStrands& strands, const OpacityShadowSettings& s) {
  const vk::PhysicalDeviceLimits& limits = device.limits();
  const std::uint32_t maxResolution = std::min(kMaxResolution, limits.maxImageDimension2D);
  if (s.resolution < kMinResolution || s.resolution > maxResolution)
    return fail("Opacity shadow map: resolution " + std::to_string(s.resolution) + " is outside [" +
                std::to_string(kMinResolution) + ", " + std::to_string(maxResolution) + "] texels.");
  if (!positiveFinite(s.strandRadius))
    return fail("Opacity shadow map: strand radius " + std::to_string(s.strandRadius) +
                " m is not positive and finite.");
  if (!positiveFinite(s.strandOpacity))
    return fail("Opacity shadow map: strand opacity " + std::to_string(s.strandOpacity) +
                " is not positive and finite.");
  if (!positiveFinite(s.extinction))
    return fail("Opacity shadow map: extinction κ " + std::to_string(s.extinction) + " is not positive and finite.");
  if (!(s.layerSpacing > 0.0f && s.layerSpacing <= 1.0f))
    return fail("Opacity shadow map: deep layer spacing " + std::to_string(s.layerSpacing) +
                " is outside (0, 1] (a fraction of the bounding sphere's diameter).");
  if (s.builder == OpacityShadowBuilder::kCompute && s.mode != OpacityShadowMode::kOpacityShadowMap)
    return fail(
        "Opacity shadow map: the compute builder makes 16-slice opacity shadow maps only, not deep opacity "
        "maps or depth shadow maps.");
  if (strands.positions == nullptr || strands.strandCount == 0)
    return fail("Opacity shadow map: there are no strands (" + std::to_string(strands.strandCount) +
                " strands, position buffer " + (strands.positions ? "given" : "missing") + ").");
  if (strands.verticesPerStrand < 2)
    return fail("Opacity shadow map: strands need at least 2 vertices each, got " +
                std::to_string(strands.verticesPerStrand) + ".");
  const std::uint64_t vertices = std::uint64_t(strands.strandCount) * strands.verticesPerStrand;
  const std::uint64_t segments = std::uint64_t(strands.strandCount) * (strands.verticesPerStrand - 1);
  if (vertices * 16 > strands.positions->size())
    return fail("Opacity shadow map: " + std::to_string(strands.strandCount) + " strands × " +
                std::to_string(strands.verticesPerStrand) + " vertices need " + std::to_string(vertices * 16) +
                " bytes of positions; the buffer has " + std::to_string(strands.positions->size()) + ".");
  if (vertices * 16 > limits.maxStorageBufferRange)
    return fail("Opacity shadow map: the positions take " + std::to_string(vertices * 16) +
                " bytes, more than the device's storage buffer range of " +
                std::to_string(limits.maxStorageBufferRange) + " bytes.");
  if (2 * segments > std::numeric_limits<std::int32_t>::max() ||
      (segments + kSplatGroup - 1) / kSplatGroup > limits.maxComputeWorkGroupCount[0])
    return fail("Opacity shadow map: " + std::to_string(segments) + " segments are more than one draw or dispatch (" +
                std::to_string(std::uint64_t(limits.maxComputeWorkGroupCount[0]) * kSplatGroup) + ") holds.");
  if (s.builder == OpacityShadowBuilder::kCompute) {
    if (!(strands.positions->usage() & vk::BufferUsageFlagBits::eUniformTexelBuffer))
      return fail(
          "Opacity shadow map: the compute builder reads the positions as a texel buffer, but their buffer was "
          "made without UNIFORM_TEXEL_BUFFER usage.");
    if (vertices > limits.maxTexelBufferElements)
      return fail("Opacity shadow map: " + std::to_string(vertices) + " vertices are more than the device's texel " +
                  "buffers hold (" + std::to_string(limits.maxTexelBufferElements) + ").");
    const std::uint64_t bytes = std::uint64_t(s.resolution) * s.resolution * OpacityShadowMapPass::kSlices * 4;
    if (bytes > limits.maxStorageBufferRange)
      return fail("Opacity shadow map: the compute builder's " + std::to_string(bytes) +
                  " bytes of slice increments exceed the device's storage buffer range of " +
                  std::to_string(limits.maxStorageBufferRange) + " bytes; lower the resolution.");
  }
  using Feature = vk::FormatFeatureFlagBits;
  vk::FormatFeatureFlags opacityNeeds =
      Feature::eSampledImage | Feature::eSampledImageFilterLinear | Feature::eTransferSrc;
  opacityNeeds |= s.builder == OpacityShadowBuilder::kCompute
                      ? vk::FormatFeatureFlags(Feature::eStorageImage)
                      : vk::FormatFeatureFlags(Feature::eColorAttachment | Feature::eColorAttachmentBlend);
  if (auto ok = checkFormat(device, OpacityShadowMapPass::kOpacityFormat, opacityNeeds, "the opacity map"); !ok)
    return ok;
  return checkFormat(device, OpacityShadowMapPass::kDepthFormat,
                     Feature::eDepthStencilAttachment | Feature::eSampledImage | Feature::eTransferSrc,
                     "the first-hair depth");
}

}  // namespace

namespace {

// Both overloads: xyz of each element.
template <class Point>
Result<BoundingSphere> boundingSphereOf(std::span<const Point> positions) {
  if (positions.empty()) return fail("Opacity shadow map: no positions to bound.");
  glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3 p(positions[i]);
    if (!finite(p)) return fail("Opacity shadow map: position " + std::to_string(i) + " is not finite.");
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  const glm::vec3 centre = 0.5f * (low + high);
  float radius = 0.0f;
  for (const Point& p : positions) radius = std::max(radius, glm::length(glm::vec3(p) - centre));
  if (!(radius > 0.0f)) return fail("Opacity shadow map: all positions coincide; the hair has no extent to bound.");
  return BoundingSphere{centre, radius * 1.001f};
}

}  // namespace

Result<BoundingSphere> boundingSphere(std::span<const glm::vec4> positions) {
  return boundingSphereOf(positions);
}

Result<BoundingSphere> boundingSphere(std::span<const glm::vec3> positions) {
  return boundingSphereOf(positions);
}

glm::mat4 orthographicLightFrame(glm::vec3 towardLight, const BoundingSphere& sphere) {
  const glm::dvec3 l = glm::normalize(glm::dvec3(towardLight));
  const glm::dvec3 helper = std::abs(l.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 e1 = glm::normalize(glm::cross(helper, l));
  const glm::dvec3 e2 = glm::cross(l, e1);
  const glm::dvec3 c(sphere.centre);
  const double r = sphere.radius;
  glm::dmat4 m(0.0);  // column-major: m[column][row]
  for (int i = 0; i < 3; ++i) {
    m[i][0] = e1[i] / r;
    m[i][1] = e2[i] / r;
    m[i][2] = -l[i] / (2.0 * r);
  }
  m[3][0] = -glm::dot(c, e1) / r;
  m[3][1] = -glm::dot(c, e2) / r;
  m[3][2] = (r + glm::dot(c, l)) / (2.0 * r);
  m[3][3] = 1.0;
  return glm::mat4(m);
}

Result<std::unique_ptr<OpacityShadowMapPass>> OpacityShadowMapPass::create(const Device& device,
                                                                           const OpacityShadowStrands& strands,
                                                                           const OpacityShadowSettings& settings) {
  if (auto valid = validate(device, strands, settings); !valid) return std::unexpected(valid.error());
  try {
    return std::unique_ptr<OpacityShadowMapPass>(new OpacityShadowMapPass(device, strands, settings));
  } catch (const std::exception& error) {
    return fail(std::string("Opacity shadow map: creating the pass failed: ") + error.what());
  }
}

OpacityShadowMapPass::OpacityShadowMapPass(const Device& device, const OpacityShadowStrands& strands,
                                           const OpacityShadowSettings& settings)
    : device_(&device),
      settings_(settings),
      positions_(*strands.positions->buffer()),
      strandCount_(strands.strandCount),
      verticesPerStrand_(strands.verticesPerStrand),
      segmentCount_(strands.strandCount * (strands.verticesPerStrand - 1)),
      strictLines_(device.limits().strictLines == VK_TRUE) {
  const bool deep = settings.mode == OpacityShadowMode::kDeepOpacityMap;
  const bool depthOnly = settings.mode == OpacityShadowMode::kDepthShadowMap;
  const bool firstHair = deep || depthOnly;  // a first-hair depth pass
  const bool compute = settings.builder == OpacityShadowBuilder::kCompute;
  using Usage = vk::ImageUsageFlagBits;

  const auto makeImage = [&](ArrayImage& target, vk::Extent2D extent, std::uint32_t layers, vk::Format format,
                             vk::ImageUsageFlags usage, vk::ImageAspectFlags aspect) {
    target.extent = extent;
    target.layers = layers;
    target.image = vk::raii::Image(device.device(), vk::ImageCreateInfo{.imageType = vk::ImageType::e2D,
                                                                        .format = format,
                                                                        .extent = {extent.width, extent.height, 1},
                                                                        .mipLevels = 1,
                                                                        .arrayLayers = layers,
                                                                        .samples = vk::SampleCountFlagBits::e1,
                                                                        .tiling = vk::ImageTiling::eOptimal,
                                                                        .usage = usage,
                                                                        .initialLayout = Layout::eUndefined});
    target.allocation =
        Allocation(device, target.image.getMemoryRequirements(), vk::MemoryPropertyFlagBits::eDeviceLocal);
    target.image.bindMemory(*target.allocation.memory(), 0);
    target.view = vk::raii::ImageView(
        device.device(),
        vk::ImageViewCreateInfo{.image = *target.image,
                                .viewType = aspect == vk::ImageAspectFlagBits::eColor ? vk::ImageViewType::e2DArray
                                                                                      : vk::ImageViewType::e2D,
                                .format = format,
                                .subresourceRange = {aspect, 0, 1, 0, layers}});
    for (std::uint32_t layer = 0; layer < layers; ++layer)
      target.layerViews.emplace_back(device.device(),
                                     vk::ImageViewCreateInfo{.image = *target.image,
                                                             .viewType = vk::ImageViewType::e2D,
                                                             .format = format,
                                                             .subresourceRange = {aspect, 0, 1, layer, 1}});
  };
  const vk::Extent2D extent{settings.resolution, settings.resolution};
  makeImage(opacity_, depthOnly ? vk::Extent2D{1, 1} : extent, deep || depthOnly ? 1 : kSlices / 4, kOpacityFormat,
            Usage::eSampled | Usage::eTransferSrc |
                (compute     ? Usage::eStorage
                 : depthOnly ? Usage::eTransferDst
                             : Usage::eColorAttachment),
            vk::ImageAspectFlagBits::eColor);
  makeImage(firstDepth_, firstHair ? extent : vk::Extent2D{1, 1}, 1, kDepthFormat,
            Usage::eDepthStencilAttachment | Usage::eSampled | Usage::eTransferSrc | Usage::eTransferDst,
            vk::ImageAspectFlagBits::eDepth);
  // Valid "no hair anywhere" images for consumers that bind both: a depth of 1 where no pass
  // writes the first depth, an opacity of 0 where none writes opacity (depth shadow maps).
  const auto clearOnce = [&](const ArrayImage& target, vk::ImageAspectFlags aspect) {
    device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      const vk::ImageSubresourceRange range{aspect, 0, 1, 0, 1};
      imageBarrier(commands, *target.image, range, Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone,
                   Access::eNone, Stage::eClear, Access::eTransferWrite);
      if (aspect == vk::ImageAspectFlagBits::eDepth)
        commands.clearDepthStencilImage(*target.image, Layout::eTransferDstOptimal, vk::ClearDepthStencilValue{1.0f, 0},
                                        range);
      else
        commands.clearColorImage(*target.image, Layout::eTransferDstOptimal,
                                 vk::ClearColorValue(std::array{0.0f, 0.0f, 0.0f, 0.0f}), range);
      imageBarrier(commands, *target.image, range, Layout::eTransferDstOptimal, Layout::eShaderReadOnlyOptimal,
                   Stage::eClear, Access::eTransferWrite, Stage::eFragmentShader | Stage::eComputeShader,
                   Access::eShaderSampledRead);
    });
  };
  if (!firstHair) clearOnce(firstDepth_, vk::ImageAspectFlagBits::eDepth);
  if (depthOnly) clearOnce(opacity_, vk::ImageAspectFlagBits::eColor);

  sampler_ =
      vk::raii::Sampler(device.device(), vk::SamplerCreateInfo{.magFilter = vk::Filter::eLinear,
                                                               .minFilter = vk::Filter::eLinear,
                                                               .mipmapMode = vk::SamplerMipmapMode::eNearest,
                                                               .addressModeU = vk::SamplerAddressMode::eClampToBorder,
                                                               .addressModeV = vk::SamplerAddressMode::eClampToBorder,
                                                               .addressModeW = vk::SamplerAddressMode::eClampToEdge,
                                                               .maxLod = 0.0f,
                                                               .borderColor = vk::BorderColor::eFloatTransparentBlack});
  nearest_ =
      vk::raii::Sampler(device.device(), vk::SamplerCreateInfo{.magFilter = vk::Filter::eNearest,
                                                               .minFilter = vk::Filter::eNearest,
                                                               .mipmapMode = vk::SamplerMipmapMode::eNearest,
                                                               .addressModeU = vk::SamplerAddressMode::eClampToEdge,
                                                               .addressModeV = vk::SamplerAddressMode::eClampToEdge,
                                                               .addressModeW = vk::SamplerAddressMode::eClampToEdge,
                                                               .maxLod = 0.0f});

  // 0 positions, 1 first depth (deep layers pass), and for the compute builder 2 slice increments,
  // 3 slices, 4 the positions again as texels. Every binding is written (lavapipe reads all of a
  // bound set's descriptors).
  const auto computeStage = vk::ShaderStageFlagBits::eCompute;
  const std::pair<vk::DescriptorType, vk::ShaderStageFlags> positionsBinding{vk::DescriptorType::eStorageBuffer,
                                                                             computeStage | kGraphicsStages};
  const std::pair<vk::DescriptorType, vk::ShaderStageFlags> depthBinding{vk::DescriptorType::eCombinedImageSampler,
                                                                         vk::ShaderStageFlagBits::eFragment};
  setLayout_ = compute ? makeSetLayout(device, {positionsBinding,
                                                depthBinding,
                                                {vk::DescriptorType::eStorageBuffer, computeStage},
                                                {vk::DescriptorType::eStorageImage, computeStage},
                                                {vk::DescriptorType::eUniformTexelBuffer, computeStage}})
                       : makeSetLayout(device, {positionsBinding, depthBinding});
  pool_ = makeDescriptorPool(device, 1,
                             {{vk::DescriptorType::eStorageBuffer, 2},
                              {vk::DescriptorType::eCombinedImageSampler, 1},
                              {vk::DescriptorType::eStorageImage, 1},
                              {vk::DescriptorType::eUniformTexelBuffer, 1}});
  set_ = allocateSet(device, pool_, setLayout_);
  writeStorageBuffer(device, set_, 0, *strands.positions);
  if (compute) {
    positionTexels_ = makeTexelView(device, *strands.positions->buffer(), vk::Format::eR32G32B32A32Sfloat);
    writeUniformTexelBuffer(device, set_, 4, positionTexels_);
  }
  const vk::DescriptorImageInfo depth{
      .sampler = *nearest_, .imageView = *firstDepth_.view, .imageLayout = Layout::eShaderReadOnlyOptimal};
  device.device().updateDescriptorSets(
      vk::WriteDescriptorSet{.dstSet = *set_,
                             .dstBinding = 1,
                             .descriptorCount = 1,
                             .descriptorType = vk::DescriptorType::eCombinedImageSampler,
                             .pImageInfo = &depth},
      {});

  const vk::PushConstantRange graphicsPush{.stageFlags = kGraphicsStages, .offset = 0, .size = sizeof(BuildConstants)};
  GraphicsPipelineSettings lines{.vertexShader = "opacity_shadow.vert",
                                 .topology = vk::PrimitiveTopology::eLineList,
                                 .setLayouts = {*setLayout_},
                                 .pushConstants = {graphicsPush}};
  if (compute) {
    // Zero at first; after that, each resolve zeroes what it has read, for the next splat.
    const std::vector<std::uint32_t> zeros(std::size_t(settings.resolution) * settings.resolution * kSlices, 0u);
    increments_ = Buffer::withData(device, std::as_bytes(std::span(zeros)), vk::BufferUsageFlagBits::eStorageBuffer);
    writeStorageBuffer(device, set_, 2, increments_);
    writeStorageImage(device, set_, 3, opacity_.view);
    splatPipeline_ = makeComputePipeline(device, "opacity_shadow_splat.comp", setLayout_, sizeof(BuildConstants));
    resolvePipeline_ = makeComputePipeline(device, "opacity_shadow_resolve.comp", setLayout_, sizeof(BuildConstants));
  } else if (firstHair) {
    GraphicsPipelineSettings depthLines = lines;
    depthLines.fragmentShader = "opacity_shadow_depth.frag";
    depthLines.depthFormat = kDepthFormat;
    depthLines.depthTest = true;
    depthLines.depthWrite = true;
    depthPipeline_ = makeGraphicsPipeline(device, depthLines);
    if (deep) {
      lines.fragmentShader = "opacity_shadow_deep.frag";
      lines.colorFormats = {kOpacityFormat};
      lines.blend = Blend::kAdditive;
      opacityPipeline_ = makeGraphicsPipeline(device, lines);
    }
  } else {
    lines.fragmentShader = "opacity_shadow.frag";
    lines.colorFormats = std::vector<vk::Format>(kSlices / 4, kOpacityFormat);
    lines.blend = Blend::kAdditive;
    opacityPipeline_ = makeGraphicsPipeline(device, lines);
  }
}

Result<void> OpacityShadowMapPass::setStrandRadius(float radius) {
  if (!positiveFinite(radius))
    return fail("Opacity shadow map: strand radius " + std::to_string(radius) + " m is not positive and finite.");
  settings_.strandRadius = radius;
  return {};
}

Result<void> OpacityShadowMapPass::setLight(glm::vec3 towardLight, const BoundingSphere& hair) {
  if (!finite(towardLight) || std::abs(glm::length(towardLight) - 1.0f) > kUnitTolerance)
    return fail("Opacity shadow map: the light direction (" + std::to_string(towardLight.x) + ", " +
                std::to_string(towardLight.y) + ", " + std::to_string(towardLight.z) +
                ") is not a finite unit vector (length within 1e-3 of 1).");
  if (!finite(hair.centre) || !positiveFinite(hair.radius))
    return fail("Opacity shadow map: the hair's bounding sphere (radius " + std::to_string(hair.radius) +
                " m) needs a finite centre and a positive, finite radius.");
  towardLight_ = glm::normalize(towardLight);
  sphere_ = hair;
  lightSet_ = true;
  const float diameter = 2.0f * hair.radius;
  const float resolution = static_cast<float>(settings_.resolution);
  uniforms_.lightFromWorld = orthographicLightFrame(towardLight_, sphere_);
  const float mode = float(settings_.mode);
  switch (settings_.mode) {
    case OpacityShadowMode::kOpacityShadowMap:
      uniforms_.depth = glm::vec4(float(kSlices), 1.0f / kSlices, settings_.extinction, mode);
      break;
    case OpacityShadowMode::kDeepOpacityMap:
      uniforms_.depth = glm::vec4(float(kDeepLayers), settings_.layerSpacing, settings_.extinction, mode);
      break;
    case OpacityShadowMode::kDepthShadowMap:  // the bias: 2 texels' worth of depth (header)
      uniforms_.depth = glm::vec4(1.0f, 2.0f / resolution, settings_.extinction, mode);
      break;
  }
  uniforms_.texels = glm::vec4(resolution, 1.0f / resolution, diameter, diameter / resolution);
  return {};
}

float OpacityShadowMapPass::sliceBoundary(std::uint32_t slice) const {
  return float(slice + 1) * 2.0f * sphere_.radius / float(kSlices);
}

float OpacityShadowMapPass::depthOf(glm::vec3 world) const {
  return sphere_.radius - glm::dot(world - sphere_.centre, towardLight_);
}

void OpacityShadowMapPass::declare(FrameGraph::Builder& pass) const {
  // Positions written by a compute pass (strand interpolation) or a copy: read by the vertex
  // shader (graphics builders) or as texels (the compute builder).
  pass.read(GraphResource(positions_),
            {Stage::eVertexShader | Stage::eComputeShader, Access::eShaderStorageRead | Access::eShaderSampledRead});
  // Each build ends with its images in SHADER_READ_ONLY layout for fragment and compute shaders
  // and copies.
  const ResourceUse readable{kMapReaders, Access::eShaderSampledRead | Access::eTransferRead,
                             Layout::eShaderReadOnlyOptimal};
  if (settings_.mode != OpacityShadowMode::kDepthShadowMap) pass.produce(opacityImage(), readable);
  if (settings_.mode != OpacityShadowMode::kOpacityShadowMap) pass.produce(firstDepthImage(), readable);
}

void OpacityShadowMapPass::declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const {
  if (settings_.mode != OpacityShadowMode::kDepthShadowMap) pass.read(opacityImage(), ResourceUse::sampled(stages));
  if (settings_.mode != OpacityShadowMode::kOpacityShadowMap)
    pass.read(firstDepthImage(), ResourceUse::sampled(stages));
}

GraphResource OpacityShadowMapPass::opacityImage() const {
  return GraphResource(*opacity_.image, {vk::ImageAspectFlagBits::eColor, 0, 1, 0, opacity_.layers});
}

GraphResource OpacityShadowMapPass::firstDepthImage() const {
  return GraphResource(*firstDepth_.image, {vk::ImageAspectFlagBits::eDepth, 0, 1, 0, 1});
}

void OpacityShadowMapPass::execute(const vk::raii::CommandBuffer& commands) const {
  if (!lightSet_) throw std::logic_error("OpacityShadowMapPass::execute before setLight");
  if (settings_.builder == OpacityShadowBuilder::kCompute)
    recordCompute(commands);
  else if (settings_.mode == OpacityShadowMode::kDeepOpacityMap)
    recordDeep(commands);
  else if (settings_.mode == OpacityShadowMode::kDepthShadowMap)
    recordFirstDepth(commands);
  else
    recordGraphics(commands);
}

void OpacityShadowMapPass::record(const vk::raii::CommandBuffer& commands) const {
  FrameGraph::recordAlone(commands, PassName::kHairShadows, *this);
}

namespace {

BuildConstants buildConstants(const OpacityShadowUniforms& uniforms, const OpacityShadowSettings& settings,
                              bool strictLines, std::uint32_t strands, std::uint32_t vertices, std::uint32_t segments) {
  const float texel = uniforms.texels.w;  // s, metres
  return BuildConstants{
      .lightFromWorld = uniforms.lightFromWorld,
      .weights = glm::vec4(settings.strandOpacity * 2.0f * settings.strandRadius / texel, strictLines ? 1.0f : 0.0f,
                           float(settings.resolution), settings.layerSpacing),
      .counts = glm::uvec4(strands, vertices, segments, 0u)};
}

// Layout transition of a whole ArrayImage-like image.
void transitionAll(const vk::raii::CommandBuffer& commands, vk::Image image, vk::ImageAspectFlags aspect,
                   std::uint32_t layers, Layout from, Layout to, vk::PipelineStageFlags2 srcStage,
                   vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage, vk::AccessFlags2 dstAccess) {
  imageBarrier(commands, image, {aspect, 0, 1, 0, layers}, from, to, srcStage, srcAccess, dstStage, dstAccess);
}

constexpr vk::PipelineStageFlags2 kReaders = kMapReaders;

}  // namespace

void OpacityShadowMapPass::drawSegments(const vk::raii::CommandBuffer& commands, const Pipeline& pipeline) const {
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline.layout, 0, {*set_}, {});
  commands.pushConstants<BuildConstants>(
      *pipeline.layout, kGraphicsStages, 0,
      buildConstants(uniforms_, settings_, strictLines_, strandCount_, verticesPerStrand_, segmentCount_));
  commands.draw(2 * segmentCount_, 1, 0, 0);
}

void OpacityShadowMapPass::recordGraphics(const vk::raii::CommandBuffer& commands) const {
  const auto color = vk::ImageAspectFlagBits::eColor;
  transitionAll(commands, *opacity_.image, color, opacity_.layers, Layout::eUndefined, Layout::eColorAttachmentOptimal,
                kReaders, Access::eNone, Stage::eColorAttachmentOutput,
                Access::eColorAttachmentWrite | Access::eColorAttachmentRead);
  std::vector<vk::RenderingAttachmentInfo> targets;
  for (const vk::raii::ImageView& view : opacity_.layerViews)
    targets.push_back({.imageView = *view,
                       .imageLayout = Layout::eColorAttachmentOptimal,
                       .loadOp = vk::AttachmentLoadOp::eClear,
                       .storeOp = vk::AttachmentStoreOp::eStore,
                       .clearValue = {.color = {.float32 = std::array{0.0f, 0.0f, 0.0f, 0.0f}}}});
  commands.beginRendering(vk::RenderingInfo{.renderArea = {{0, 0}, opacity_.extent},
                                            .layerCount = 1,
                                            .colorAttachmentCount = static_cast<std::uint32_t>(targets.size()),
                                            .pColorAttachments = targets.data()});
  setViewportAndScissor(commands, opacity_.extent);
  drawSegments(commands, opacityPipeline_);
  commands.endRendering();
  transitionAll(commands, *opacity_.image, color, opacity_.layers, Layout::eColorAttachmentOptimal,
                Layout::eShaderReadOnlyOptimal, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, kReaders,
                Access::eShaderSampledRead | Access::eTransferRead);
}

// Nearest hair depth: deep opacity maps' pass 1, and all of a depth shadow map.
void OpacityShadowMapPass::recordFirstDepth(const vk::raii::CommandBuffer& commands) const {
  const auto depthAspect = vk::ImageAspectFlagBits::eDepth;
  const auto depthTests = Stage::eEarlyFragmentTests | Stage::eLateFragmentTests;
  transitionAll(commands, *firstDepth_.image, depthAspect, 1, Layout::eUndefined, Layout::eDepthAttachmentOptimal,
                kReaders, Access::eNone, depthTests,
                Access::eDepthStencilAttachmentRead | Access::eDepthStencilAttachmentWrite);
  const vk::RenderingAttachmentInfo depth{.imageView = *firstDepth_.view,
                                          .imageLayout = Layout::eDepthAttachmentOptimal,
                                          .loadOp = vk::AttachmentLoadOp::eClear,
                                          .storeOp = vk::AttachmentStoreOp::eStore,
                                          .clearValue = {.depthStencil = {.depth = 1.0f, .stencil = 0}}};
  commands.beginRendering(
      vk::RenderingInfo{.renderArea = {{0, 0}, firstDepth_.extent}, .layerCount = 1, .pDepthAttachment = &depth});
  setViewportAndScissor(commands, firstDepth_.extent);
  drawSegments(commands, depthPipeline_);
  commands.endRendering();
  transitionAll(commands, *firstDepth_.image, depthAspect, 1, Layout::eDepthAttachmentOptimal,
                Layout::eShaderReadOnlyOptimal, depthTests, Access::eDepthStencilAttachmentWrite, kReaders,
                Access::eShaderSampledRead | Access::eTransferRead);
}

void OpacityShadowMapPass::recordDeep(const vk::raii::CommandBuffer& commands) const {
  recordFirstDepth(commands);  // pass 1: nearest hair depth
  // Pass 2: the layers, relative to that depth.
  const auto color = vk::ImageAspectFlagBits::eColor;
  transitionAll(commands, *opacity_.image, color, 1, Layout::eUndefined, Layout::eColorAttachmentOptimal, kReaders,
                Access::eNone, Stage::eColorAttachmentOutput,
                Access::eColorAttachmentWrite | Access::eColorAttachmentRead);
  const vk::RenderingAttachmentInfo target{.imageView = *opacity_.layerViews[0],
                                           .imageLayout = Layout::eColorAttachmentOptimal,
                                           .loadOp = vk::AttachmentLoadOp::eClear,
                                           .storeOp = vk::AttachmentStoreOp::eStore,
                                           .clearValue = {.color = {.float32 = std::array{0.0f, 0.0f, 0.0f, 0.0f}}}};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {{0, 0}, opacity_.extent},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &target});
  setViewportAndScissor(commands, opacity_.extent);
  drawSegments(commands, opacityPipeline_);
  commands.endRendering();
  transitionAll(commands, *opacity_.image, color, 1, Layout::eColorAttachmentOptimal, Layout::eShaderReadOnlyOptimal,
                Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, kReaders,
                Access::eShaderSampledRead | Access::eTransferRead);
}

void OpacityShadowMapPass::recordCompute(const vk::raii::CommandBuffer& commands) const {
  // The previous frame's resolve zeroed the increments as it read them.
  const vk::MemoryBarrier2 zeroed{.srcStageMask = Stage::eComputeShader,
                                  .srcAccessMask = Access::eShaderStorageWrite,
                                  .dstStageMask = Stage::eComputeShader,
                                  .dstAccessMask = Access::eShaderStorageRead | Access::eShaderStorageWrite};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &zeroed});

  const BuildConstants constants =
      buildConstants(uniforms_, settings_, strictLines_, strandCount_, verticesPerStrand_, segmentCount_);
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *splatPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *splatPipeline_.layout, 0, {*set_}, {});
  commands.pushConstants<BuildConstants>(*splatPipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
  commands.dispatch((segmentCount_ + kSplatGroup - 1) / kSplatGroup, 1, 1);

  const vk::MemoryBarrier2 splatted{.srcStageMask = Stage::eComputeShader,
                                    .srcAccessMask = Access::eShaderStorageWrite,
                                    .dstStageMask = Stage::eComputeShader,
                                    .dstAccessMask = Access::eShaderStorageRead};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &splatted});
  const auto color = vk::ImageAspectFlagBits::eColor;
  transitionAll(commands, *opacity_.image, color, opacity_.layers, Layout::eUndefined, Layout::eGeneral, kReaders,
                Access::eNone, Stage::eComputeShader, Access::eShaderStorageWrite);
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *resolvePipeline_.pipeline);
  commands.pushConstants<BuildConstants>(*resolvePipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
  const std::uint32_t groups = (settings_.resolution + kResolveGroup - 1) / kResolveGroup;
  commands.dispatch(groups, groups, 1);
  transitionAll(commands, *opacity_.image, color, opacity_.layers, Layout::eGeneral, Layout::eShaderReadOnlyOptimal,
                Stage::eComputeShader, Access::eShaderStorageWrite, kReaders,
                Access::eShaderSampledRead | Access::eTransferRead);
}

std::vector<float> OpacityShadowMapPass::readOpacity() const {
  const std::size_t texels = std::size_t(opacity_.extent.width) * opacity_.extent.height;
  const std::size_t layers = opacity_.layers;
  Buffer host(*device_, texels * layers * 8, vk::BufferUsageFlagBits::eTransferDst,
              vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    const auto color = vk::ImageAspectFlagBits::eColor;
    transitionAll(commands, *opacity_.image, color, opacity_.layers, Layout::eShaderReadOnlyOptimal,
                  Layout::eTransferSrcOptimal, kReaders, Access::eNone, Stage::eCopy, Access::eTransferRead);
    commands.copyImageToBuffer(*opacity_.image, Layout::eTransferSrcOptimal, *host.buffer(),
                               vk::BufferImageCopy{.imageSubresource = {color, 0, 0, opacity_.layers},
                                                   .imageExtent = {opacity_.extent.width, opacity_.extent.height, 1}});
    transitionAll(commands, *opacity_.image, color, opacity_.layers, Layout::eTransferSrcOptimal,
                  Layout::eShaderReadOnlyOptimal, Stage::eCopy, Access::eNone, kReaders, Access::eShaderSampledRead);
    const vk::MemoryBarrier2 toHost{.srcStageMask = Stage::eCopy,
                                    .srcAccessMask = Access::eTransferWrite,
                                    .dstStageMask = Stage::eHost,
                                    .dstAccessMask = Access::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
  });
  // The copy is layer after layer; the result is texel after texel.
  std::vector<std::uint16_t> halves(texels * layers * 4);
  std::memcpy(halves.data(), host.mapped().data(), halves.size() * 2);
  std::vector<float> values(halves.size());
  for (std::size_t layer = 0; layer < layers; ++layer)
    for (std::size_t texel = 0; texel < texels; ++texel)
      for (std::size_t c = 0; c < 4; ++c)
        values[texel * layers * 4 + layer * 4 + c] = glm::unpackHalf1x16(halves[(layer * texels + texel) * 4 + c]);
  return values;
}

std::vector<float> OpacityShadowMapPass::readFirstDepth() const {
  const std::size_t texels = std::size_t(firstDepth_.extent.width) * firstDepth_.extent.height;
  Buffer host(*device_, texels * 4, vk::BufferUsageFlagBits::eTransferDst,
              vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    const auto depth = vk::ImageAspectFlagBits::eDepth;
    transitionAll(commands, *firstDepth_.image, depth, 1, Layout::eShaderReadOnlyOptimal, Layout::eTransferSrcOptimal,
                  kReaders, Access::eNone, Stage::eCopy, Access::eTransferRead);
    commands.copyImageToBuffer(
        *firstDepth_.image, Layout::eTransferSrcOptimal, *host.buffer(),
        vk::BufferImageCopy{.imageSubresource = {depth, 0, 0, 1},
                            .imageExtent = {firstDepth_.extent.width, firstDepth_.extent.height, 1}});
    transitionAll(commands, *firstDepth_.image, depth, 1, Layout::eTransferSrcOptimal, Layout::eShaderReadOnlyOptimal,
                  Stage::eCopy, Access::eNone, kReaders, Access::eShaderSampledRead);
    const vk::MemoryBarrier2 toHost{.srcStageMask = Stage::eCopy,
                                    .srcAccessMask = Access::eTransferWrite,
                                    .dstStageMask = Stage::eHost,
                                    .dstAccessMask = Access::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
  });
  std::vector<float> values(texels);
  std::memcpy(values.data(), host.mapped().data(), texels * 4);
  return values;
}

std::vector<glm::vec2> OpacityShadowMapPass::probe(std::span<const glm::vec3> points) const {
  struct Push {  // mirrors the push constants of shaders/opacity_shadow_probe.comp
    OpacityShadowUniforms osm;
    std::uint32_t count;
  };
  constexpr std::uint32_t kProbeGroup = 64;  // local_size_x of opacity_shadow_probe.comp
  if (points.empty()) return {};
  const Device& device = *device_;
  const auto stage = vk::ShaderStageFlagBits::eCompute;
  const auto hostMemory = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
  Buffer input(device, points.size() * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer, hostMemory);
  Buffer output(device, points.size() * sizeof(glm::vec2), vk::BufferUsageFlagBits::eStorageBuffer, hostMemory);
  auto* packed = reinterpret_cast<glm::vec4*>(input.mapped().data());
  for (std::size_t i = 0; i < points.size(); ++i) packed[i] = glm::vec4(points[i], 1.0f);

  const vk::raii::DescriptorSetLayout setLayout =
      makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, stage},
                             {vk::DescriptorType::eCombinedImageSampler, stage},
                             {vk::DescriptorType::eStorageBuffer, stage},
                             {vk::DescriptorType::eStorageBuffer, stage}});
  const vk::raii::DescriptorPool pool = makeDescriptorPool(
      device, 1, {{vk::DescriptorType::eCombinedImageSampler, 2}, {vk::DescriptorType::eStorageBuffer, 2}});
  const vk::raii::DescriptorSet set = allocateSet(device, pool, setLayout);
  const std::array images{
      vk::DescriptorImageInfo{
          .sampler = *sampler_, .imageView = *opacity_.view, .imageLayout = Layout::eShaderReadOnlyOptimal},
      vk::DescriptorImageInfo{
          .sampler = *nearest_, .imageView = *firstDepth_.view, .imageLayout = Layout::eShaderReadOnlyOptimal}};
  const std::array buffers{vk::DescriptorBufferInfo{.buffer = *input.buffer(), .range = VK_WHOLE_SIZE},
                           vk::DescriptorBufferInfo{.buffer = *output.buffer(), .range = VK_WHOLE_SIZE}};
  device.device().updateDescriptorSets(
      {vk::WriteDescriptorSet{.dstSet = *set,
                              .dstBinding = 0,
                              .descriptorCount = 2,
                              .descriptorType = vk::DescriptorType::eCombinedImageSampler,
                              .pImageInfo = images.data()},
       vk::WriteDescriptorSet{.dstSet = *set,
                              .dstBinding = 2,
                              .descriptorCount = 2,
                              .descriptorType = vk::DescriptorType::eStorageBuffer,
                              .pBufferInfo = buffers.data()}},
      {});
  const Pipeline probe = makeComputePipeline(device, "opacity_shadow_probe.comp", setLayout, sizeof(Push));
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    commands.bindPipeline(vk::PipelineBindPoint::eCompute, *probe.pipeline);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *probe.layout, 0, {*set}, {});
    commands.pushConstants<Push>(*probe.layout, stage, 0, Push{uniforms_, std::uint32_t(points.size())});
    commands.dispatch(std::uint32_t((points.size() + kProbeGroup - 1) / kProbeGroup), 1, 1);
    const vk::MemoryBarrier2 toHost{.srcStageMask = Stage::eComputeShader,
                                    .srcAccessMask = Access::eShaderStorageWrite,
                                    .dstStageMask = Stage::eHost,
                                    .dstAccessMask = Access::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
  });
  std::vector<glm::vec2> results(points.size());
  std::memcpy(results.data(), output.mapped().data(), results.size() * sizeof(glm::vec2));
  return results;
}

}  // namespace mane::render
