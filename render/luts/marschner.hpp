#pragma once
// Hair scattering after Marschner et al. 2003 (R, TT and TRT lobes of a rough dielectric
// cylinder with an absorbing interior), in an energy-bounded form after d'Eon et al. 2011 and
// pbrt-v3, factored into two 2D functions that lookup textures store, as in NVIDIA's Nalu demo.
// This file is the CPU reference (double precision); render/luts/marschner_lut.hpp bakes the same
// functions on the GPU (shaders/marschner_lut.comp) and shaders/hair_shading.glsl reads them.
//
// Sources
//   [M03]  Marschner, Jensen, Cammarano, Worley, Hanrahan, "Light Scattering from Human Hair
//          Fibers", SIGGRAPH 2003: eq. 1 (the scattering integral), Table 1 (parameters).
//   [dE11] d'Eon, Francois, Hill, Letteri, Aubry, "An Energy-Conserving Hair Reflectance
//          Model", EGSR 2011: eq. 5 (white furnace), eq. 7 (M_p), eqs. 10-11 (N_p as an
//          integral over the fibre width with a wrapped Gaussian detector), §4.1 and Fig. 3 (why
//          [M03]'s M_p is not energy-conserving), §6.1 (melanin absorption cross sections).
//   [P16]  Pharr, "The Implementation of a Hair Scattering Model" (pbrt-v3, 2016; its
//          src/materials/hair.cpp): attenuation A_p at the outgoing direction, with the exact 3D
//          Fresnel angle and the chord 2cosγt/cosθt; white-furnace tests (src/tests/hair.cpp).
//   [N05]  Nguyen & Donnelly, "Hair Animation and Rendering in the Nalu Demo", GPU Gems 2,
//          ch. 23 (2005): M and N lookup textures, mip-mapped.
//
// Geometry. t is the unit fibre tangent (root → tip), ωi points to the light, ωr to the eye.
//   θi = asin(ωi·t), θr = asin(ωr·t)  longitudinal angles from the normal plane, [−π/2, π/2]
//   φ  = angle between the projections of ωi and ωr on the normal plane, [0, π];
//        φ = 0 scatters back towards the light, φ = π straight through the fibre
//   θh = (θi + θr)/2, θd = (θr − θi)/2                                              [M03]
//
// The factored model, p = 0, 1, 2 for R, TT, TRT:
//   S(ωi, ωr) = Σ_p M_p(θi, θr) · N_p(θr, φ)                                          (1)
// S is normalised as in [dE11]: the radiance towards ωr per unit irradiance arriving from ωi,
// measured perpendicular to ωi, so L_r = ∫ S L_i dωi and a directional light of perpendicular
// irradiance E adds S·E with no cosine factor. It equals [M03] eq. 1's S times cos θi; [M03]'s
// 1/cos²θd is gone.
//
//   M_p(θi, θr) = κ/(2 sinh κ) · exp(−κ sinθi sinθ') · I0(κ cosθi |cosθ'|),           (2)
//                 κ = 1/β_p², θ' = θr − 2α_p                                   [dE11 eq. 7]
// is a von Mises-Fisher lobe around the specular cone integrated over azimuth, normalised for
// every θ': ∫ M_p cosθi dθi = 1 over [−π/2, π/2]. For small β it tends to [M03]'s Gaussian
// g(β_p; θh − α_p); the shift 2α_p on θr puts the peak at θh = α_p as in [M03].
//
//   N_p(θr, φ) = ½ ∫_{−1}^{1} A_p(h) D(φ − Φ_p(h)) dh                      [dE11 eqs. 10-11]  (3)
//   Φ_p(h) = 2p γt − 2γi + pπ,  γi = asin h,  sin γt = h/η'(θr)                      [M03]
//   A_R = f,  A_TT = (1 − f)² T,  A_TRT = (1 − f)² f T²
//   f = F(η, cos ψ), cos ψ = cosθr cosγi: exact unpolarised Fresnel at the 3D angle    [P16]
//   T = exp(−σa · 2cosγt / cosθt), sinθt = sinθr/η: the chord through the fibre        [P16]
//   D = normal density of standard deviation β_N wrapped onto the circle (k = −1, 0, 1)
// with η'(θ) = sqrt(η² − sin²θ)/cosθ Bravais' index for the refraction projected on the normal
// plane [M03]. The h integral uses kAzimuthalNodes midpoint nodes in γi ∈ [0, π/2] (h = sin γi,
// dh = cosγi dγi; the ±h pair is folded since A is even and Φ_p(−h) ≡ −Φ_p(h) mod 2π). That rule is
// part of the model: the GPU bake uses the same nodes.
//
// Energy. Because ∫ M_p cosθi dθi = 1 for any θr, ∫ D dφ = 1, and A depends on the eye's θr only,
// the white-furnace albedo (directional albedo for the eye at θr, [dE11 eq. 5]) is exactly
//   ∫ S dωi = Σ_p ½∫ A_p dh,  and  A_R + A_TT + A_TRT = f + (1 − f)(1 − f²) ≤ 1  at σa = 0,
// so it never exceeds 1 (it falls short by what TRRT and higher orders would carry, left out as
// in [M03]), and it decreases as σa grows. Choices that break this, and why they were not taken:
//  - [M03]'s Gaussian M_p(θh) with 1/cos²θd: albedos near 2 for smooth fibres, above 1 at
//    grazing angles [dE11 §4.1, Fig. 3]; replaced by (2).
//  - A_p evaluated at θd, i.e. Nalu's N(θd, φ): with [M03]'s lobe shifts each lobe samples A at
//    θd ≈ θr − α_p, R at larger angles where Fresnel is higher; the furnace then reaches 1.07
//    near θr = 70° with the default groom. Evaluating A at θr, the direction held fixed in the
//    furnace, is pbrt's formulation [P16]; it costs reciprocity, which a rasteriser never uses.
//  - [M03]'s parallel-polarisation index η''(θ) = η² cosθ / sqrt(η² − sin²θ) in the Fresnel
//    term: it reproduces the exact reflectance only at γi = 0 (η' is exact for the perpendicular
//    part at every γi), so f uses the 3D angle as [dE11] and [P16] do.
//  - [M03]'s printed transmittance exp(−2σa(1 + cos 2γt)) is not the chord length; T uses the
//    geometric chord 2cosγt/cosθt of [P16].
//
// Left out: eccentricity (elliptical cross sections) and [M03]'s caustic fudge (w_c, k_G, Δη'):
// fibres are circular and the Gaussian detector spreads TRT's caustics instead [dE11].
//
// Units: radians; σa in 1/(fibre radius): a chord through the centre attenuates by exp(−2σa).

