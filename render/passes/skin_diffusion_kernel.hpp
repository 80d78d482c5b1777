#pragma once
// The blurs of texture-space diffusion (render/passes/skin_diffusion_pass.hpp), as numbers: which six
// Gaussians run in which order, and which taps one texel's blur along one axis reads. The GPU
// (shaders/skin_diffusion_blur.comp) and the CPU reference (skin_diffusion_reference.hpp) both
// follow this file.
//
// Six blurs in a cascade, after [dEL07] §14.4.2/§14.5.1: Gaussians compose by adding variances,
// G(v1) * G(v2) = G(v1 + v2), so blur i starts from blur i−1's result and adds only the
// difference v_i − v_{i−1}. The wide Gaussians then need no more taps than the narrow ones.
//   [dEL07] d'Eon & Luebke, "Advanced Techniques for Realistic Real-Time Skin Rendering",
//           GPU Gems 3, ch. 14 (2007).
//
// Taps, per texel and axis, with σ in texels = σ_mm / stretch (mm per texel) and H half taps:
//  - 2H + 1 taps at whole-texel offsets x_k = round(k·Δ), k = −H…H, spacing Δ = max(1, 3σ/H):
//    they span ±3σ, or ±H texels when that is wider (narrow Gaussians keep their tails). Whole
//    texels, not interpolated ones: interpolating between texels adds a tent filter, and 13
//    interpolated taps at spacing σ/2 (GPU Gems' way, with more taps) strayed up to 12 % from R(r)
//    at 0.06–0.09 mm per texel, where the second Gaussian's input is barely two texels wide.
//  - weights G(x_k)·(x_{k+1} − x_{k−1})/2, the trapezoid rule on the rounded nodes, normalised
//    to sum 1 per texel: every blur keeps the energy it is given.
//  - H = 12 for the first blur (the raw irradiance has detail at one texel) and for any blur
//    whose sparse spacing 3σ_i/6 would exceed the previous Gaussian's σ (its input would alias:
//    the ripple of Gaussians of width σ summed at spacing d is 2·exp(−2π²σ²/d²)); H = 6 for the
//    rest. For d'Eon's variances: 12, 12, 6, 6, 6, 6 (25 taps for the first two, 13 after).
// The trip counts are fixed per pipeline (a specialization constant): lavapipe runs this blur
// several times slower with loops and branches that depend on the texel around the image reads
// (docs/lavapipe.md#loops-test-at-the-end), and reads through imageLoad faster than through
// texelFetch.
// Measured on a 1D prototype of the cascade (point impulse, 0.04–0.12 mm per texel): the
// response matches R(r) within 2.2 % wherever R is ≥ 1 % of its peak, its sums over disks
// within 0.25 %; at 0.0625 mm per texel within 0.1 %.
//
// Limits: a blur reads whole texels, so a Gaussian narrower than ~0.7 texel is under-resolved
// (at 1024² a 25 cm face has 0.25 mm per texel: d'Eon's first two Gaussians, σ = 0.08 and
// 0.22 mm, act almost as the identity there, as they should). A first Gaussian wider than 4
// texels (maps finer than 0.02 mm per texel) is sampled sparsely from the raw irradiance and
// aliases its sharpest features.

#include <array>
#include <span>

#include <glm/glm.hpp>

#include "render/luts/skin_profile.hpp"

namespace mane::render {

/// One of the six blurs: it takes the previous blur's result (the irradiance, for the first) to
/// the profile's Gaussian of variance `variance`.
struct SkinDiffusionStage {
  double variance = 0.0;   ///< v_i of the Gaussian this blur completes, mm²
  double sigma = 0.0;      ///< sqrt(v_i − v_{i−1}): the standard deviation of this blur alone, mm
  glm::dvec3 weight{0.0};  ///< the profile's RGB weight of that Gaussian
  int halfTaps = 6;        ///< H: kSkinBlurDenseHalfTaps or kSkinBlurSparseHalfTaps
};

inline constexpr int kSkinBlurDenseHalfTaps = 12;  ///< 25 taps
inline constexpr int kSkinBlurSparseHalfTaps = 6;  ///< 13 taps
inline constexpr double kSkinBlurReach = 3.0;      ///< taps span ±3σ (or ±H texels, if wider)
inline constexpr double kSkinBlurMinSigma = 1e-3;  ///< texels; narrower blurs copy

/// The profile's Gaussians sorted by variance (ties keep their order), as cascade stages.
std::array<SkinDiffusionStage, kSkinGaussianCount> skinDiffusionStages(const SkinProfile& profile);

/// The whole-texel offset of tap k ≥ 0 of a blur of `sigmaTexels` with `halfTaps` (see above).
double skinBlurTapOffset(double sigmaTexels, int halfTaps, int k);

/// Blurred coverage below this leaves a texel of the diffused map black: no covered texel lies
/// within the kernels' reach, and the quotient (see skin_diffusion_pass.hpp, "Seams") would be noise.
inline constexpr double kSkinMinCoverage = 1e-3;

/// The stretch (mm per texel) that texels outside the UV islands blur with, for maps given as
/// texels: the mean of the positive stretch values, or 1 mm when there are none. Outside the
/// islands the blurs only dilate the islands' values, so any plausible width will do.
double skinUncoveredStretch(std::span<const glm::vec2> stretch);

}  // namespace mane::render
