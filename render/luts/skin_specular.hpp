#pragma once
// Specular reflection of skin's oily surface layer: the Kelemen/Szirmay-Kalos BRDF with a
// Beckmann distribution and Schlick's Fresnel, as d'Eon & Luebke use it for skin.
//
// Sources
//   [KS01]  Kelemen & Szirmay-Kalos, "A Microfacet Based Coupled Specular-Matte BRDF Model with
//           Importance Sampling", Eurographics 2001 short paper: the geometry term of a microfacet
//           BRDF replaced by 1/((L+V)·(L+V)), i.e. f = P_H(H)·F / |L + V|².
//   [dEL07] d'Eon & Luebke, GPU Gems 3 ch. 14 (2007), §14.3: Kelemen/Szirmay-Kalos for skin,
//           F0 = 0.028 (Example 14-2), the Beckmann term precomputed into a texture as
//           0.5·P_H^0.1 and decoded with pow(2x, 10) (Example 14-1).
//   [Sch94] Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", 1994:
//           F(c) = F0 + (1 − F0)(1 − c)⁵.
//   [Bec63] Beckmann & Spizzichino, 1963: the distribution of microfacet slopes.
//
// Beckmann here is normalised as a distribution of microfacet normals projected on the surface,
// ∫ D(m) cos θm dω = 1 over the hemisphere:
//   D(θm, α) = exp(−tan²θm / α²) / (π α² cos⁴θm)
// [dEL07]'s PHBeckmann leaves out the 1/π, so its ρs (0.18 in their example) corresponds to
// π times as much here.
//
// Units: roughness α (Beckmann's m, the RMS microfacet slope) without unit; D in 1/sr.

#include <glm/glm.hpp>

namespace mane::render {

/// Normal-incidence reflectance of skin's surface layer ([dEL07] Example 14-2; an index of ≈1.4).
inline constexpr double kSkinSpecularF0 = 0.028;

/// Beckmann's normalised D(θm, α) from cos θm = N·H ∈ [0, 1] and α > 0; 0 for N·H ≤ 0.
double beckmannDistribution(double nDotH, double roughness);

/// Schlick's F(c) = F0 + (1 − F0)(1 − c)⁵ for c = cos of the angle between the light (or eye)
/// and the microfacet normal H, clamped to [0, 1].
double schlickFresnel(double cosTheta, double f0 = kSkinSpecularF0);

/// [KS01] as [dEL07] shades it: f = ρs · D(N·H) · F(H·V) / |L + V|² with H = normalize(L + V),
/// in 1/sr (multiply by N·L and the light's irradiance for radiance). Unit vectors in; 0 when the
/// light or the eye is below the surface.
double kelemenSzirmayKalos(glm::dvec3 normal, glm::dvec3 toLight, glm::dvec3 toEye, double roughness, double rhoS,
                           double f0 = kSkinSpecularF0);

/// The share of light from every direction that [KS01] reflects towards an eye at cos θ = `nDotV`
/// (0..1) with ρs = 1: ∫ f·max(N·L, 0) dL over the hemisphere, by the midpoint rule on a 512 × 256
/// grid in (θ, φ). Under an environment of pre-filtered radiance L̃ in the reflected direction,
/// skin's specular radiance is ρs × this × L̃ (Karis's split sum).
double kelemenSzirmayKalosAlbedo(double nDotV, double roughness, double f0 = kSkinSpecularF0);

/// The alpha channel of the pre-integrated skin table stores the Beckmann term as 0.5·D^0.1
/// ([dEL07] Example 14-1), decoded with pow(2x, 10). Why, in a half-float table:
///  - range: the tenth root maps D from tails of 1e-30 up to 1024 (α ≥ 0.018 at N·H = 1) into
///    [0, 1], and any larger D still fits; storing D itself would flush the tails to zero;
///  - uniform relative precision: the decoded D is within 10× the half float's relative step,
///    ≤ 1 % where a write rounds toward zero (Vulkan allows it; lavapipe does), 0.5 % rounding to
///    nearest — ample for a highlight's intensity;
///  - filtering: a bilinear lookup interpolates the near-exponential lobe much better in the
///    compressed form (256 texels, α = 0.2 … 0.5: 1.2e-4 of the peak against 3.5e-3 for D).
double encodeBeckmann(double d);
/// The inverse of encodeBeckmann: pow(2x, 10).
double decodeBeckmann(double encoded);

}  // namespace mane::render
