#pragma once
// The images a frame renders into: HDR colour (RGBA16F, multisampled where asked, resolved to
// a single-sample image the post passes read), depth, and the 8-bit sRGB output.

#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "render/resources.hpp"

namespace mane::render {

struct RenderTargetSettings {
  vk::Extent2D extent{1280, 720};
  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  /// Single-sample only: keep the deferred skin's G-buffer (render/passes/surface_pass.hpp,
  /// "Deferred skin").
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

  /// Starts the main scene pass: discards the colour and depth images' old contents, begins
  /// dynamic rendering into sceneColor() (cleared to `clearColor`, linear RGBA; resolved into
  /// hdr() at the end under MSAA) and depth (cleared to 1, not kept), and sets the viewport and
  /// scissor to the whole target. End it with commands.endRendering(); hdr() is then in
  /// COLOR_ATTACHMENT_OPTIMAL.
  /// afterSkin: the deferred skin's G-buffer pass (below) has drawn the depth: keep it, and make
  /// the G-buffer readable by fragment shaders (SHADER_READ_ONLY layout).
  void beginScene(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor, bool afterSkin = false) const;

  /// The scene pass in two halves, with work between them that reads the depth (HairOcclusion):
  /// beginOpaque starts it as beginScene does but keeps the colour and depth at its end, unresolved;
  /// resumeScene continues it on them, then ends as beginScene's pass does. End each half with
  /// commands.endRendering().
  void beginOpaque(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor, bool afterSkin = false) const;
  void resumeScene(const vk::raii::CommandBuffer& commands) const;

  /// The deferred skin's G-buffer pass, before the scene pass (render/passes/surface_pass.hpp,
  /// "Deferred skin"): discards the G-buffer's and the depth's old contents and begins dynamic
  /// rendering into the G-buffer (not cleared: only the pixels the skin writes are read) and the
  /// depth (cleared to 1, kept). End it with commands.endRendering(), then begin the scene pass
  /// with afterSkin.
  void beginSkinGBuffer(const vk::raii::CommandBuffer& commands) const;

private:
  enum class ScenePart { kWhole, kOpaque, kRest };
  void begin(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor, ScenePart part,
             bool afterSkin) const;

  RenderTargetSettings settings_;
  Image msaaColor_;
  Image hdr_;
  Image depth_;
  Image output_;
  std::vector<Image> skinGBuffer_;
};

}  // namespace mane::render