#include <cstdint>

#include <glm/glm.hpp>

#include "common/error.hpp"

namespace mane::render {

/// The three scattering paths of [M03]: p = number of internal segments.
enum class HairLobe : std::uint8_t {
  kR = 0,    ///< reflection at the surface (white)
  kTT = 1,   ///< transmission through the fibre (coloured, forward)
  kTRT = 2,  ///< one internal reflection (coloured, shifted highlight)
};

/// Shape of one lobe's longitudinal distribution.
struct HairLobeShape {
  /// α_p, radians: the lobe peaks at θh = α_p ([M03] Table 1; negative = towards the root).
  float shift = 0.0f;
  /// β_p, radians: the lobe's standard deviation in θi for a fixed θr, κ = 1/β_p² in eq. (2)
  /// (v = β² of [dE11] eq. 7). [M03]'s Gaussian in θh with the same β is twice as wide in θi
  /// (and integrates to 2, [dE11 §4.1]); its Table 1 values are used here as they stand.
  /// The GPU tables need β ≥ 0.5° (half floats hold M ≤ 1/β²).
  float width = 0.1f;
};

/// Optical parameters of one groom: plain data, shared by the CPU model and the GPU bake.
struct HairShadingParams {
  /// σa per RGB channel in 1/(fibre radius); see absorptionFromMelanin(). The default is the
  /// blonde preset's.
  glm::vec3 absorption{0.1444f, 0.2491f, 0.516f};
  /// Index of refraction of the cortex: 1.55 for keratin ([M03] Table 1).
  float refractiveIndex = 1.55f;
  /// [M03] Table 1 ranges: α_R −10°..−5°, α_TT = −α_R/2, α_TRT = −3α_R/2;
  /// β_R 5°..10°, β_TT = β_R/2, β_TRT = 2β_R. These are the middles of those ranges.
  HairLobeShape r{-0.1309f, 0.1309f};    // α −7.5°, β 7.5°
  HairLobeShape tt{0.06545f, 0.06545f};  // α 3.75°, β 3.75°
  HairLobeShape trt{0.19635f, 0.2618f};  // α 11.25°, β 15°
  /// β_N: standard deviation of the azimuthal Gaussian detector, radians. Stands in for
  /// [M03]'s caustic width w_c (10°..25°) and surface roughness across the fibre.
  float azimuthalWidth = 0.1745f;  // 10°

