// Free fall: position Verlet without damping reproduces x(t) = x0 + v0·t + ½·g·t² exactly in
// exact arithmetic, because that quadratic satisfies the Verlet recurrence
// x[n+1] = 2x[n] − x[n−1] + g·h² term for term (its second difference is g·h²). The only
// error left is floating-point rounding. The initial velocity v0 enters through the previous
// position: x_prev = x(−h) = x0 − v0·h + ½·g·h² (Particles::addMoving).

#include <cmath>

#include <gtest/gtest.h>

#include "physics/solver.hpp"
#include "tests/support/particle_solver.hpp"

namespace mane::physics {
namespace {

using mane::testing::ParticleSolver;

SolverSettings freeFallSettings(double step, glm::vec3 gravity) {
  SolverSettings settings;
  settings.fixedStep = step;
  settings.gravity = gravity;
  settings.damping = 0.0f;
  settings.constraintIterations = 1;
  settings.maxSubstepsPerFrame = 1;
  return settings;
}

TEST(FreeFall, DyadicInputsMatchTheParabolaBitForBit) {
  // g = −8 m/s², h = 1/128 s, x0 and v0·h dyadic: every intermediate value is a short binary
  // fraction, so every float operation is exact and the result must equal the analytic
  // position exactly (tolerance 0).
  const double h = 1.0 / 128.0;
  const glm::vec3 g{0.0f, -8.0f, 0.0f};
  const glm::vec3 x0{0.5f, 20.0f, -1.0f};
  const glm::vec3 v0{1.0f, 4.0f, 0.25f};
  auto solver = ParticleSolver::create(freeFallSettings(h, g));
  ASSERT_TRUE(solver);
  solver->particles.addMoving(x0, v0, static_cast<float>(h), g, 1.0f);
  for (int n = 1; n <= 256; ++n) {
    solver->step();
    const double t = n * h;
    for (int axis = 0; axis < 3; ++axis) {
      const double exact = x0[axis] + v0[axis] * t + 0.5 * g[axis] * t * t;
      ASSERT_EQ(static_cast<double>(solver->particles.positions[0][axis]), exact) << "step " << n << ", axis " << axis;
    }
  }
}

TEST(FreeFall, RealisticStepMatchesTheParabolaToRounding) {
  // g = 9.81 m/s², h = 1/120 s, 1 s of fall, |x| < 16 m throughout. Per step, x − x_prev is
  // exact (Sterbenz: the two are within a factor 2) and the two additions each round by at most
  // half an ulp of |x|, ulp(16 m) = 2⁻²⁰ m ≈ 9.5e-7 m; together at most one ulp r. Verlet
  // carries a position error made at step k into every later step (the error obeys the same
  // recurrence e[n+1] = 2e[n] − e[n−1] + r), so after n steps |error| ≤ n(n+1)/2 · r — about
  // 7e-3 m after 120 steps. These roundings are not random: adding g·h² ≈ 6.8e-4 m to a
  // position near 10 m rounds the same way step after step, so the bound is nearly reached.
  const double h = 1.0 / 120.0;
  const glm::vec3 g{0.0f, -9.81f, 0.0f};
  const glm::vec3 x0{0.0f, 10.0f, 0.0f};
  const glm::vec3 v0{1.5f, 3.0f, -0.7f};
  const double ulp = std::ldexp(1.0, -20);  // ulp of floats in [8, 16)
  auto solver = ParticleSolver::create(freeFallSettings(h, g));
  ASSERT_TRUE(solver);
  solver->particles.addMoving(x0, v0, static_cast<float>(h), g, 1.0f);
  for (int n = 1; n <= 120; ++n) {
    solver->step();
    const double t = n * h;
    // + 4 ulp for the rounding of x_prev and g·h² themselves.
    const double tolerance = (0.5 * n * (n + 1) + 4.0) * ulp;
    for (int axis = 0; axis < 3; ++axis) {
      const double exact = static_cast<double>(x0[axis]) + static_cast<double>(v0[axis]) * t +
                           0.5 * static_cast<double>(g[axis]) * t * t;
      ASSERT_NEAR(solver->particles.positions[0][axis], exact, tolerance) << "step " << n << ", axis " << axis;
    }
  }
}

TEST(FreeFall, KinematicParticlesDoNotFall) {
  // Inverse mass 0 is infinite mass (Jakobsen 2001): the integrator must leave it exactly put.
  auto solver = ParticleSolver::create(freeFallSettings(1.0 / 120.0, {0.0f, -9.81f, 0.0f}));
  ASSERT_TRUE(solver);
  solver->particles.add({1.0f, 2.0f, 3.0f}, 0.0f);
  for (int n = 0; n < 100; ++n) solver->step();
  EXPECT_EQ(solver->particles.positions[0], glm::vec3(1.0f, 2.0f, 3.0f));
}

TEST(FreeFall, DampingScalesTheImpliedVelocityEveryStep) {
  // Without gravity, x' − x = (1 − d)(x − x_prev): the displacement per step decays
  // geometrically. Reference 0.01·(1 − d)^n m computed in double; tolerance 5e-8 m: the
  // displacement is the difference of two positions below 0.1 m whose ulp is 7.5e-9 m, and
  // each step's rounding carries over, so a few ulps after 50 steps.
  const float d = 0.1f;
  SolverSettings settings = freeFallSettings(0.01, {0.0f, 0.0f, 0.0f});
  settings.damping = d;
  auto solver = ParticleSolver::create(settings);
  ASSERT_TRUE(solver);
  solver->particles.addMoving({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 0.01f, {0, 0, 0}, 1.0f);
  for (int n = 1; n <= 50; ++n) {
    solver->step();
    const float displacement = solver->particles.positions[0].x - solver->particles.previousPositions[0].x;
    const double expected = 0.01 * std::pow(1.0 - static_cast<double>(d), n);
    ASSERT_NEAR(displacement, expected, 5e-8) << "step " << n;
  }
}

}  // namespace
}  // namespace mane::physics
