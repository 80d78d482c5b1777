#pragma once
// Short-lived particles read as spray and smoke (NVIDIA's "Clear Sailing", 2004): each flies
// from where it was emitted, pulled by a constant acceleration g (gravity; upward for smoke's
// lift) while its velocity relaxes towards the wind's at a rate c (drag), and grows and fades
// over a set life.
//
// dv/dt = g + c (w − v) has the closed form v(t) = v∞ + (v₀ − v∞) e^{−ct}, v∞ = w + g/c, whose
// integral gives the position: the step follows it for any dt (to float's rounding), so the
// fast-then-damped flight of a cannon's smoke does not depend on the step (with c = 0 it is the
// parabola of free flight).
// The exponential is physics/detail/portable_math.hpp's: deterministic on every platform.

#include <cstddef>
#include <vector>  // std::erase_if

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

struct EffectParticleSettings {
  glm::vec3 acceleration{0.0f, -9.81f, 0.0f};  ///< g, m/s² (finite)
  float dragPerSecond = 0.0f;                  ///< c, 1/s, ≥ 0
  float lifeSeconds = 1.0f;                    ///< > 0: a particle is removed at this age
  float growthPerSecond = 0.0f;                ///< metres of radius gained per second, ≥ 0
  std::size_t capacity = 1024;                 ///< ≥ 1: emissions past it are dropped
};

struct EffectParticle {
  glm::vec3 position{0.0f};  ///< metres
  glm::vec3 velocity{0.0f};  ///< m/s
  float radius = 0.0f;       ///< metres
  float age = 0.0f;          ///< seconds since it was emitted
};

class EffectParticles {
public:
  /// Fails on settings out of the documented ranges, naming the field.
  [[nodiscard]] static Result<EffectParticles> create(const EffectParticleSettings& settings);

  /// Adds a particle; false (and nothing added) when the store is full.
  bool emit(const glm::vec3& position, const glm::vec3& velocity, float radius);

  /// Advances every particle by `dt` seconds in air moving with `wind` (m/s) and removes those
  /// that reach their life. The particles keep the order they were emitted in.
  void step(float dt, const glm::vec3& wind);

  /// Removes the particles `doomed` returns true for, keeping the others' order.
  template <typename Predicate>
  void removeIf(Predicate doomed) {
    std::erase_if(particles_, doomed);
  }

  [[nodiscard]] const std::vector<EffectParticle>& particles() const { return particles_; }
  [[nodiscard]] const EffectParticleSettings& settings() const { return settings_; }
  /// How far through its life a particle is, in [0, 1].
  [[nodiscard]] float lifeShare(const EffectParticle& particle) const { return particle.age / settings_.lifeSeconds; }

private:
  explicit EffectParticles(const EffectParticleSettings& settings) : settings_(settings) {}

  EffectParticleSettings settings_;
  std::vector<EffectParticle> particles_;
};

}  // namespace mane::physics
