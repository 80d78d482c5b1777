#pragma once
// A procedural daylight sky: Preetham, Shirley and Smits 1999, "A Practical Analytic Model for
// Daylight" (their appendix A.2): the Perez distribution of luminance and chromaticity with
// coefficients linear in the turbidity, and the zenith's luminance and chromaticity, converted
// from CIE xyY to linear sRGB. Below the horizon lies a grey Lambertian ground lit by the sky and
// the sun.

#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "render/environment/environment_map.hpp"

namespace mane::render {

struct SkySettings {
  /// Unit direction towards the sun (+Y up). A sun below the horizon lights the sky as one on it.
  glm::vec3 towardSun{0.0f, 1.0f, 0.0f};
  /// Haze: 2 is a clear sky, 6 a hazy one; the model was fitted from 2 to 10.
  float turbidity = 3.0f;
  /// The luminance of the radiance at the zenith (Rec. 709's weights of linear RGB), in the units
  /// of the lights' radiance; the model gives the colours and the rest of the sky's ratios to it.
  float zenithLuminance = 1.0f;
  /// The ground's reflectance, 0..1.
  float groundAlbedo = 0.3f;
  /// The sun's light on a surface facing it, in the renderer's units (DirectionalLight's colour ×
  /// intensity: a white Lambertian surface facing it shows that radiance); it lights the ground.
  glm::vec3 sunLight{0.0f};
};

/// What is wrong with `settings` (a turbidity outside [1.7, 10], a direction of no length,
/// anything negative or not finite); nothing when they are sound.
[[nodiscard]] Result<void> validateSky(const SkySettings& settings);

/// The sky's radiance towards unit `direction` above the horizon (direction.y > 0), in units of
/// the lights' radiance; the ground is not included.
[[nodiscard]] glm::vec3 skyRadiance(const SkySettings& settings, glm::vec3 direction);

/// The whole environment, sky and ground, as a cube map `size` texels wide. The ground's radiance
/// is albedo × (the sky's irradiance on it / π + the sun's light × its elevation's sine).
[[nodiscard]] CubeMap skyCubeMap(const SkySettings& settings, int size);

}  // namespace mane::render
