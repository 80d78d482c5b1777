#pragma once
// The HDR post chain (render/passes/post_pass.hpp) as numbers, on the CPU: the sizes of its
// images, the glow's blur kernel, and reference implementations of every step the GPU does, for
// tests and tools. The shaders (shaders/post_*.comp, shaders/output.frag) follow this file.
//
//   [RSSF02] Reinhard, Stark, Shirley & Ferwerda, "Photographic Tone Reproduction for Digital
//            Images", SIGGRAPH 2002.
//   [Tim04]  NVIDIA's "Timbury" demo (Ryan Geiss 2004, docs/design.md#sources): the frame drawn
//            to fp16, downsampled, blurred x, y, x, y and mixed with the sharp image; automatic
//            gain from a tiny copy.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace mane::render {

/// The glow and the auto gain work on a copy of the frame this many times smaller per side.
inline constexpr std::uint32_t kPostDownsampleFactor = 4;
/// The auto gain's tiny image has at most this many texels per side.
inline constexpr std::uint32_t kPostTinyMaxSize = 64;
/// The glow blur reaches at most this many texels each side (kGlowRadius in shaders/post_blur.comp).
inline constexpr int kGlowMaxRadius = 8;
/// σ of each of the four glow blurs, in downsampled texels. Two blurs per axis compose to
/// σ·√2 ≈ 3.5 texels ≈ 14 pixels of the full frame.
inline constexpr float kGlowSigma = 2.5f;
/// δ of the log-average, log(δ + L) ([RSSF02] eq. 1): keeps black pixels finite.
inline constexpr double kLogLuminanceDelta = 1e-4;

/// Linear RGBA texels, row after row.
struct HdrImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec4> texels;

  const glm::vec4& at(std::uint32_t x, std::uint32_t y) const { return texels[std::size_t(y) * width + x]; }
};

/// Luminance of linear sRGB/Rec. 709 primaries (ITU-R BT.709 weights).
double luminance(glm::dvec3 rgb);

/// Texels per side of the downsampled copy: ⌈size / kPostDownsampleFactor⌉.
glm::uvec2 postQuarterSize(glm::uvec2 frame);
/// k: each tiny texel averages a k×k block of the downsampled copy, k = ⌈longest side / 64⌉.
std::uint32_t postTinyBlock(glm::uvec2 quarter);
/// Texels per side of the tiny image: ⌈quarter / k⌉ (≤ kPostTinyMaxSize).
glm::uvec2 postTinySize(glm::uvec2 quarter);

/// The glow's 1D Gaussian, w[k] for the offsets ±k, k = 0…R with R = ⌈3σ⌉ (at most
/// kGlowMaxRadius), normalised so w[0] + 2·Σ_{k≥1} w[k] = 1: the blur keeps the image's energy.
std::vector<float> glowKernel(float sigma = kGlowSigma);

/// The downsampled copy: each texel the mean of a 4×4 block, rows and columns past the edge
/// repeating the last ones (the GPU reads 4 bilinear taps, clamped to the edge). A box over the
/// whole footprint counts every pixel exactly once, so no small highlight is lost before the glow.
HdrImage downsampleForPost(const HdrImage& frame);
/// One blur along x (axis 0) or y (axis 1) with `kernel` (glowKernel), clamped to the edge.
HdrImage blurAlong(const HdrImage& image, std::span<const float> kernel, int axis);
/// The glow: downsampleForPost, then blurs along x, y, x, y.
HdrImage glowReference(const HdrImage& frame, std::span<const float> kernel);
/// The auto gain's tiny image: each texel the mean of its k×k block (postTinyBlock) of the
/// downsampled copy, over the texels inside it.
HdrImage tinyForAutoGain(const HdrImage& quarter);
/// L̄ = exp(mean(log(δ + L))) over the texels ([RSSF02] eq. 1).
double logAverageLuminance(const HdrImage& image);

