#pragma once
// A spectacle lens as the glasses pass draws it (render/passes/glasses_pass.hpp): glass between
// two spherical surfaces inside an elliptical outline.
//
// The lens frame: metres, the optical axis along z, the front surface's vertex at the origin and
// the back surface's at z = −centreThickness; +z points out of the front surface, away from the
// wearer's eye. A surface of curvature c (1/radius) falls back from its vertex by the sag
// c·r²/(1 + √(1 − c²r²)) at distance r from the axis: c > 0 bulges towards +z, 0 is flat.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::render {

struct LensShape {
  float frontCurvature = 0.0f;             ///< 1/m
  float backCurvature = 0.0f;              ///< 1/m
  float centreThickness = 0.002f;          ///< m, > 0
  glm::vec2 halfAperture{0.025f, 0.018f};  ///< m: the outline's half width (x) and half height (y)
  float ior = 1.5f;                        ///< the glass's index of refraction, [1, 3]
  glm::vec3 transmittance{1.0f};           ///< the glass's tint: what a pass through it keeps, each in [0, 1]
};

/// A lens placed in the world: `model` takes the lens frame to the world (rigid, metres).
struct Lens {
  LensShape shape;
  glm::mat4 model{1.0f};
};

/// How far a surface of curvature `curvature` falls back from its vertex at distance `r` from the
/// axis, metres; needs |curvature|·r < 1.
[[nodiscard]] float lensSag(float curvature, float r);

/// The thin-lens power (n − 1)(c_front − c_back) of `shape`, dioptres (1/m).
[[nodiscard]] float thinLensPower(const LensShape& shape);

/// Whether `shape` can be drawn: finite, thickness > 0, a half aperture in (0, 0.1] m, ior in
/// [1, 3], transmittance in [0, 1], both surfaces defined over the whole outline (|c|·r < 1) and
/// the glass at least as thick as nothing at the outline's edge. Errors say which.
[[nodiscard]] Result<void> validateLensShape(const LensShape& shape);

/// validateLensShape, and `lens.model` finite and rigid (a rotation within 1e-3 and a translation).
[[nodiscard]] Result<void> validateLens(const Lens& lens);

/// The most a spectacle prescription may ask, dioptres, either sign.
inline constexpr float kMaxLensPower = 20.0f;

/// A spectacle lens of `powerDioptres` (thin-lens power, |P| ≤ kMaxLensPower) cut to
/// `halfAperture`, as an optician would grind it: a meniscus whose front surface follows Vogel's
/// rule for the base curve (front power P/2 + 6 D for plus lenses, P/4 + 6 D for minus ones, at
/// least 1 D), the back surface giving the power, and the glass as thin as 1.5 mm at the centre
/// of a minus lens or 1 mm at the thinnest point of a plus lens's edge allow.
[[nodiscard]] Result<LensShape> spectacleLens(float powerDioptres, glm::vec2 halfAperture, float ior = 1.5f);

}  // namespace mane::render
