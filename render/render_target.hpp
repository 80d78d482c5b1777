#pragma once
// The images a frame renders into: HDR colour (RGBA16F, multisampled where asked, resolved to
// a single-sample image the post passes read), depth, and the 8-bit sRGB output.

#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "render/frame_graph.hpp"
#include "render/resources.hpp"

namespace mane::render {

struct RenderTargetSettings {
  vk::Extent2D extent{1280, 720};
  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  /// Single-sample only: keep the deferred skin's G-buffer (render/passes/deferred_skin_pass.hpp).
  bool skinGBuffer = false;
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
  /// The deferred skin's G-buffer, kGBufferImages RGBA32F images (position, geometric normal,
  /// detail normal, albedo): empty unless settings asked for it.
  static constexpr std::size_t kGBufferImages = 4;
  static constexpr vk::Format kGBufferFormat = vk::Format::eR32G32B32A32Sfloat;
  std::span<const Image> skinGBuffer() const { return skinGBuffer_; }

  /// The scene pass whole, or in two halves with work between them that reads the depth
  /// (HairOcclusionPass): kOpaque keeps the colour and depth at its end, unresolved; kRest
  /// continues on them and ends as the whole pass does.
  enum class ScenePart { kWhole, kOpaque, kRest };

  /// What scene pass `part` does to the images, for a frame graph: it draws into sceneColor()
  /// (cleared, except in kRest; resolved into hdr() at the end under MSAA) and tests against
  /// and writes depth() (cleared but after the skin's G-buffer pass; kept only for kRest).
  /// afterSkin: the deferred skin's G-buffer pass (below) drew the depth, and the pass reads the
  /// G-buffer.
  void declareScene(FrameGraph::Builder& pass, ScenePart part, bool afterSkin = false) const;
  /// Begins dynamic rendering of scene pass `part` (declareScene says what the frame graph must
  /// do before it), clearing to `clearColor` (linear RGBA) where it clears, and sets the viewport
  /// and scissor to the whole target. End it with commands.endRendering().
  void beginScenePart(const vk::raii::CommandBuffer& commands, ScenePart part, const glm::vec4& clearColor,
                      bool afterSkin = false) const;
  /// The whole scene pass outside a frame graph (tests, benchmarks): after every earlier command,
  /// drops the colour and depth images' old contents and begins it. hdr() is then in
  /// COLOR_ATTACHMENT_OPTIMAL after commands.endRendering().
  void beginScene(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor) const;

  /// The deferred skin's G-buffer pass, before the scene pass
  /// (render/passes/deferred_skin_pass.hpp): it drops the G-buffer's and the depth's old contents
  /// and draws into the G-buffer (not cleared: only the pixels the skin writes are read) and the
  /// depth (cleared to 1, kept), for a frame graph. Then declare the scene pass with afterSkin.
  void declareSkinGBuffer(FrameGraph::Builder& pass) const;
  /// Begins the G-buffer pass's dynamic rendering (declareSkinGBuffer says what the frame graph
  /// must do before it). End it with commands.endRendering().
  void beginSkinGBuffer(const vk::raii::CommandBuffer& commands) const;

private:
  RenderTargetSettings settings_;
  Image msaaColor_;
  Image hdr_;
  Image depth_;
  Image output_;
  std::vector<Image> skinGBuffer_;
};

}  // namespace mane::render