/// The share of the way to its target the adapted luminance moves in a frame of `frameSeconds`
/// with time constant `adaptationSeconds`: 1 − exp(−Δt/τ) (1 when τ = 0): exponential decay,
/// independent of how the time is cut into frames.
double adaptationRate(double frameSeconds, double adaptationSeconds);
/// The next adapted log-luminance: log L̄_a + rate·(log L̄ − log L̄_a).
double adaptLogLuminance(double adaptedLog, double frameLog, double rate);

/// Reinhard's operator on a colour ([RSSF02] eq. 2–3): L = luminance(gain·rgb) and
/// L_d = L/(1 + L); the colour keeps its chromaticity, scaled by L_d/L: gain·rgb/(1 + L).
glm::dvec3 reinhard(glm::dvec3 rgb, double gain);

// God rays, on the downsampled copy: the bright texels (the rest occludes), a
// polar image around the light, a blur along each ray away from the light, back to the copy's grid.
// Positions on the copy are continuous texel coordinates, texel (x, y) covering [x, x+1]×[y, y+1];
// the polar image's texel (i, j) is the angle θ = 2π(i + ½)/A at the radius r = j copy texels.

/// Taps of the radial blur (kTaps in shaders/post_ray_blur.comp).
inline constexpr int kGodRayTaps = 32;
/// Polar texels between the blur's taps: the shafts reach kGodRayTaps · kGodRayStep = 64 copy
/// texels (256 pixels) from each bright texel, fading by the decay per tap.
inline constexpr int kGodRayStep = 2;

/// The polar image of a copy `quarter` texels large: R = ⌈|quarter|⌉ + 1 radii, one per copy texel,
/// enough for a light anywhere on screen; A = ⌈πR⌉ rounded up to a multiple of 8 angles, so
/// neighbouring rays are at most 2 texels apart at the far corner (1 at half the distance).
glm::uvec2 godRayPolarSize(glm::uvec2 quarter);
/// The part of it a light at `centre` (copy texel coordinates, on the copy) uses: as
/// godRayPolarSize with R = ⌈the distance to the farthest corner⌉ + 1 (at most that size). A
/// light at the centre uses about a quarter of the texels, one in a corner all of them.
glm::uvec2 godRayPolarExtent(glm::uvec2 quarter, glm::vec2 centre);
/// rgb · max(L − threshold, 0)/L: texels brighter than the threshold keep their excess, the rest
/// (occluders, dark sky) are 0.
HdrImage godRayBright(const HdrImage& quarter, float threshold);
/// The polar image around `centre` (copy texel coordinates): bilinear samples of `image` at
/// centre + r(cos θ, sin θ), clamped to the edge.
HdrImage toPolar(const HdrImage& image, glm::vec2 centre, glm::uvec2 polarSize);
/// Back to an image `size` texels large: each texel centre's angle and radius around `centre`,
/// sampled bilinearly from `polar`, wrapping in angle and clamped in radius.
HdrImage fromPolar(const HdrImage& polar, glm::vec2 centre, glm::uvec2 size);
/// w[k] ∝ decay^k · (1 − (k/kGodRayTaps)²), k < kGodRayTaps, normalised to sum 1.
std::vector<float> godRayWeights(float decay);
/// Along each ray (a column of the polar image): out(j) = Σ_{k: j − k·kGodRayStep ≥ 0} w[k] ·
/// in(j − k·kGodRayStep): light moves only outwards, away from the light, fading with the decay;
/// none comes from before the light, so a ray keeps the light it had (short of the image's end).
HdrImage radialBlur(const HdrImage& polar, std::span<const float> weights);
/// The whole: godRayBright, toPolar (of godRayPolarExtent), radialBlur, fromPolar, on the
/// downsampled copy.
HdrImage godRaysReference(const HdrImage& quarter, glm::vec2 centre, float threshold, float decay);

}  // namespace mane::render
