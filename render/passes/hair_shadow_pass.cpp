#include "render/passes/hair_shadow_pass.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mane::render {

Result<std::unique_ptr<HairShadowPass>> HairShadowPass::create(const Device& device) {
  try {
    return std::unique_ptr<HairShadowPass>(new HairShadowPass(device));
  } catch (const vk::SystemError& error) {
    return fail(std::string("hair shadows: Vulkan error while creating the empty map: ") + error.what());
  }
}

HairShadowPass::HairShadowPass(const Device& device) : device_(&device) {
  using Layout = vk::ImageLayout;
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  const auto makeImage = [&](vk::raii::Image& image, Allocation& memory, vk::raii::ImageView& view, vk::Format format,
                             vk::ImageUsageFlags usage, vk::ImageAspectFlags aspect, vk::ImageViewType viewType) {
    image = vk::raii::Image(device.device(), vk::ImageCreateInfo{.imageType = vk::ImageType::e2D,
                                                                 .format = format,
                                                                 .extent = {1, 1, 1},
                                                                 .mipLevels = 1,
                                                                 .arrayLayers = 1,
                                                                 .samples = vk::SampleCountFlagBits::e1,
                                                                 .tiling = vk::ImageTiling::eOptimal,
                                                                 .usage = usage | vk::ImageUsageFlagBits::eSampled,
                                                                 .initialLayout = Layout::eUndefined});
    memory = Allocation(device, image.getMemoryRequirements(), vk::MemoryPropertyFlagBits::eDeviceLocal);
    image.bindMemory(*memory.memory(), 0);
    view = vk::raii::ImageView(
        device.device(),
        vk::ImageViewCreateInfo{
            .image = *image, .viewType = viewType, .format = format, .subresourceRange = {aspect, 0, 1, 0, 1}});
  };
  makeImage(emptyOpacity_, emptyOpacityMemory_, emptyOpacityView_, OpacityShadowMapPass::kOpacityFormat,
            vk::ImageUsageFlagBits::eTransferDst, vk::ImageAspectFlagBits::eColor, vk::ImageViewType::e2DArray);
  makeImage(emptyDepth_, emptyDepthMemory_, emptyDepthView_, OpacityShadowMapPass::kDepthFormat,
            vk::ImageUsageFlagBits::eTransferDst, vk::ImageAspectFlagBits::eDepth, vk::ImageViewType::e2D);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    const vk::ImageSubresourceRange colour{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1};
    const vk::ImageSubresourceRange depth{vk::ImageAspectFlagBits::eDepth, 0, 1, 0, 1};
    imageBarrier(commands, *emptyOpacity_, colour, Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone,
                 Access::eNone, Stage::eClear, Access::eTransferWrite);
    imageBarrier(commands, *emptyDepth_, depth, Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone,
                 Access::eNone, Stage::eClear, Access::eTransferWrite);
    commands.clearColorImage(*emptyOpacity_, Layout::eTransferDstOptimal,
                             vk::ClearColorValue(std::array{0.0f, 0.0f, 0.0f, 0.0f}), colour);
    commands.clearDepthStencilImage(*emptyDepth_, Layout::eTransferDstOptimal, vk::ClearDepthStencilValue{1.0f, 0},
                                    depth);
    const auto toRead = Stage::eFragmentShader | Stage::eComputeShader;
    imageBarrier(commands, *emptyOpacity_, colour, Layout::eTransferDstOptimal, Layout::eShaderReadOnlyOptimal,
                 Stage::eClear, Access::eTransferWrite, toRead, Access::eShaderSampledRead);
    imageBarrier(commands, *emptyDepth_, depth, Layout::eTransferDstOptimal, Layout::eShaderReadOnlyOptimal,
                 Stage::eClear, Access::eTransferWrite, toRead, Access::eShaderSampledRead);
  });
  emptySampler_ = vk::raii::Sampler(
      device.device(),
      vk::SamplerCreateInfo{.magFilter = vk::Filter::eNearest, .minFilter = vk::Filter::eNearest, .maxLod = 0.0f});
}

Result<void> HairShadowPass::setGrooms(std::span<const Groom> grooms, const HairShadowSettings& settings) {
  std::vector<GroomMap> maps;
  if (settings.mode != HairShadowMode::kOff) {
    const OpacityShadowMode mode = settings.mode == HairShadowMode::kDeepOpacityMap
                                       ? OpacityShadowMode::kDeepOpacityMap
                                       : OpacityShadowMode::kOpacityShadowMap;
    for (std::size_t g = 0; g < grooms.size() && g < kMaxMaps; ++g) {
      const Groom& groom = grooms[g];
      if (!(std::isfinite(groom.extinction) && groom.extinction > 0.0f))
        return fail("groom " + std::to_string(g) + ": the shadow extinction must be finite and > 0, got " +
                    std::to_string(groom.extinction));
      // 16 slices: the compute builder, faster than the graphics one on lavapipe for the
      // ponytail's 50,000 strands (docs/performance.md, bench/hair_shadow_bench.cpp) and
      // bit-identical run to run.
      const OpacityShadowBuilder builder = mode == OpacityShadowMode::kOpacityShadowMap
                                               ? OpacityShadowBuilder::kCompute
                                               : OpacityShadowBuilder::kGraphics;
      auto map = OpacityShadowMapPass::create(
          *device_, groom.strands,
          {.mode = mode,
           .builder = builder,
           .resolution = groom.resolution > 0 ? std::min(groom.resolution, settings.resolution) : settings.resolution,
           .strandRadius = 0.5f * groom.width,
           .strandOpacity = groom.opacity,
           .extinction = groom.extinction});
      if (!map) return fail("groom " + std::to_string(g) + ": " + map.error().message);
      maps.push_back({std::move(*map), std::nullopt});
    }
  }
  maps_ = std::move(maps);
  mode_ = settings.mode;
  uniforms_ = {};
  return {};
}