  /// The shape of lobe `p`.
  const HairLobeShape& lobe(HairLobe p) const { return p == HairLobe::kR ? r : (p == HairLobe::kTT ? tt : trt); }
};

/// σa from melanin concentrations with [dE11 §6.1]'s RGB cross sections, as [P16] applies them:
/// eumelanin (0.419, 0.697, 1.37), pheomelanin (0.187, 0.4, 1.05) per unit concentration.
/// Roughly: 0 white, 0.3 blonde, 1.3 brown, 8 black (eumelanin).
glm::vec3 absorptionFromMelanin(float eumelanin, float pheomelanin);

/// Dark hair: eumelanin 8. The fibre interior absorbs nearly all light that enters, so the
/// white surface reflection R dominates.
HairShadingParams darkHairParams();

/// Blonde hair: eumelanin 0.3, pheomelanin 0.1. Light crosses the fibre, so the coloured
/// TT (forward) and TRT (secondary highlight) lobes show.
HairShadingParams blondeHairParams();

/// An error naming the first parameter that is out of range (non-finite, σa < 0, η ≤ 1 or
/// > 3, a width outside (0, π/2], a shift outside [−π/4, π/4]).
Result<void> validate(const HairShadingParams& params);

/// M_p of the three lobes (colourless), 1/radian.
struct LongitudinalLobes {
  double r = 0.0, tt = 0.0, trt = 0.0;
};

/// N_p of the three lobes, 1/radian: R is colourless, TT and TRT per RGB.
struct AzimuthalLobes {
  double r = 0.0;
  glm::dvec3 tt{0.0}, trt{0.0};
};

/// Midpoint nodes of the h integral of N_p (γi ∈ [0, π/2]); the GPU bake uses the same.
inline constexpr std::uint32_t kAzimuthalNodes = 64;

/// Unpolarised Fresnel reflectance of a dielectric of relative index `eta` (> 0) for light
/// arriving at angle acos(cosIncidence) from the normal; 1 beyond total internal reflection.
double fresnelDielectric(double eta, double cosIncidence);

/// Bravais' perpendicular index η'(θ) = sqrt(η² − sin²θ)/cosθ: Snell's law for the directions
/// projected on the normal plane of a fibre hit at longitudinal angle θ [M03]. Infinite at θ = ±π/2.
double bravaisPerpendicularIndex(double eta, double theta);

/// Bravais' parallel index η''(θ) = η² cosθ / sqrt(η² − sin²θ) [M03], which [M03] uses for the
/// parallel-polarised Fresnel term. Exact at γi = 0 only, so the model uses the 3D Fresnel
/// (see the file comment); kept for comparisons.
double bravaisParallelIndex(double eta, double theta);

/// Equation (2): M_p(θi, θr) for all three lobes.
LongitudinalLobes longitudinalScattering(const HairShadingParams& params, double thetaI, double thetaR);

/// Equation (2) for one lobe of variance v = β² (radians²) with the shifted θ' = θr − 2α given.
double longitudinalLobe(double variance, double thetaI, double shiftedThetaR);

/// Equation (3): N_p(θr, φ) for all three lobes, from cos θr ∈ [0, 1] and cos φ ∈ [−1, 1].
AzimuthalLobes azimuthalScattering(const HairShadingParams& params, double cosThetaR, double cosPhi);

/// ∫ N_p(θr, φ) dφ over the circle = ½ ∫ A_p(h) dh: the fraction of the light falling on the
/// fibre's width that leaves along lobe p, by the same h nodes as azimuthalScattering; also the
/// lobe's share of the white-furnace albedo.
AzimuthalLobes azimuthalAlbedo(const HairShadingParams& params, double cosThetaR);

/// Angles of a pair of directions around a fibre (see the file comment).
struct HairAngles {
  double thetaI = 0.0, thetaR = 0.0;  ///< radians
  double cosThetaR = 1.0;             ///< cos θr
  double cosPhi = 1.0;                ///< 1 when either direction is along the tangent
};

/// The angles of `toLight` and `toEye` (unit vectors) around the unit `tangent`.
HairAngles hairAngles(glm::dvec3 toLight, glm::dvec3 toEye, glm::dvec3 tangent);

/// Equation (1): S per RGB, 1/steradian; a light of perpendicular irradiance E adds S·E.
glm::dvec3 hairScattering(const HairShadingParams& params, glm::dvec3 toLight, glm::dvec3 toEye, glm::dvec3 tangent);

}  // namespace mane::render
