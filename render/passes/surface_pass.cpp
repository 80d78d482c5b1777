#include "render/passes/surface_pass.hpp"

#include "render/passes/deferred_skin_pass.hpp"

namespace mane::render {

SurfacePass::SurfacePass(const Device& device, const SurfaceScene& scene, const TranslucencyPass& translucency,
                         const HairShadowPass& shadows, vk::Format colorFormat, vk::Format depthFormat,
                         vk::SampleCountFlagBits samples)
    : device_(&device),
      scene_(&scene),
      translucency_(&translucency),
      shadows_(&shadows),
      colorFormat_(colorFormat),
      depthFormat_(depthFormat),
      samples_(samples) {
  buildPipelines();
}

std::size_t SurfacePass::pipelineFor(const SurfaceMaterial& material) {
  std::size_t shading = 0;
  if (material.shading == SurfaceShading::kSkin)
    shading = material.skin.diffusion == SkinDiffusion::kTextureSpace ? 2 : 1;
  return shading * kTranslucencyMethods + static_cast<std::size_t>(material.translucency.method);
}

void SurfacePass::buildPipelines() {
  std::array<bool, kShadings * kTranslucencyMethods> used{};
  used[0] = true;  // Lambert: its layout binds the frame set even when nothing is drawn
  for (std::size_t m = 0; m < scene_->materialCount(); ++m) used[pipelineFor(scene_->material(m))] = true;
  for (std::size_t variant = 0; variant < pipelines_.size(); ++variant) {
    pipelines_[variant] = {};
    if (!used[variant]) continue;
    const std::size_t shading = variant / kTranslucencyMethods;
    GraphicsPipelineSettings settings = scene_->meshPipeline(depthFormat_);
    settings.fragmentShader = "surface.frag";
    settings.colorFormats = {colorFormat_};
    settings.samples = samples_;
    settings.setLayouts = {scene_->frameLayout(), scene_->materialLayout(), translucency_->thicknessLayout()};
    // Constants 0, 1: the hair shadow maps (shaders/hair_shadows.glsl); 2: skin; 3: its diffuse
    // light from the texture-space diffusion instead of the pre-integrated table; 4: the
    // translucency method (shaders/translucency.glsl).
    settings.constants = shadows_->shaderConstants();
    settings.constants.push_back(shading != 0 ? 1u : 0u);
    settings.constants.push_back(shading == 2 ? 1u : 0u);
    settings.constants.push_back(static_cast<std::uint32_t>(variant % kTranslucencyMethods));
    pipelines_[variant] = makeGraphicsPipeline(*device_, settings);
  }
}

void SurfacePass::draw(const vk::raii::CommandBuffer& commands, const FrameInput& frame, bool skinDeferred) const {
  // Every pipeline shares one layout.
  const vk::PipelineLayout layout = *pipelines_[0].layout;
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0, {*scene_->frameSet()}, {});
  const Pipeline* bound = nullptr;
  for (const MeshInstance& instance : frame.instances) {
    const SurfaceMaterial& material = scene_->material(instance);
    if (material.shading == SurfaceShading::kFur && frame.furShells) continue;  // the fur pass draws its skin
    if (skinDeferred && DeferredSkinPass::deferrable(material)) continue;       // drawn into the G-buffer
    const Pipeline& pipeline = pipelines_[pipelineFor(material)];
    if (bound != &pipeline) commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline.pipeline);
    bound = &pipeline;
    commands.bindDescriptorSets(
        vk::PipelineBindPoint::eGraphics, layout, 1,
        {*scene_->materialSet(instance.material), *translucency_->thicknessSet(instance, *scene_)}, {});
    scene_->drawMesh(commands, layout, instance);
  }
}

}  // namespace mane::render
