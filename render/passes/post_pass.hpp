#pragma once
// HDR post-processing before the output pass, after NVIDIA's "Timbury" demo (Ryan Geiss 2004;
// docs/design.md#sources): "draw the scene into a large fp16 texture, analyse its brightness, keep
// a copy and blur it generously, mix the blurred and the sharp images to soften the picture, darken
// with the result of the brightness analysis". Compute passes on small images, so the only
// full-size work is one read of the frame here and the output pass (every full-screen pass is
// expensive on lavapipe, docs/lavapipe.md#full-screen-passes):
//  1. Downsample (shaders/post_downsample.comp): the HDR frame to a copy 4× smaller per side, each
//     texel the mean of a 4×4 block.
//  2. Glow (shaders/post_blur.comp): four separable Gaussian blurs of the copy, along x, y, x, y
//     (Timbury's "pseudo-Gaussian, but fast"), with normalised weights; the output pass mixes the
//     result with the sharp frame by PostSettings::glowStrength.
//  3. Auto gain (shaders/post_tiny.comp, post_adapt.comp): the copy reduced to at most 64×64 texels,
//     its log-average luminance L̄ = exp(mean(log(δ + L))) ([RSSF02] eq. 1) by one workgroup in a
//     fixed order, and the adapted L̄ moved towards it by 1 − exp(−Δt/τ) in log luminance, kept in
//     a small GPU buffer from frame to frame. The gain exposure · a / L̄ maps the adapted log-average
//     to the key value a ([RSSF02] eq. 2); the output pass applies it and the tone map (Reinhard's
//     L/(1 + L) or the linear scale, render/passes/output_pass.hpp).
//  4. God rays (shaders/post_ray_*.comp; bright regions and occluders rendered to a buffer,
//     converted to polar coordinates around the light's screen position, blurred along the radius,
//     converted back and added): the copy's texels above a luminance threshold (the rest,
//     occluders, 0), a polar image around the light (one column per angle, one row per copy
//     texel of radius), a blur down each column away from the light with decaying weights, and the
//     inverse transform to the copy's grid; the output pass adds it × PostSettings::godRays.
//  5. Hand-off (shaders/post_overlay.comp): the gain, the glow's share and the god rays folded
//     into one image on the copy's grid, the overlay (rgb to add, alpha the frame's scale), so that
//     the full-size output pass takes one bilinear sample and reads no buffer: on lavapipe each
//     extra sample or buffer read there costs about as much as the plain output pass itself
//     (docs/lavapipe.md#full-screen-passes).
// Timbury's automatic gain averages luminance linearly and divides by it; the log-average is
// Reinhard's, which the Timbury slides name as the better-balanced alternative (a few very bright
// pixels, like the sun, pull a linear mean far more).
//
//   [RSSF02] Reinhard, Stark, Shirley & Ferwerda, "Photographic Tone Reproduction for Digital
//            Images", SIGGRAPH 2002.
//
// The numbers (sizes, the kernel) and CPU references of every step: render/passes/post_reference.hpp.
// Cost on lavapipe: bench/post_bench.cpp.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/passes/post_reference.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// The auto gain's state, kept on the GPU between frames (std430 `Exposure` in
/// shaders/post_adapt.comp).
struct PostExposure {
  float adaptedLogLuminance = 0.0f;  ///< log L̄_adapted, natural log of luminance
  float frameLogLuminance = 0.0f;    ///< log L̄ of the last frame measured
  float gain = 0.0f;                 ///< exposure · key / L̄_adapted: what the output pass multiplies by
  std::uint32_t frames = 0;          ///< frames measured since creation or the last reset; 0: the next one snaps
};

/// An error naming the bad field: a key that is not positive and finite, a glow strength outside
/// [0, 1], a negative or non-finite adaptation time or frame time, or an unknown tone mapping.
[[nodiscard]] Result<void> validate(const PostSettings& settings);

/// Where a directional light (`direction` towards it, world space) appears on screen, as frame uv
/// (0..1, v downwards); none when it is behind the camera or outside the frame (no god rays then).
std::optional<glm::vec2> godRayLightUv(const Camera& camera, glm::vec3 direction, float aspect);

