#pragma once
// What a fibre scatters towards the eye from an environment given by its spherical harmonics,
// through the Marschner lobes of render/luts/marschner.hpp.
//
// The lit radiance is L_r(ωr) = ∫ S(ωi, ωr) L(ωi) dωi with S = Σ_p M_p(θi, θr) N_p(θr, φ). Around
// the tangent t, replace L by its average over the azimuth at each θi: band l of the harmonics
// averages to P_l(sin θi) times that band's value at t, e_l(t) = Σ_m L_lm Y_lm(t) (the addition
// theorem). N_p then integrates over φ alone, to the lobe's albedo A_p(θr), and
//
//   L_r = Σ_l e_l(t) · Σ_p A_p(θr) ∫ M_p(θi, θr) P_l(sin θi) cos θi dθi.
//
// Each lobe thus weighs each band by where its cone lies: the R lobe sees the environment around
// the mirror cone θi ≈ 2α_R − θr, TT the far side, TRT a wider cone. Exact for an environment
// that does not change round the tangent (a constant sky included); otherwise it drops the
// azimuthal detail, as the low-order projection of hair's environment light in real-time hair
// renderers does. The factors depend on θr alone, so a groom bakes them once, sampled in θr.

#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "render/luts/marschner.hpp"

namespace mane::render {

/// The weights of bands 0, 1 and 2 of the environment's radiance at the tangent, for one θr.
struct HairEnvironmentBands {
  std::array<double, 3> reflected{};    ///< the R lobe: the light's own colour
  std::array<glm::dvec3, 3> crossed{};  ///< TT + TRT per RGB: a strand's colour multiplies them
};

/// The weights at the eye's longitudinal angle `thetaR` (radians, [−π/2, π/2]). Band 0 is the
/// white-furnace albedo split by lobe; the θi integral takes kHairEnvironmentNodes midpoints.
[[nodiscard]] HairEnvironmentBands hairEnvironmentBands(const HairShadingParams& params, double thetaR);

/// Midpoints of the θi integral over [−π/2, π/2]: 0.05° apart, ten to the standard deviation of
/// the narrowest lobe the GPU tables allow (β = 0.5°).
inline constexpr std::size_t kHairEnvironmentNodes = 3600;

/// Samples of the table the hair lighting pass reads: θr = −π/2 + π·k/(n − 1).
inline constexpr std::size_t kHairEnvironmentSamples = 65;

/// hairEnvironmentBands at every sample θr.
[[nodiscard]] std::vector<HairEnvironmentBands> hairEnvironmentTable(const HairShadingParams& params);

}  // namespace mane::render
