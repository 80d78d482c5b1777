#include "render/passes/surface_shadow_pass.hpp"

#include <algorithm>
#include <cmath>

#include "render/passes/surface_scene.hpp"

namespace mane::render {
namespace {

/// A skinned mesh moves away from its bind pose; its bind-pose sphere is widened by this much to
/// hold it through its clips.
constexpr float kSkinnedBoundsMargin = 1.5f;

}  // namespace

SurfaceShadowPass::SurfaceShadowPass(const Device& device, std::uint32_t vertexStride)
    : depth_(device, vertexStride),
      compare_(device.device(), vk::SamplerCreateInfo{.magFilter = vk::Filter::eLinear,
                                                      .minFilter = vk::Filter::eLinear,
                                                      .addressModeU = vk::SamplerAddressMode::eClampToEdge,
                                                      .addressModeV = vk::SamplerAddressMode::eClampToEdge,
                                                      .addressModeW = vk::SamplerAddressMode::eClampToEdge,
                                                      .compareEnable = true,
                                                      .compareOp = vk::CompareOp::eLessOrEqual,
                                                      .maxLod = 0.0f}) {}

void SurfaceShadowPass::prepare(const FrameInput& frame, const SurfaceScene& scene) {
  draws_.clear();
  DrawnBounds bounds;
  if (!frame.lights.empty()) {
    for (const MeshInstance& instance : frame.instances) {
      if (!scene.canDraw(instance)) continue;
      draws_.push_back({.vertices = scene.vertices(instance.mesh),
                        .indices = scene.indices(instance.mesh),
                        .indexCount = scene.indexCount(instance.mesh),
                        .model = instance.model});
      bounds.add(scene.bounds(instance.mesh), instance.model,
                 scene.isSkinned(instance.mesh) ? kSkinnedBoundsMargin : 1.0f);
    }
  }
  const glm::vec3 towardLight = frame.lights.empty() ? glm::vec3(0, 1, 0) : glm::normalize(frame.lights[0].direction);
  depth_.prepare(towardLight, bounds.sphere(), !draws_.empty());
  const float texel = 1.0f / LightDepthPass::kResolution;  // map units
  const float discRadius = frame.lights.empty() ? 0.0f : std::clamp(frame.lights[0].discRadius, 0.0f, 1.5f);
  uniforms_ = {.map = depth_.uniforms(),
               .penumbra = {std::tan(discRadius), kWidestSearchTexels * texel, kMinimumFilterTexels * texel,
                            kNormalOffsetTexels * depth_.uniforms().scale.z}};
}

void SurfaceShadowPass::declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const {
  pass.read(depth_.image(), ResourceUse::sampled(stages));
}

}  // namespace mane::render
