#pragma once
// Pre-integrated skin: the skin profile (render/luts/skin_profile.hpp) integrated around a ring of
// radius r lit by a directional light, so that a shader gets subsurface scattering on curved skin
// from one lookup by (N·L, 1/r). This is the CPU reference (double precision); the table it
// defines is baked on the GPU by render/luts/preintegrated_skin_lut.hpp
// (shaders/preintegrated_skin.comp) and read by shaders/preintegrated_skin.glsl.
//
// Sources
//   [Pen11] Penner & Borshukov, "Pre-Integrated Skin Shading", GPU Pro 2 (2011), and Penner's
//           SIGGRAPH 2011 course talk: the ring integral below over x ∈ [−π/2, π/2].
//   [seed]  the source document the project implements for skin (Takamine's master's thesis,
//           Tokyo University of Technology, eq. 3.1; docs/design.md#sources): the same integral
//           over the curvature-dependent range x ∈ [−π(r+1)/(2r), π(r+1)/(2r)].
//   [dEL07] d'Eon & Luebke, GPU Gems 3 ch. 14: the six-Gaussian profile, Kelemen/Szirmay-Kalos
//           specular with the Beckmann term stored in a texture (render/luts/skin_specular.hpp).
//
// The diffuse term, per RGB:
//   D(θ, r) = ∫ max(cos(θ + x), 0) · R(2r·sin(x/2)) dx / ∫ R(2r·sin(x/2)) dx,   x ∈ [−X, X]   (1)
// θ = acos(N·L); 2r·sin(x/2) is the chord from the shaded point to the point at angle x on the
// ring; the max(·, 0) keeps light from arriving from behind a point, as in [Pen11] (the seed
// writes cos). X = π/2 [Pen11] or X = π(r + 1)/(2r) = (π/2)(1 + 1/r) [seed].
//
// Units. r is the radius of curvature in mm, the profile's unit; a mesh in world units gives
// 1/r_mm = (1/r_world) / SkinProfile::millimetresPerUnit. The seed's range adds 1 to r, so it
// depends on that unit: in mm it is ±π at r = 1 mm and tends to Penner's ±π/2 as r grows. For
// r < 1 mm it passes ±π and counts the far side of the ring twice; it is kept as the seed states
// it, and the default table (1/r ≤ 1 mm⁻¹) never reaches there.
//
// Quadrature (shared with the GPU bake, so both compute the same rule). Each Gaussian of (1) is
// integrated separately, over the arc where its chord is within kProfileReach standard deviations
// (|x| ≤ 2 asin(kProfileReach·σ/(2r)), or all of [−X, X] when that reaches past it: the mass left
// out is erfc(6/√2) ≈ 2e-9), split at x = 0 (the kernel's peak) and at the kinks of max(cos, 0),
// each piece by kSkinQuadratureNodes-point Gauss-Legendre. Against a 1e-3 rad midpoint rule this
// agrees to ≈ 2e-6 over the table, the midpoint rule's own error at the kinks. At 1/r = 0 the
// kernel is a delta and D = max(N·L, 0) exactly.

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "common/error.hpp"
#include "render/frame.hpp"
#include "render/luts/gauss_legendre.hpp"
#include "render/luts/skin_profile.hpp"

