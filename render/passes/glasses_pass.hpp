#pragma once
// Spectacle lenses (render/lens.hpp) drawn over the finished scene by screen-space refraction:
// a copy of the frame's colour, then each lens's front surface, whose fragments trace the eye's
// ray through the glass (shaders/glasses_refraction.glsl) and read what it meets in the copy and
// the frame's depth. After the surfaces and the hair, before the post chain; not multisampled (a
// lens's edge lies under its rim).
//
// What the copy does not hold, the lenses cannot show: a ray that leaves the screen or meets
// something hidden in the frame finds the environment or the nearest thing the frame shows, and
// hair in front of a lens is drawn over by it.

#include <span>

#include "render/frame_graph.hpp"
#include "render/lens.hpp"
#include "render/passes/surface_scene.hpp"
#include "render/pipelines.hpp"
#include "render/render_target.hpp"
#include "render/resources.hpp"

namespace mane::render {

class GlassesPass {
public:
  /// Reads `scene`'s frame set (camera, lights, environment) and draws into `target`; both must
  /// outlive the pass. Throws vk::SystemError on failure.
  GlassesPass(const Device& device, const SurfaceScene& scene, const RenderTarget& target);

  /// The frame's view; before recording, after SurfaceScene::update.
  void prepare(const FrameInput& frame, float aspect);
  /// The copy of the frame's colour, for a frame graph, and its commands.
  void declareCopy(FrameGraph::Builder& pass) const;
  void recordCopy(const vk::raii::CommandBuffer& commands) const;
  /// The lenses drawn over the frame's colour, for a frame graph, and their commands.
  void declareDraw(FrameGraph::Builder& pass) const;
  void recordDraw(const vk::raii::CommandBuffer& commands, std::span<const Lens> lenses) const;

private:
  const SurfaceScene* scene_;
  const RenderTarget* target_;
  Image behind_;  // the frame's colour before the lenses
  Buffer view_;   // GlassesView of shaders/glasses_refraction.glsl
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::Sampler depthSampler_{nullptr};
  vk::raii::DescriptorSetLayout layout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Pipeline pipeline_;
};

}  // namespace mane::render