class PostPass {
public:
  static constexpr vk::Format kFormat = vk::Format::eR16G16B16A16Sfloat;

  /// The images and pipelines for frames the size of `frame`, which the passes sample (in
  /// SHADER_READ_ONLY layout when recorded); it must outlive the chain. Throws on a Vulkan
  /// failure, or on a device that cannot filter RGBA32F images (the overlay's format; lavapipe
  /// and desktop GPUs can).
  PostPass(const Device& device, const Image& frame);

  /// Whether `settings` needs any of the passes here (glow, auto gain or god rays); the defaults
  /// need none.
  static bool runs(const PostSettings& settings) {
    return settings.glowStrength > 0.0f || settings.autoGain || settings.godRays > 0.0f;
  }

  /// The passes `settings` asks for, in order: downsample, auto gain, glow, god rays (when
  /// `godRayLight`, the light's frame uv, is given); then the barrier that hands their results to
  /// the output pass's fragment shader. Outside rendering.
  void record(const vk::raii::CommandBuffer& commands, const PostSettings& settings, float exposure,
              std::optional<glm::vec2> godRayLight = std::nullopt);
  /// Step 1: the frame → the downsampled copy. Starts a frame: no god rays until recordGodRays.
  void recordDownsample(const vk::raii::CommandBuffer& commands);
  /// What step 1 reads of the frame (sampled by a compute shader), for a frame graph. The steps
  /// use no other image of another pass; the barriers between them are the chain's own.
  void declareDownsample(FrameGraph::Builder& pass) const;
  /// Step 3, after recordDownsample: the tiny image, its log-average, the adaptation, the gain.
  /// `exposure` multiplies the gain (exposure compensation). Next frame starts from the state this
  /// leaves, so record it once per frame.
  void recordAutoGain(const vk::raii::CommandBuffer& commands, const PostSettings& settings, float exposure);
  /// Step 2, after recordDownsample: the four blurs into the glow (readGlow()).
  void recordGlow(const vk::raii::CommandBuffer& commands) const;
  /// Step 4, after recordDownsample: god rays around `lightUv` (frame uv), with
  /// settings.godRayThreshold and godRayDecay (readGodRays()). `blur` false skips the radial
  /// blur: the bare polar round trip, for tests. The hand-off adds them this frame
  /// (godRaysRecorded()).
  void recordGodRays(const vk::raii::CommandBuffer& commands, const PostSettings& settings, glm::vec2 lightUv,
                     bool blur = true);
  /// Step 5, last: folds what `settings` asked this frame (the auto gain or `exposure`, the glow,
  /// the god rays where recordGodRays ran) into overlay() and makes it, and the exposure state,
  /// visible to fragment shaders (and the state to the host).
  void recordHandOff(const vk::raii::CommandBuffer& commands, const PostSettings& settings, float exposure);
  /// What step 5 leaves for the output pass (overlay(), made visible by its own barrier), for a
  /// frame graph.
  void declareHandOff(FrameGraph::Builder& pass) const;

  /// What the output pass reads of overlay() (shaders/output.frag's kOverlay).
  enum class OverlayUse : std::uint32_t {
    kNone,      ///< nothing: the exposure alone scales the frame
    kScale,     ///< alpha alone, the same in every texel: the auto gain
    kFiltered,  ///< bilinear samples: alpha scales the frame, rgb is added (glow, god rays)
  };
  /// The use of the overlay the last recordHandOff made (kNone before any).
  OverlayUse overlayUse() const { return overlayUse_; }
  /// rgb: g·(s·glow + r·rays), alpha: g·(1 − s), on the downsampled copy's grid, GENERAL layout
  /// (shaders/post_overlay.comp); bilinear-sample it with sampler().
  const Image& overlay() const { return overlay_; }
  /// Whether recordGodRays ran since the last recordDownsample.
  bool godRaysRecorded() const { return godRaysRecorded_; }
  /// The light in the downsampled copy's texel coordinates, for frame uv `lightUv`.
  glm::vec2 godRayCentre(glm::vec2 lightUv) const;
  /// Bilinear, clamped to the edge.
  const vk::raii::Sampler& sampler() const { return sampler_; }
  /// Scale from frame uv to overlay() uv: the copy covers 4·its size pixels, a little more than
  /// the frame.
  glm::vec2 overlayUvScale() const;
  /// The blur weights w[0…R] (glowKernel()).
  const std::vector<float>& glowWeights() const { return kernel_; }