namespace mane::render {

// Which range equation (1) uses is SkinIntegrationRange of render/frame.hpp, where materials
// name it: kPenner = [−π/2, π/2] [Pen11], kCurvature = ±π(r+1)/(2r) [seed].

/// X of equation (1), radians, for curvature 1/r in 1/mm (≥ 0; at 0 the seed's range is π/2).
double integrationHalfRange(SkinIntegrationRange range, double curvature);

/// Equation (1) per RGB for N·L ∈ [−1, 1] and curvature 1/r ≥ 0 in 1/mm.
glm::dvec3 preintegratedDiffuse(const SkinProfile& profile, SkinIntegrationRange range, double nDotL, double curvature);

/// What the ambient light of an environment does on skin of curvature 1/r (1/mm), per RGB and per
/// spherical-harmonic band ℓ = 0, 1, 2: by the Funk–Hecke theorem, light L(ω) = Σ L_ℓm·Y_ℓm(ω)
/// reaching skin whose response to a direction at cosine μ is D(μ) of equation (1) leaves
/// Σ A_ℓ·L_ℓm·Y_ℓm(n), A_ℓ = 2π ∫ D(μ)·P_ℓ(μ) dμ over [−1, 1]. Returned as A_ℓ over Lambert's
/// (D = max(μ, 0): π, 2π/3, π/4; Ramamoorthi & Hanrahan 2001), the factors by which skin scales
/// each band of a Lambertian surface's irradiance: 1 at 1/r = 0. Each half of [−1, 1] by
/// 32-point Gauss-Legendre.
std::array<glm::dvec3, 3> preintegratedAmbientBands(const SkinProfile& profile, SkinIntegrationRange range,
                                                    double curvature);
/// Gauss-Legendre nodes of each piece of the quadrature (see the file comment).
inline constexpr std::uint32_t kSkinQuadratureNodes = 12;
/// How many standard deviations of each Gaussian the quadrature covers.
inline constexpr double kProfileReach = 6.0;

/// The kSkinQuadratureNodes-point Gauss-Legendre rule on [−1, 1].
const std::array<QuadratureNode, kSkinQuadratureNodes>& skinQuadratureRule();

// ---------------------------------------------------------------------------------------------
// The table. Texel (i, j) of a size × size table sits at parameters s = i/(size − 1),
// t = j/(size − 1): both ends of each range on texel centres, as the Marschner tables do, so a
// bilinear lookup never extrapolates and 1/r = 0 reads the exact max(N·L, 0).
//   rgb = D of equation (1) at N·L = 2s − 1 and 1/r = t · maxCurvature (1/mm)
//   a   = encodeBeckmann(beckmannDistribution(N·H = s, α = t · kMaxSkinRoughness))
// The alpha channel shares the texel grid but not the parameters: one fetch at the diffuse
// coordinates and one at the specular ones read the same texture (render/luts/skin_specular.hpp
// for the encoding). Row α = 0 holds 0: Beckmann is a delta there; lookups need α ≳ 0.1 for the
// peak (width ≈ α²/2 in N·H) to span a few texels.

/// Roughness at t = 1; [dEL07]'s measured skin roughness is 0.3 … 0.45.
inline constexpr double kMaxSkinRoughness = 1.0;

struct PreintegratedSkinSettings {
  SkinProfile profile;
  SkinIntegrationRange range = SkinIntegrationRange::kCurvature;
  /// Texels per side. 256: bilinear lookups then differ from equation (1) by ≤ 4.4e-4 for
  /// 1/r ≥ maxCurvature/16 (about one half-float step near 1) and the encoded Beckmann term by
  /// ≤ 1.2e-4 of its peak for α = 0.2 … 0.5; 512 only quarters errors already below the storage
  /// precision, at 4× the memory and bake time.
  std::uint32_t size = 256;
  /// 1/r at t = 1, in 1/mm. 1 mm⁻¹ (r = 1 mm) is where the seed's range reaches ±π; curvier
  /// skin clamps to this row. A head's curvatures lie well inside (nose ≈ 0.2, ear rim ≈ 0.5).
  double maxCurvature = 1.0;
};

/// An error naming the first bad setting: the profile (validate(SkinProfile)), a size outside
/// [2, 4096], or a maxCurvature that is not finite or outside (0, 10] mm⁻¹.
Result<void> validate(const PreintegratedSkinSettings& settings);

/// The physical parameters of texel (i, j).
struct PreintegratedSkinSample {
  double nDotL = 0.0;
  double curvature = 0.0;  ///< 1/mm
  double nDotH = 0.0;
  double roughness = 0.0;
};
PreintegratedSkinSample preintegratedSkinSample(const PreintegratedSkinSettings& settings, std::uint32_t i,
                                                std::uint32_t j);

/// What texel (i, j) holds, computed on the CPU: the reference of the GPU bake.
glm::dvec4 preintegratedSkinTexel(const PreintegratedSkinSettings& settings, std::uint32_t i, std::uint32_t j);

}  // namespace mane::render
