#pragma once
// Opaque meshes drawn forward and lit by directional lights (shaders/surface.frag): albedo
// texture × base colour, tangent-space normal map, ambient, and per material either Lambert
// diffuse or skin (render/passes/skin_shading.hpp: the pre-integrated table, or the irradiance
// diffused in texture space), with translucency where the material asks for it
// (render/passes/translucency_pass.hpp); the first light is attenuated by the hair shadows
// (render/passes/hair_shadow_pass.hpp). Skin that the frame defers (render/passes/deferred_skin_pass.hpp)
// and fur materials drawn as shells (render/passes/fur_pass.hpp) are left to their passes. The
// meshes, materials and frame uniforms are the scene's (render/passes/surface_scene.hpp).

#include <array>

#include "render/frame.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/passes/surface_scene.hpp"
#include "render/passes/translucency_pass.hpp"
#include "render/pipelines.hpp"

namespace mane::render {

class SurfacePass {
public:
  /// Draws into `colorFormat` over depth `depthFormat` with `samples` samples. `scene`,
  /// `translucency` and `shadows` must outlive the pass.
  SurfacePass(const Device& device, const SurfaceScene& scene, const TranslucencyPass& translucency,
              const HairShadowPass& shadows, vk::Format colorFormat, vk::Format depthFormat,
              vk::SampleCountFlagBits samples);

  /// Builds the pipelines the scene's materials use, for the hair shadows' current maps (after
  /// SurfaceScene::setScene and HairShadowPass::setGrooms). Throws vk::SystemError on failure.
  void buildPipelines();

  /// Draws every instance of the frame (Renderer::render has checked them with
  /// SurfaceScene::canDraw) but those with a fur material while FrameInput::furShells is on, and
  /// with `skinDeferred` the deferred skin's; inside a dynamic rendering scope with matching
  /// formats, after SurfaceScene::update.
  void draw(const vk::raii::CommandBuffer& commands, const FrameInput& frame, bool skinDeferred = false) const;

private:
  // Pipelines: shading (Lambert, pre-integrated skin, texture-space skin) × translucency method.
  static constexpr std::size_t kShadings = 3;
  static constexpr std::size_t kTranslucencyMethods = 3;
  static std::size_t pipelineFor(const SurfaceMaterial& material);

  const Device* device_;
  const SurfaceScene* scene_;
  const TranslucencyPass* translucency_;
  const HairShadowPass* shadows_;
  vk::Format colorFormat_;
  vk::Format depthFormat_;
  vk::SampleCountFlagBits samples_;
  std::array<Pipeline, kShadings * kTranslucencyMethods> pipelines_;  ///< one layout; unused ones empty
};

}  // namespace mane::render
