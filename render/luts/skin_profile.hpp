#pragma once
// The diffusion profile of skin as a sum of six Gaussians: the radial reflectance R(r) of a
// point of light entering flat skin, per RGB channel, after
//   [dEL07] d'Eon & Luebke, "Advanced Techniques for Realistic Real-Time Skin Rendering",
//           GPU Gems 3, ch. 14 (2007), §14.4.2, Table 14-1 (the three-layer skin fit).
//
//   G(v, r) = exp(−r²/(2v)) / (2πv)          a 2D Gaussian of variance v, ∫ G dA = 1
//   R(r)    = Σ_i w_i G(v_i, r)               per RGB, Σ_i w_i = 1 per channel, so ∫ R dA = 1
//
// Units: r in millimetres and v in mm², as [dEL07] gives them; R in 1/mm². A scene measured in
// other units converts through SkinProfile::millimetresPerUnit (1000 for metres). The same profile
// drives the pre-integrated lookup table (render/luts/preintegrated_skin.hpp) and texture-space
// diffusion (six separable blurs of these variances and weights).

#include <array>
#include <cstddef>

#include <glm/glm.hpp>

#include "common/error.hpp"

namespace mane::render {

/// One term of the sum: a normalised 2D Gaussian and its weight per RGB channel.
struct SkinGaussian {
  double variance = 1.0;  ///< v, mm²
  glm::dvec3 weight{0.0};
};

inline constexpr std::size_t kSkinGaussianCount = 6;

/// [dEL07] Table 14-1: variances 0.0064 … 7.41 mm², weights per RGB.
inline constexpr std::array<SkinGaussian, kSkinGaussianCount> kDEonSkinGaussians{{
    {0.0064, {0.233, 0.455, 0.649}},
    {0.0484, {0.100, 0.336, 0.344}},
    {0.187, {0.118, 0.198, 0.0}},
    {0.567, {0.113, 0.007, 0.007}},
    {1.99, {0.358, 0.004, 0.0}},
    {7.41, {0.078, 0.0, 0.0}},
}};

/// The normalised 2D Gaussian G(v, r) = exp(−r²/(2v)) / (2πv): v in mm², r in mm, result in 1/mm².
double skinGaussian(double variance, double radius);

struct SkinProfile {
  std::array<SkinGaussian, kSkinGaussianCount> gaussians = kDEonSkinGaussians;
  /// Millimetres per world unit: 1000 for a scene in metres, 10 for centimetres.
  double millimetresPerUnit = 1000.0;

  /// R(r) per RGB, 1/mm², at distance `radius` in mm from where the light entered.
  glm::dvec3 reflectance(double radius) const;
  /// R at a distance given in world units, as a density per world unit²: R(d·s)·s² with
  /// s = millimetresPerUnit, so it integrates to 1 over the plane in world units too.
  glm::dvec3 reflectanceAtWorldDistance(double distance) const;
  /// Per RGB, of light that crossed `thickness` mm of skin, the fraction that leaves: R summed
  /// over a plane of entry points at that depth, ∫ R(√(d² + ρ²)) dA = Σ_i w_i·exp(−d²/(2v_i))
  /// (each G integrates to 1 over a plane; its exp(−d²/2v) factor is constant across it), so
  /// T(0) = 1. The translucency of thin skin, after Jimenez et al., "Real-Time Realistic Skin
  /// Translucency" (IEEE CG&A 2010), whose sum exp(−d²/v_i) leaves out the 2 of d'Eon's G.
  glm::dvec3 transmittance(double thickness) const;
  /// A length in world units, in mm.
  double millimetres(double worldLength) const { return worldLength * millimetresPerUnit; }
  /// Per RGB, the share of the channel's weight in Gaussians of variance ≥ `minVariance` (mm²):
  /// how much of its light has spread wider than that scale before it exits. The skin pass
  /// blends each channel's normal towards the geometric one by this share (blurred normals).
  glm::dvec3 broadShare(double minVariance) const;
};

/// An error naming the first bad field: a variance that is not finite and positive, a weight
/// that is negative or not finite, a channel whose weights do not sum to 1 within 1e-3, or a
/// scale that is not finite and positive.
Result<void> validate(const SkinProfile& profile);

}  // namespace mane::render
