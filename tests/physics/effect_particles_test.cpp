// Spray and smoke particles.
//
// Oracles: the closed forms of dv/dt = g + c (w − v): the parabola of free flight without drag;
// with drag and no gravity, a particle launched at v₀ stops v₀/c away; the terminal velocity
// w + g/c; and the step does not change the flight (the update is exact).

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "physics/effect_particles.hpp"

namespace mane::physics {
namespace {

EffectParticles make(const EffectParticleSettings& settings) {
  auto particles = EffectParticles::create(settings);
  EXPECT_TRUE(particles) << particles.error().message;
  return std::move(*particles);
}

TEST(EffectParticles, WithoutDragAParticleFliesTheParabola) {
  EffectParticles particles = make({.acceleration = {0.0f, -9.81f, 0.0f}, .lifeSeconds = 10.0f});
  ASSERT_TRUE(particles.emit({1.0f, 0.0f, 2.0f}, {3.0f, 12.0f, -1.0f}, 0.1f));
  float highest = 0.0f;
  for (int i = 0; i < 120; ++i) {
    particles.step(1.0f / 60.0f, glm::vec3(5.0f));  // no drag: the wind does nothing
    highest = std::max(highest, particles.particles()[0].position.y);
  }
  const EffectParticle& p = particles.particles()[0];
  EXPECT_NEAR(p.position.x, 1.0f + 3.0f * 2.0f, 1e-4f);
  EXPECT_NEAR(p.position.y, 12.0f * 2.0f - 0.5f * 9.81f * 4.0f, 1e-3f);
  EXPECT_NEAR(p.position.z, 2.0f - 2.0f, 1e-4f);
  EXPECT_NEAR(p.velocity.y, 12.0f - 9.81f * 2.0f, 1e-4f);
  // The apex v²/2g, to within the height lost over half a step either side of it.
  EXPECT_NEAR(highest, 144.0f / (2.0f * 9.81f), 0.5f * 9.81f / (60.0f * 60.0f));
}

TEST(EffectParticles, AVanishingDragFliesTheParabolaStill) {
  // At c = 1e-7 per second the drag moves a particle by v₀ c t²/2 ≈ 1e-6 m over 2 s: the step
  // must not lose the parabola to rounding as c dt nears 0.
  for (float drag : {0.0f, 1e-7f, 1e-4f}) {
    EffectParticles particles =
        make({.acceleration = {0.0f, -9.81f, 0.0f}, .dragPerSecond = drag, .lifeSeconds = 10.0f});
    particles.emit(glm::vec3(0.0f), {3.0f, 12.0f, 0.0f}, 0.1f);
    for (int i = 0; i < 120; ++i) particles.step(1.0f / 60.0f, glm::vec3(0.0f));
    const EffectParticle& p = particles.particles()[0];
    // The drag's share over 2 s: x loses about v₀ c t²/2, y about (v₀ t²/2 − g t³/6) c.
    EXPECT_NEAR(p.position.x, 6.0f, 1e-4f + 3.0f * drag * 2.0f) << drag;
    EXPECT_NEAR(p.position.y, 24.0f - 0.5f * 9.81f * 4.0f, 1e-3f + 20.0f * drag) << drag;
  }
}

TEST(EffectParticles, DragStopsALaunchedParticleAtItsSpeedOverTheRate) {
  EffectParticles particles = make({.acceleration = glm::vec3(0.0f), .dragPerSecond = 2.0f, .lifeSeconds = 100.0f});
  particles.emit(glm::vec3(0.0f), {20.0f, 0.0f, 0.0f}, 0.5f);
  for (int i = 0; i < 60 * 15; ++i) particles.step(1.0f / 60.0f, glm::vec3(0.0f));
  EXPECT_NEAR(particles.particles()[0].position.x, 20.0f / 2.0f, 1e-3f);
  EXPECT_NEAR(particles.particles()[0].velocity.x, 0.0f, 1e-6f);
}

TEST(EffectParticles, ItEndsAtTheWindsVelocityPlusGravityOverDrag) {
  EffectParticles particles = make({.acceleration = {0.0f, 0.6f, 0.0f}, .dragPerSecond = 1.5f, .lifeSeconds = 100.0f});
  particles.emit(glm::vec3(0.0f), {0.0f, 0.0f, 30.0f}, 0.5f);
  const glm::vec3 wind(4.0f, 0.0f, -2.0f);
  for (int i = 0; i < 60 * 20; ++i) particles.step(1.0f / 60.0f, wind);
  const glm::vec3 v = particles.particles()[0].velocity;
  EXPECT_NEAR(v.x, 4.0f, 1e-4f);
  EXPECT_NEAR(v.y, 0.6f / 1.5f, 1e-4f);
  EXPECT_NEAR(v.z, -2.0f, 1e-4f);
}

TEST(EffectParticles, TheFlightDoesNotDependOnTheStep) {
  const EffectParticleSettings settings{
      .acceleration = {0.0f, -3.0f, 0.0f}, .dragPerSecond = 0.8f, .lifeSeconds = 10.0f, .growthPerSecond = 0.5f};
  EffectParticles coarse = make(settings);
  EffectParticles fine = make(settings);
  for (EffectParticles* p : {&coarse, &fine}) p->emit({0.0f, 1.0f, 0.0f}, {7.0f, 9.0f, 1.0f}, 0.2f);
  coarse.step(1.5f, glm::vec3(2.0f, 0.0f, 0.0f));
  for (int i = 0; i < 90; ++i) fine.step(1.0f / 60.0f, glm::vec3(2.0f, 0.0f, 0.0f));
  const EffectParticle& a = coarse.particles()[0];
  const EffectParticle& b = fine.particles()[0];
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(a.position[axis], b.position[axis], 1e-4f);
    EXPECT_NEAR(a.velocity[axis], b.velocity[axis], 1e-4f);
  }
  EXPECT_NEAR(a.radius, 0.2f + 0.5f * 1.5f, 1e-5f);
  EXPECT_NEAR(b.radius, 0.2f + 0.5f * 1.5f, 1e-5f);
}

TEST(EffectParticles, ParticlesLiveTheirLifeAndTheStoreHoldsItsCapacity) {
  EffectParticles particles = make({.lifeSeconds = 1.0f, .capacity = 3});
  EXPECT_TRUE(particles.emit(glm::vec3(0.0f), glm::vec3(0.0f), 0.1f));
  particles.step(0.5f, glm::vec3(0.0f));
  EXPECT_TRUE(particles.emit(glm::vec3(1.0f), glm::vec3(0.0f), 0.1f));
  EXPECT_TRUE(particles.emit(glm::vec3(2.0f), glm::vec3(0.0f), 0.1f));
  EXPECT_FALSE(particles.emit(glm::vec3(3.0f), glm::vec3(0.0f), 0.1f));
  EXPECT_NEAR(particles.lifeShare(particles.particles()[0]), 0.5f, 1e-6f);
  particles.step(0.5f, glm::vec3(0.0f));  // the first reaches its life
  ASSERT_EQ(particles.particles().size(), 2u);
  particles.removeIf([](const EffectParticle& p) { return p.position.x == 1.0f; });
  ASSERT_EQ(particles.particles().size(), 1u);
  EXPECT_EQ(particles.particles()[0].position.x, 2.0f);
}

TEST(EffectParticles, RefusesSettingsOutOfRangeByName) {
  const auto refused = [](const EffectParticleSettings& s, const char* field) {
    const auto particles = EffectParticles::create(s);
    ASSERT_FALSE(particles) << field;
    EXPECT_NE(particles.error().message.find(field), std::string::npos) << particles.error().message;
  };
  refused({.acceleration = {0.0f, NAN, 0.0f}}, "acceleration");
  refused({.dragPerSecond = -1.0f}, "dragPerSecond");
  refused({.lifeSeconds = 0.0f}, "lifeSeconds");
  refused({.growthPerSecond = INFINITY}, "growthPerSecond");
  refused({.capacity = 0}, "capacity");
}

}  // namespace
}  // namespace mane::physics
