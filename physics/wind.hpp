#pragma once
// Wind: a velocity field with gusts, and the drag it exerts on a strand segment.
//
// Gusts are value noise in time (pseudo-random levels at every gust period, joined by a
// smoothstep, so the wind speed is C¹ in time), shifted by the time the air takes to travel
// along the wind direction, so a gust front sweeps across a groom instead of hitting every
// strand at once. Everything is arithmetic on floats and integers: no libm, no platform
// differences, identical results for any thread count.
//
// The force depends on a segment's orientation to the wind: a thin cylinder in a flow feels
// drag from the velocity component normal to its axis only (the axial part just slides along
// it; slender-body drag, e.g. Hoerner, "Fluid-Dynamic Drag", 1965, ch. 3). The drag is linear,
// a = k · (w − v)⊥, a common choice in real-time hair (it is stable for any step with k·h < 1).

#include <cstdint>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

struct WindSettings {
  glm::vec3 direction{1.0f, 0.0f, 0.0f};  ///< where the air goes; normalised on use, non-zero
  float speed = 0.0f;                     ///< mean air speed, m/s, ≥ 0
  float gustAmplitude = 0.0f;             ///< gusts add up to ± this to the speed, m/s, ≥ 0
  float gustPeriod = 2.0f;                ///< seconds between independent gust levels, > 0
  float dragPerSecond = 2.0f;             ///< k in a = k·(w − v)⊥, 1/s, ≥ 0
  std::uint64_t seed = 1;                 ///< gust sequence; equal seeds give equal wind
};

/// Checks the ranges documented on `WindSettings`, naming the field.
[[nodiscard]] Result<void> validateWind(const WindSettings& settings);

class WindField {
public:
  /// `settings` must pass `validateWind`.
  explicit WindField(const WindSettings& settings);

  /// Air velocity (m/s) at `position` (metres, world) and `time` (seconds). The speed never
  /// drops below zero: a gust can calm the wind but not reverse it.
  [[nodiscard]] glm::vec3 velocityAt(const glm::vec3& position, double time) const;

  /// The gust term alone, in [−1, 1], at `time` for air that passed the origin `time` ago.
  [[nodiscard]] float gust(double time) const;

  [[nodiscard]] const WindSettings& settings() const { return settings_; }

private:
  WindSettings settings_;
  glm::vec3 direction_;  ///< unit
};

/// Acceleration (m/s²) of a particle moving with `particleVelocity` on a segment whose unit axis
/// is `segmentAxis`, in air moving with `airVelocity`: k·(w − v) with the axial part removed.
[[nodiscard]] glm::vec3 windAcceleration(const glm::vec3& airVelocity, const glm::vec3& particleVelocity,
                                         const glm::vec3& segmentAxis, float dragPerSecond);

}  // namespace mane::physics
