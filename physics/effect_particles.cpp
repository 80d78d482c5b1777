#include "physics/effect_particles.hpp"

#include <cmath>
#include <string>

#include "physics/detail/hair_math.hpp"
#include "physics/detail/portable_math.hpp"

namespace mane::physics {

Result<EffectParticles> EffectParticles::create(const EffectParticleSettings& settings) {
  const auto bad = [](const char* field, const char* expected) {
    return fail(std::string("effect particles: ") + field + " must be " + expected + ".");
  };
  if (!detail::isFinite(settings.acceleration)) return bad("acceleration", "finite");
  if (!(std::isfinite(settings.dragPerSecond) && settings.dragPerSecond >= 0.0f))
    return bad("dragPerSecond", "finite and ≥ 0");
  if (!(std::isfinite(settings.lifeSeconds) && settings.lifeSeconds > 0.0f))
    return bad("lifeSeconds", "finite and > 0");
  if (!(std::isfinite(settings.growthPerSecond) && settings.growthPerSecond >= 0.0f))
    return bad("growthPerSecond", "finite and ≥ 0");
  if (settings.capacity < 1) return bad("capacity", "at least 1");
  EffectParticles particles(settings);
  particles.particles_.reserve(settings.capacity);
  return particles;
}

bool EffectParticles::emit(const glm::vec3& position, const glm::vec3& velocity, float radius) {
  if (particles_.size() >= settings_.capacity) return false;
  particles_.push_back({.position = position, .velocity = velocity, .radius = radius, .age = 0.0f});
  return true;
}

void EffectParticles::step(float dt, const glm::vec3& wind) {
  const glm::vec3 g = settings_.acceleration;
  const float c = settings_.dragPerSecond;
  // With drag: v∞ = w + g/c, v(dt) = v∞ + (v − v∞)·decay, x(dt) = x + v∞ dt + (v − v∞)(1 − decay)/c.
  // Without: the parabola.
  const float decay = static_cast<float>(detail::exponential(-static_cast<double>(c) * dt));
  const glm::vec3 terminal = c > 0.0f ? wind + g / c : glm::vec3(0.0f);
  const float reach = c > 0.0f ? (1.0f - decay) / c : dt;
  for (EffectParticle& p : particles_) {
    if (c > 0.0f) {
      const glm::vec3 transient = p.velocity - terminal;
      p.position += terminal * dt + transient * reach;
      p.velocity = terminal + transient * decay;
    } else {
      p.position += p.velocity * dt + g * (0.5f * dt * dt);
      p.velocity += g * dt;
    }
    p.radius += settings_.growthPerSecond * dt;
    p.age += dt;
  }
  const float life = settings_.lifeSeconds;
  removeIf([life](const EffectParticle& p) { return p.age >= life; });
}

}  // namespace mane::physics
