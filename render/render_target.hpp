#pragma once
// The images a frame renders into: HDR colour (RGBA16F, multisampled where asked, resolved to
// a single-sample image the post passes read), depth, and the 8-bit sRGB output.

#include <glm/vec4.hpp>

#include "render/resources.hpp"

namespace mane::render {

struct RenderTargetSettings {
  vk::Extent2D extent{1280, 720};
  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
};

class RenderTarget {
public:
  static constexpr vk::Format kHdrFormat = vk::Format::eR16G16B16A16Sfloat;
  static constexpr vk::Format kDepthFormat = vk::Format::eD32Sfloat;
  static constexpr vk::Format kOutputFormat = vk::Format::eR8G8B8A8Srgb;

  RenderTarget(const Device& device, const RenderTargetSettings& settings);

  vk::Extent2D extent() const { return settings_.extent; }
  vk::SampleCountFlagBits samples() const { return settings_.samples; }
  float aspect() const { return float(settings_.extent.width) / float(settings_.extent.height); }
  bool multisampled() const { return settings_.samples != vk::SampleCountFlagBits::e1; }

  /// Where the scene is drawn: the multisampled image, or `hdr()` itself without MSAA.
  const Image& sceneColor() const { return multisampled() ? msaaColor_ : hdr_; }
  /// Single-sample HDR colour (the resolve target under MSAA); sampled by post passes.
  const Image& hdr() const { return hdr_; }
  const Image& depth() const { return depth_; }
  /// 8-bit sRGB display image; can be copied to the host or blitted to a swapchain.
  const Image& output() const { return output_; }

  /// Starts the main scene pass: discards the colour and depth images' old contents, begins
  /// dynamic rendering into sceneColor() (cleared to `clearColor`, linear RGBA; resolved into
  /// hdr() at the end under MSAA) and depth (cleared to 1, not kept), and sets the viewport and
  /// scissor to the whole target. End it with commands.endRendering(); hdr() is then in
  /// COLOR_ATTACHMENT_OPTIMAL.
  void beginScene(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor) const;

  /// The scene pass in two halves, with work between them that reads the depth (HairOcclusion):
  /// beginOpaque starts it as beginScene does but keeps the colour and depth at its end, unresolved;
  /// resumeScene continues it on them, then ends as beginScene's pass does. End each half with
  /// commands.endRendering().
  void beginOpaque(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor) const;
  void resumeScene(const vk::raii::CommandBuffer& commands) const;

private:
  enum class ScenePart { kWhole, kOpaque, kRest };
  void begin(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor, ScenePart part) const;

  RenderTargetSettings settings_;
  Image msaaColor_;
  Image hdr_;
  Image depth_;
  Image output_;
};

}  // namespace mane::render
