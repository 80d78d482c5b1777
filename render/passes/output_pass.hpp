#pragma once
// HDR colour → the 8-bit sRGB output image (shaders/output.frag): the post chain's overlay applied
// (render/passes/post_pass.hpp: the gain — FrameInput::exposure, or the automatic gain — with the
// glow mixed in and the god rays added), or without the chain the exposure alone, then a tone map:
// the linear scale, clamped, or Reinhard's L/(1 + L) (Reinhard et al. 2002, eq. 3); the sRGB
// attachment applies the transfer curve. Each combination of tone map and use of the overlay is
// its own specialised pipeline, made the first time a frame asks for it; the default one (linear,
// no chain: the plain exposure scale) is made up front.

#include <array>

#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/passes/post_pass.hpp"
#include "render/pipelines.hpp"
#include "render/render_target.hpp"

namespace mane::render {

class OutputPass {
public:
  /// `post` (which must outlive the pass) provides the overlay.
  OutputPass(const Device& device, const RenderTarget& target, const PostPass& post);

  /// What `record` reads (target.hdr(), and where `post` runs the chain its overlay) and writes
  /// (target.output(), whose old contents it drops), for a frame graph.
  void declare(FrameGraph::Builder& pass, const RenderTarget& target, const PostSettings& post) const;
  /// Reads target.hdr() (in SHADER_READ_ONLY layout) and, where `post` runs the chain, its
  /// overlay (recorded before, this frame: PostPass::recordHandOff), and writes target.output()
  /// (in COLOR_ATTACHMENT layout).
  void record(const vk::raii::CommandBuffer& commands, const RenderTarget& target, float exposure,
              const PostSettings& post);

private:
  const Pipeline& pipelineFor(ToneMapping toneMapping, PostPass::OverlayUse overlay);

  const Device* device_;
  const PostPass* post_;
  vk::raii::DescriptorSetLayout layout_{nullptr};
  /// [tone mapping][overlay use]
  std::array<Pipeline, 6> pipelines_;
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
};

}  // namespace mane::render
