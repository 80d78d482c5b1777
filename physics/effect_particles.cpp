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
  // With a = g + c w, dv/dt = a − c v gives v(dt) = v e^{−c dt} + a·reach and
  // x(dt) = x + v·reach + a·lag, where reach = (1 − e^{−c dt})/c and lag = (dt − reach)/c; at
  // c = 0 they are dt and dt²/2, the parabola. Where c dt is small the differences would cancel,
  // so there they come from their series (the terms left out are below 1e-13 of them).
  const double c = settings_.dragPerSecond;
  const double x = c * dt;
  const double decay = detail::exponential(-x);
  double reach = 0.0;
  double lag = 0.0;
  if (x < 1e-3) {
    reach = dt * (1.0 - x / 2.0 + x * x / 6.0 - x * x * x / 24.0);
    lag = double(dt) * dt * (0.5 - x / 6.0 + x * x / 24.0 - x * x * x / 120.0);
  } else {
    reach = (1.0 - decay) / c;
    lag = (dt - reach) / c;
  }
  const glm::vec3 a = settings_.acceleration + settings_.dragPerSecond * wind;
  for (EffectParticle& p : particles_) {
    p.position += p.velocity * static_cast<float>(reach) + a * static_cast<float>(lag);
    p.velocity = p.velocity * static_cast<float>(decay) + a * static_cast<float>(reach);
    p.radius += settings_.growthPerSecond * dt;
    p.age += dt;
  }
  const float life = settings_.lifeSeconds;
  removeIf([life](const EffectParticle& p) { return p.age >= life; });
}

}  // namespace mane::physics
