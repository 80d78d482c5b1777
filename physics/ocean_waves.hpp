#pragma once
// The sea's surface as a sum of Gerstner waves, grown from the wind.
//
// Each wave moves the water that rests at x₀ = (x, z) on a circle in the plane of its travel
// (Gerstner 1802; Tessendorf, "Simulating Ocean Water", SIGGRAPH course notes 2001, §3.1):
//
//   position(x₀, t) = (x₀ − λ Σ dᵢ Aᵢ sin θᵢ,  Σ Aᵢ cos θᵢ),   θᵢ = kᵢ dᵢ·x₀ + φᵢ − ωᵢ t,
//
// with deep water's dispersion ωᵢ = √(g kᵢ). λ pulls the water towards the crests and sharpens
// them; where the horizontal map folds (its Jacobian J < 0) a crest breaks. To first order
// J = 1 − λ Σ kᵢAᵢ cos θᵢ, so λ is set from the choppiness asked for by the spread of that sum
// over a sea of independent phases (see OceanSettings::choppiness).
//
// The waves sample the Pierson–Moskowitz spectrum of a fully developed sea (Pierson and
// Moskowitz 1964): S(ω) = α g² ω⁻⁵ exp(−β (ω₀/ω)⁴), α = 8.1e-3, β = 0.74, ω₀ = g/U with U the
// wind speed 19.5 m above the sea. Its integral has a closed form, so each wave takes exactly
// the energy of its band of frequencies (Aᵢ = √(2 Eᵢ)); the bands are spaced evenly in log ω
// from half the peak to the shortest wavelength asked for. Directions spread about the wind as
// cos²θ, phases are uniform; both come from splitmix64.
//
// Everything is deterministic on every platform: sines, cosines and exponentials come from
// physics/detail/portable_math.hpp, and the time enters only through each wave's phase, reduced
// to [0, 2π) in double precision (`phasesAt`), which is also what the GPU's copy of the same sum
// receives, so both evaluate the same function.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

/// The sea's gravity, m/s².
inline constexpr float kOceanGravity = 9.81f;

struct OceanSettings {
  float windSpeed = 10.0f;              ///< m/s, 19.5 m above the sea, > 0
  glm::vec2 windDirection{1.0f, 0.0f};  ///< (x, z) the wind blows towards; non-zero
  /// [0, 1]: 0 rolls sine waves; c spreads the Jacobian J over the sea by c/3 (its standard
  /// deviation), so at 1 the surface folds over (J < 0) on about 0.13 % of it, three deviations out.
  float choppiness = 0.8f;
  int waveCount = 45;               ///< 1 … kMaxOceanWaves
  float shortestWavelength = 1.0f;  ///< m, > 0, below the spectrum's peak wavelength
  std::uint64_t seed = 1;           ///< directions and phases; equal seeds, equal seas
};

/// What the GPU's copy of the sum holds at most (shaders/ocean_waves.glsl).
inline constexpr int kMaxOceanWaves = 64;

/// One wave. Directions are unit (x, z); the wave travels along its direction.
struct GerstnerWave {
  glm::vec2 direction{1.0f, 0.0f};
  float wavenumber = 1.0f;        ///< k = 2π/wavelength, 1/m
  float angularFrequency = 1.0f;  ///< ω, rad/s
  float amplitude = 0.0f;         ///< A, m
  float phase = 0.0f;             ///< φ at t = 0, radians
};

/// The water that rests at x₀, at one time.
struct OceanSample {
  glm::vec2 rest{0.0f};                ///< (x, z) where this water rests, metres
  glm::vec3 position{0.0f};            ///< metres
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  ///< unit, upward
  glm::vec3 velocity{0.0f};            ///< m/s
  float jacobian = 1.0f;               ///< of x₀ ↦ the horizontal position; < 0 folds
};

/// Checks the ranges documented on `OceanSettings`, naming the field.
[[nodiscard]] Result<void> validateOcean(const OceanSettings& settings);

/// The significant wave height of the Pierson–Moskowitz sea for `windSpeed` (m/s): 4√m₀, with
/// m₀ = α U⁴ / (4 β g²) the spectrum's integral.
[[nodiscard]] double piersonMoskowitzSignificantHeight(double windSpeed);

class OceanWaves {
public:
  /// The waves the wind grows. Fails on settings `validateOcean` refuses.
  [[nodiscard]] static Result<OceanWaves> create(const OceanSettings& settings);

  /// Waves given one by one (an empty list is a calm sea); `choppiness` is λ itself here.
  /// Fails on more than kMaxOceanWaves waves, or a wave with a direction that is not unit, a
  /// wavenumber or frequency that is not positive, a negative amplitude or a value not finite.
  [[nodiscard]] static Result<OceanWaves> fromWaves(std::vector<GerstnerWave> waves, float choppiness);

  [[nodiscard]] std::span<const GerstnerWave> waves() const { return waves_; }
  /// λ: how far the water moves towards the crests, per metre of height.
  [[nodiscard]] float choppiness() const { return choppiness_; }

  /// Each wave's phase φᵢ − ωᵢ t reduced to [0, 2π), rounded to float: what a GPU evaluating
  /// the same sum adds to kᵢ dᵢ·x₀. `out` holds one value per wave.
  void phasesAt(double time, std::span<float> out) const;

  /// The water resting at `rest` = (x, z), at `time` seconds.
  [[nodiscard]] OceanSample sample(glm::vec2 rest, double time) const;

  /// The water found at `position` = (x, z) at `time`: the rest point whose water lies over
  /// `position`, found by at most kSurfaceSteps steps of Newton's method (to a tenth of a
  /// millimetre wherever the surface is not about to fold, J > 0.2). Its `position.y` is the sea's
  /// height there. Where the surface folds over, one of the waters found there.
  [[nodiscard]] OceanSample surfaceAt(glm::vec2 position, double time) const;

  static constexpr int kSurfaceSteps = 10;

private:
  OceanWaves(std::vector<GerstnerWave> waves, float choppiness);
  /// `sample`, and where `horizontalMap` is not null the 2×2 Jacobian matrix of x₀ ↦ (x, z).
  OceanSample evaluate(glm::vec2 rest, double time, glm::dmat2* horizontalMap) const;

  std::vector<GerstnerWave> waves_;
  float choppiness_;
};

}  // namespace mane::physics
