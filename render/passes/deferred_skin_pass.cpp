#include "render/passes/deferred_skin_pass.hpp"

#include <stdexcept>
#include <string>

#include "render/descriptors.hpp"
#include "render/render_target.hpp"

namespace mane::render {

DeferredSkinPass::DeferredSkinPass(const Device& device, const SurfaceScene& scene, const HairShadowPass& shadows,
                                   vk::Format colorFormat, vk::Format depthFormat)
    : device_(&device), scene_(&scene), shadows_(&shadows), colorFormat_(colorFormat), depthFormat_(depthFormat) {
  static_assert(RenderTarget::kGBufferImages == 4, "shaders/skin_deferred.frag reads four images");
  const std::pair texture{vk::DescriptorType::eCombinedImageSampler,
                          vk::ShaderStageFlags(vk::ShaderStageFlagBits::eFragment)};
  gBufferLayout_ = makeSetLayout(device, {texture, texture, texture, texture});
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eRepeat, 1.0f);
}

void DeferredSkinPass::setGBuffer(std::span<const Image> gBuffer) {
  if (gBuffer.size() != RenderTarget::kGBufferImages)
    throw std::invalid_argument("setGBuffer: the G-buffer needs " + std::to_string(RenderTarget::kGBufferImages) +
                                " images, got " + std::to_string(gBuffer.size()));
  gBufferPool_ =
      makeDescriptorPool(*device_, 1, {{vk::DescriptorType::eCombinedImageSampler, RenderTarget::kGBufferImages}});
  gBufferSet_ = allocateSet(*device_, gBufferPool_, gBufferLayout_);
  for (std::size_t i = 0; i < gBuffer.size(); ++i)
    writeSampledImage(*device_, gBufferSet_, static_cast<std::uint32_t>(i), gBuffer[i], sampler_);
  gBufferExtent_ = gBuffer.front().extent();
}

void DeferredSkinPass::buildPipelines() {
  gBufferPipeline_ = {};
  lightingPipeline_ = {};
  // Only with a G-buffer to draw into (single-sample targets alone keep one).
  bool skin = false;
  for (std::size_t m = 0; m < scene_->materialCount(); ++m) skin = skin || deferrable(scene_->material(m));
  if (!*gBufferSet_ || !skin) return;
  GraphicsPipelineSettings gBuffer = scene_->meshPipeline(depthFormat_);
  gBuffer.fragmentShader = "skin_gbuffer.frag";
  gBuffer.colorFormats.assign(RenderTarget::kGBufferImages, RenderTarget::kGBufferFormat);
  gBuffer.setLayouts = {scene_->frameLayout(), scene_->materialLayout()};
  // As the forward pipeline of deferrable skin: no translucency, the pre-integrated table.
  gBuffer.constants = shadows_->shaderConstants();
  gBuffer.constants.insert(gBuffer.constants.end(), {1u, 0u, 0u});
  gBufferPipeline_ = makeGraphicsPipeline(*device_, gBuffer);
  // Over the screen at the far plane (the viewport's depth range, set when drawn): its depth test
  // passes where the G-buffer pass left skin nearer than that.
  lightingPipeline_ = makeGraphicsPipeline(
      *device_,
      GraphicsPipelineSettings{.vertexShader = "fullscreen.vert",
                               .fragmentShader = "skin_deferred.frag",
                               .colorFormats = {colorFormat_},
                               .depthFormat = depthFormat_,
                               .depthTest = true,
                               .depthCompare = vk::CompareOp::eGreater,
                               .setLayouts = {scene_->frameLayout(), scene_->materialLayout(), *gBufferLayout_},
                               .constants = gBuffer.constants});
}

bool DeferredSkinPass::deferrable(const SurfaceMaterial& material) {
  return material.shading == SurfaceShading::kSkin && material.skin.diffusion != SkinDiffusion::kTextureSpace &&
         material.translucency.method == TranslucencyMethod::kNone;
}

std::optional<std::size_t> DeferredSkinPass::deferredMaterial(const FrameInput& frame) const {
  std::optional<std::size_t> found;
  for (const MeshInstance& instance : frame.instances) {
    if (!deferrable(scene_->material(instance))) continue;
    if (found && *found != instance.material) return std::nullopt;
    found = instance.material;
  }
  return found;
}

bool DeferredSkinPass::defersSkin(const FrameInput& frame) const {
  return *lightingPipeline_.pipeline && *gBufferSet_ && deferredMaterial(frame).has_value();
}

void DeferredSkinPass::drawGBuffer(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const {
  const vk::PipelineLayout layout = *gBufferPipeline_.layout;
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *gBufferPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0,
                              {*scene_->frameSet(), *scene_->materialSet(*deferredMaterial(frame))}, {});
  for (const MeshInstance& instance : frame.instances)
    if (deferrable(scene_->material(instance))) scene_->drawMesh(commands, layout, instance);
}

void DeferredSkinPass::drawLighting(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const {
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *lightingPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *lightingPipeline_.layout, 0,
                              {*scene_->frameSet(), *scene_->materialSet(*deferredMaterial(frame)), *gBufferSet_}, {});
  commands.setViewport(0, vk::Viewport{.width = float(gBufferExtent_.width),
                                       .height = float(gBufferExtent_.height),
                                       .minDepth = 1.0f,
                                       .maxDepth = 1.0f});
  commands.draw(3, 1, 0, 0);
  setViewportAndScissor(commands, gBufferExtent_);
}

}  // namespace mane::render