Result<void> HairShadowPass::setBounds(std::size_t groom, const BoundingSphere& hair) {
  if (!(std::isfinite(hair.radius) && hair.radius > 0.0f) || !std::isfinite(hair.centre.x) ||
      !std::isfinite(hair.centre.y) || !std::isfinite(hair.centre.z))
    return fail("hair shadows: groom " + std::to_string(groom) + "'s bounding sphere is not finite and positive");
  if (groom < maps_.size()) maps_[groom].bounds = hair;
  return {};
}

void HairShadowPass::clearBounds(std::size_t groom) {
  if (groom < maps_.size()) maps_[groom].bounds.reset();
}

Result<void> HairShadowPass::setStrandWidth(std::size_t groom, float width) {
  if (!(std::isfinite(width) && width > 0.0f))
    return fail("hair shadows: groom " + std::to_string(groom) + "'s strand width " + std::to_string(width) +
                " m is not positive and finite");
  if (groom < maps_.size()) return maps_[groom].map->setStrandRadius(0.5f * width);
  return {};
}

void HairShadowPass::prepare(glm::vec3 towardLight) {
  uniforms_ = {};
  for (std::size_t g = 0; g < maps_.size(); ++g) {
    GroomMap& groom = maps_[g];
    // setBounds checked the sphere and callers pass a unit direction, so this cannot fail.
    groom.lit = groom.bounds && groom.map->setLight(towardLight, *groom.bounds).has_value();
    if (!groom.lit) continue;
    uniforms_.maps[g] = groom.map->uniforms();
    uniforms_.count.x = std::uint32_t(g + 1);
  }
}

void HairShadowPass::declare(FrameGraph::Builder& pass) const {
  for (const GroomMap& groom : maps_)
    if (groom.lit) groom.map->declare(pass);
}

void HairShadowPass::execute(const vk::raii::CommandBuffer& commands) const {
  for (const GroomMap& groom : maps_)
    if (groom.lit) groom.map->execute(commands);
}

void HairShadowPass::record(const vk::raii::CommandBuffer& commands, glm::vec3 towardLight) {
  prepare(towardLight);
  FrameGraph::recordAlone(commands, PassName::kHairShadows, *this);
}

void HairShadowPass::declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const {
  // The empty map is cleared once and never written again: nothing to wait for.
  for (const GroomMap& groom : maps_)
    if (groom.bounds) groom.map->declareReads(pass, stages);
}

SpecializationConstants HairShadowPass::shaderConstants() const {
  return {static_cast<std::uint32_t>(maps_.size()), mode_ == HairShadowMode::kDeepOpacityMap ? 1u : 0u};
}

void HairShadowPass::writeDescriptors(const vk::raii::DescriptorSet& set, std::uint32_t firstBinding) const {
  std::array<vk::DescriptorImageInfo, kBindings> images;
  for (std::uint32_t slot = 0; slot < kMaxMaps; ++slot) {
    const bool bound = slot < maps_.size() && maps_[slot].bounds;
    const OpacityShadowMapPass* map = bound ? maps_[slot].map.get() : nullptr;
    images[slot] = {.sampler = map ? *map->sampler() : *emptySampler_,
                    .imageView = map ? *map->opacityView() : *emptyOpacityView_,
                    .imageLayout = vk::ImageLayout::eShaderReadOnlyOptimal};
    images[kMaxMaps + slot] = {.sampler = map ? *map->firstDepthSampler() : *emptySampler_,
                               .imageView = map ? *map->firstDepthView() : *emptyDepthView_,
                               .imageLayout = vk::ImageLayout::eShaderReadOnlyOptimal};
  }
  std::array<vk::WriteDescriptorSet, kBindings> writes;
  for (std::uint32_t i = 0; i < kBindings; ++i)
    writes[i] = vk::WriteDescriptorSet{.dstSet = *set,
                                       .dstBinding = firstBinding + i,
                                       .descriptorCount = 1,
                                       .descriptorType = vk::DescriptorType::eCombinedImageSampler,
                                       .pImageInfo = &images[i]};
  device_->device().updateDescriptorSets(writes, {});
}

}  // namespace mane::render
