#pragma once
// Deferred skin (single-sample targets that keep a G-buffer: RenderTargetSettings::skinGBuffer).
// lavapipe runs a fragment shader on whole 4 × 4 blocks of every triangle it touches, so a head
// whose triangles cover a few pixels each runs several invocations per covered pixel
// (docs/lavapipe.md#fragments-are-shaded-in-4--4-blocks). So where a frame's pre-integrated skin
// (without translucency) uses one material, it is drawn first into the G-buffer and the depth by
// shaders/skin_gbuffer.frag, which does only what needs screen derivatives (the normal map's frame,
// the textures' mip levels). The main pass then lights it with shaders/skin_deferred.frag on a
// triangle over the screen at the far plane, depth-tested "greater" against the skin, so that
// lavapipe skips the shading of the blocks without skin and lights each skin pixel once, before
// drawing the other surfaces over it (SurfacePass leaves those instances out). Both halves run the
// forward shader's operations on the same values (the G-buffer is RGBA32F), so the image is the
// same. Skin's shading: render/passes/skin_shading.hpp.

#include <optional>
#include <span>

#include "render/frame.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/passes/surface_scene.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

class DeferredSkinPass {
public:
  /// Lights into `colorFormat` over depth `depthFormat`, single-sample. `scene` and `shadows`
  /// must outlive the pass.
  DeferredSkinPass(const Device& device, const SurfaceScene& scene, const HairShadowPass& shadows,
                   vk::Format colorFormat, vk::Format depthFormat);

  /// The G-buffer (RenderTarget::skinGBuffer) the skin is drawn into and lit from; it must
  /// outlive the pass. Before buildPipelines, which builds them only when a G-buffer is set.
  void setGBuffer(std::span<const Image> gBuffer);
  /// Builds the pipelines for the scene's materials and the hair shadows' current maps (after
  /// SurfaceScene::setScene and HairShadowPass::setGrooms); none without a G-buffer or skin to defer.
  void buildPipelines();

  /// Whether `material` would be deferred: pre-integrated skin without translucency.
  [[nodiscard]] static bool deferrable(const SurfaceMaterial& material);
  /// Whether the frame's skin is deferred: a G-buffer is set, and the frame's deferrable
  /// instances, at least one, share a material.
  [[nodiscard]] bool defersSkin(const FrameInput& frame) const;

  /// Draws those instances into the G-buffer; inside RenderTarget::beginSkinGBuffer's scope.
  void drawGBuffer(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const;
  /// Lights the G-buffer's skin; first in the scene pass declared and begun with afterSkin
  /// (RenderTarget::beginScenePart), whose depth is still the G-buffer pass's.
  void drawLighting(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const;

private:
  /// The one material of the frame's deferrable instances; none when they have none or several.
  std::optional<std::size_t> deferredMaterial(const FrameInput& frame) const;

  const Device* device_;
  const SurfaceScene* scene_;
  const HairShadowPass* shadows_;
  vk::Format colorFormat_;
  vk::Format depthFormat_;
  Pipeline gBufferPipeline_;
  Pipeline lightingPipeline_;
  // The G-buffer's set (set 2 of the lighting; empty until setGBuffer) and its images' size.
  vk::raii::DescriptorSetLayout gBufferLayout_{nullptr};
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorPool gBufferPool_{nullptr};
  vk::raii::DescriptorSet gBufferSet_{nullptr};
  vk::Extent2D gBufferExtent_{};
};

}  // namespace mane::render
