#pragma once
// The sun cut out of an environment and handed back as a directional light, so that a scene lit
// by a panorama and a key light counts the sun once: in the light, which casts the shadows and
// the sharp highlights, and not again in the environment's irradiance and reflections.
//
// The sun is the brightest texel's neighbourhood: the texels within kCoreDegrees of it brighter
// than kAboveSky × the sky round it (the mean radiance of the ring from kCoreDegrees to
// kRingDegrees). Each such texel keeps min(L, L_sky) per channel, and what it gives up, (L −
// L_sky)⁺·dω, goes to the light, which lies along their luminance-weighted mean direction: the
// light's irradiance on a surface facing it equals what the texels gave, so the energy is kept,
// up to the cosine's change across the core (at most 1 − cos 5°, 0.4 %, for texels at its edge).
// A panorama whose brightest texel is less than kSunContrast × its sky (an overcast sky) has no
// sun to cut.

#include <optional>

#include "render/environment/environment_map.hpp"
#include "render/frame.hpp"

namespace mane::render {

struct SunExtraction {
  CubeMap radiance;                     ///< the environment without its sun
  std::optional<DirectionalLight> sun;  ///< none where the sky has no sun
  double solidAngle = 0.0;              ///< of the texels cut, steradians
};

inline constexpr double kCoreDegrees = 5.0;
inline constexpr double kRingDegrees = 10.0;
inline constexpr double kAboveSky = 2.0;
inline constexpr double kSunContrast = 20.0;

/// `cube` with its sun cut out, and the sun as a light: its direction (towards it), colour (the
/// largest channel 1) × intensity = the irradiance it gave up, disc radius √(Ω/π) for the solid
/// angle Ω cut, disc radiance that irradiance / Ω in units of its colour.
[[nodiscard]] SunExtraction extractSun(CubeMap cube);

}  // namespace mane::render
