#pragma once
// The opaque scene's depth, reduced to the farthest value per square tile of the frame, for
// HairPass to hide the strands behind it (hair_pass.hpp, "Hidden strands"). It runs after the
// deferred skin's G-buffer pass, or else between the two halves of the main pass, after the
// surfaces and furs have written their depth; before the hair is chosen, shaded and drawn
// (shaders/hair_occlusion.glsl: one invocation per tile, every sample of every pixel in it).

#include <glm/vec2.hpp>

#include "render/frame_graph.hpp"
#include "render/passes/hair_pass.hpp"
#include "render/pipelines.hpp"
#include "render/render_target.hpp"
#include "render/resources.hpp"

namespace mane::render {

class HairOcclusionPass {
public:
  /// Tiles of this many pixels: 8 keeps the reduction at 64 reads per invocation (256 at 4×
  /// MSAA) and a strand segment's box within a few tiles.
  static constexpr std::uint32_t kTileSize = 8;

  /// For the depth of `target`, which must outlive the pass.
  HairOcclusionPass(const Device& device, const RenderTarget& target);

  /// What the reduction reads (the target's depth, sampled) and writes (the tiles), for a frame
  /// graph.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the reduction outside a rendering scope, after opaque draws; the barriers and the
  /// depth's layout come from a frame graph (declare).
  void execute(const vk::raii::CommandBuffer& commands) const;

  [[nodiscard]] const Buffer& tileMaxDepth() const { return tiles_; }
  [[nodiscard]] HairOcclusionTiles tiles() const { return grid_; }

private:
  const RenderTarget* target_;
  HairOcclusionTiles grid_;
  Buffer tiles_;
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Pipeline pipeline_;
};

}  // namespace mane::render