  /// Read-backs for tests and tools; each waits for the GPU. Between frames.
  [[nodiscard]] Result<HdrImage> readDownsampled() const;
  [[nodiscard]] Result<HdrImage> readGlow() const;
  [[nodiscard]] Result<HdrImage> readTiny() const;
  [[nodiscard]] Result<HdrImage> readGodRayBright() const;
  [[nodiscard]] Result<HdrImage> readGodRayPolar() const;
  [[nodiscard]] Result<HdrImage> readGodRayPolarBlurred() const;
  [[nodiscard]] Result<HdrImage> readGodRays() const;
  PostExposure readExposure() const;
  /// Forgets the adaptation: the next auto gain snaps to its frame. Between frames.
  void resetExposure();

private:
  /// One invocation per texel of `size`, in workgroups of `workgroup` invocations (8 × 8: the
  /// local size of the 2D post shaders).
  void dispatch(const vk::raii::CommandBuffer& commands, const Pipeline& pipeline, const vk::raii::DescriptorSet& set,
                vk::Extent2D size, vk::Extent2D workgroup = {8, 8}) const;
  void initialiseImages();

  const Device* device_;
  const Image* frame_;
  vk::Extent2D frameSize_;
  std::vector<float> kernel_;
  // Every image stays in GENERAL layout: written as storage images, sampled by the output pass.
  Image downsampled_;   ///< the frame, 4× smaller
  Image across_;        ///< a blur along x
  Image glow_;          ///< a blur along y: after the fourth, the glow
  Image tiny_;          ///< at most 64×64
  Image rayBright_;     ///< god rays: the bright texels of the copy
  Image polar_;         ///< their polar image, godRayPolarSize(copy)
  Image polarBlurred_;  ///< blurred along the radius
  Image godRays_;       ///< back on the copy's grid
  Image overlay_;       ///< what the output pass applies, RGBA32F
  bool godRaysRecorded_ = false;
  OverlayUse overlayUse_ = OverlayUse::kNone;
  Buffer exposure_;  ///< PostExposure, host-visible so tests can read it
  vk::raii::Sampler sampler_{nullptr};

  vk::raii::DescriptorSetLayout sampledLayout_{nullptr};  ///< sampled source, storage destination
  vk::raii::DescriptorSetLayout storageLayout_{nullptr};  ///< storage source, storage destination
  vk::raii::DescriptorSetLayout adaptLayout_{nullptr};    ///< storage tiny image, storage buffer
  vk::raii::DescriptorSetLayout overlayLayout_{nullptr};  ///< glow, god rays, storage buffer, overlay
  Pipeline downsamplePipeline_;
  Pipeline blurPipelines_[2];  ///< along x, along y
  Pipeline tinyPipeline_;
  Pipeline adaptPipeline_;
  Pipeline rayBrightPipeline_;
  Pipeline rayPolarPipeline_;
  Pipeline rayBlurPipeline_;
  Pipeline rayUnpolarPipeline_;
  /// [auto gain][glow][god rays], each made the first time a frame asks for it
  std::array<Pipeline, 8> overlayPipelines_;
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet downsampleSet_{nullptr};
  vk::raii::DescriptorSet acrossSets_[2]{vk::raii::DescriptorSet(nullptr), vk::raii::DescriptorSet(nullptr)};
  vk::raii::DescriptorSet downSet_{nullptr};  ///< across → glow
  vk::raii::DescriptorSet tinySet_{nullptr};
  vk::raii::DescriptorSet adaptSet_{nullptr};
  vk::raii::DescriptorSet rayBrightSet_{nullptr};
  vk::raii::DescriptorSet rayPolarSet_{nullptr};
  vk::raii::DescriptorSet rayBlurSet_{nullptr};
  vk::raii::DescriptorSet overlaySet_{nullptr};
  vk::raii::DescriptorSet rayUnpolarSets_[2]{vk::raii::DescriptorSet(nullptr),
                                             vk::raii::DescriptorSet(nullptr)};  ///< from polar_, from polarBlurred_
};

}  // namespace mane::render
