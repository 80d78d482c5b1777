#pragma once
// HDR colour → the 8-bit sRGB output image: a linear exposure scale, clamped; the sRGB
// attachment applies the transfer curve. Tone mapping and glow come with the post issue.

#include "render/pipelines.hpp"
#include "render/render_target.hpp"

namespace mane::render {

class OutputPass {
public:
  OutputPass(const Device& device, const RenderTarget& target);

  /// Reads target.hdr() (in SHADER_READ_ONLY layout) and writes target.output() (in
  /// COLOR_ATTACHMENT layout).
  void record(const vk::raii::CommandBuffer& commands, const RenderTarget& target, float exposure) const;

private:
  vk::raii::DescriptorSetLayout layout_{nullptr};
  Pipeline pipeline_;
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
};

}  // namespace mane::render
