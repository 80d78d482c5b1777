// Constraint relaxation (Jakobsen 2001, §3) and long-range attachments (Kim, Chentanez & Müller
// 2012). Oracles: the exact geometry of one projection; the convergence of Gauss–Seidel
// sweeps (more sweeps, less error); and the tether bound (no particle beyond its rest distance
// along the strand from the root).

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "physics/constraints.hpp"
#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/solver.hpp"
#include "tests/support/particle_solver.hpp"

namespace mane::physics {
namespace {

using mane::testing::ParticleSolver;

float distance(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = b - a;
  return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

TEST(DistanceConstraint, ProjectionSharesTheCorrectionByInverseMass) {
  // Rest length 1, current length 3 along x; weights 1 and 3: the error of 2 is shared 1/4 : 3/4
  // (Jakobsen 2001, eq. in §3). All values dyadic, so the result is exact.
  glm::vec3 a{0.0f, 0.0f, 0.0f};
  glm::vec3 b{3.0f, 0.0f, 0.0f};
  projectDistance(a, b, 1.0f, 3.0f, 1.0f);
  EXPECT_EQ(a, glm::vec3(0.5f, 0.0f, 0.0f));
  EXPECT_EQ(b, glm::vec3(1.5f, 0.0f, 0.0f));
}

TEST(DistanceConstraint, KinematicEndNeverMoves) {
  glm::vec3 root{1.0f, 2.0f, 3.0f};
  glm::vec3 tip{1.0f, -5.0f, 3.0f};
  projectDistance(root, tip, 0.0f, 1.0f, 2.0f);
  EXPECT_EQ(root, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(tip, glm::vec3(1.0f, 0.0f, 3.0f));
  // Two kinematic ends and coincident points are left alone rather than divided by zero.
  glm::vec3 p{0.0f}, q{0.0f};
  projectDistance(p, q, 1.0f, 1.0f, 1.0f);
  EXPECT_EQ(p, glm::vec3(0.0f));
  EXPECT_EQ(q, glm::vec3(0.0f));
}

TEST(Tether, OnlyPullsBackAndNeverPushes) {
  glm::vec3 p{0.0f, -4.0f, 0.0f};
  projectTether(p, glm::vec3(0.0f), 2.0f);
  EXPECT_EQ(p, glm::vec3(0.0f, -2.0f, 0.0f));
  glm::vec3 q{0.0f, -1.0f, 0.0f};
  projectTether(q, glm::vec3(0.0f), 2.0f);  // slack: inside the sphere, untouched
  EXPECT_EQ(q, glm::vec3(0.0f, -1.0f, 0.0f));
}

// A 24-particle strand hanging from a kinematic root, given a random velocity kick (fixed
// seed), stepped once with `iterations` sweeps; returns the largest relative stretch.
float stretchAfterOneStep(int iterations) {
  SolverSettings settings;
  settings.fixedStep = 1.0 / 60.0;
  settings.damping = 0.0f;
  settings.constraintIterations = iterations;
  settings.tethers = false;  // measure the distance relaxation alone
  auto solver = ParticleSolver::create(settings);
  EXPECT_TRUE(solver);
  SplitMix64 rng(42);
  constexpr int kParticles = 24;
  for (int i = 0; i < kParticles; ++i) {
    const glm::vec3 velocity{rng.nextFloat(-3.0f, 3.0f), rng.nextFloat(-3.0f, 3.0f), rng.nextFloat(-3.0f, 3.0f)};
    solver->particles.addMoving({0.02f * static_cast<float>(i), 0.0f, 0.0f}, velocity,
                                static_cast<float>(settings.fixedStep), settings.gravity, i == 0 ? 0.0f : 1.0f);
    if (i > 0) solver->distances.push_back({static_cast<ParticleIndex>(i - 1), static_cast<ParticleIndex>(i), 0.02f});
  }
  solver->step();
  return maxRelativeStretch(solver->particles, solver->distances);
}

TEST(DistanceConstraint, ErrorFallsMonotonicallyAsIterationsRise) {
  // Gauss–Seidel sweeps over a chain contract the error; the worst stretch after the step must
  // not rise from 1 to 64 sweeps, and must fall by at least 10× over that range.
  float previous = stretchAfterOneStep(1);
  const float first = previous;
  for (int iterations = 2; iterations <= 64; ++iterations) {
    const float stretch = stretchAfterOneStep(iterations);
    EXPECT_LE(stretch, previous) << iterations << " iterations";
    previous = stretch;
  }
  EXPECT_LT(previous, 0.1f * first) << "1 sweep: " << first << ", 64 sweeps: " << previous;
  RecordProperty("stretch_1_sweep", std::to_string(first));
  RecordProperty("stretch_64_sweeps", std::to_string(previous));
}

// Shakes a head carrying a groom back and forth and round, 2 s of frames at 60 Hz, with a
// single constraint sweep (as loose as the solver gets); returns the worst ratio of a particle's
// distance from its root to its rest distance along the strand, and the worst excess in metres.
struct Reach {
  float ratio = 0.0f;
  float excess = -1.0f;
};
Reach worstReachDuringShake(bool tethers) {
  GroomSettings groom;
  groom.seed = 3;
  groom.strandCount = 24;
  groom.particlesPerStrand = 16;
  groom.strandLength = 0.4f;
  auto strands = generateGroom(groom);
  EXPECT_TRUE(strands);
  SolverSettings settings;
  settings.constraintIterations = 1;
  settings.tethers = tethers;
  auto hair = HairSystem::create(*strands, settings);
  EXPECT_TRUE(hair);
  Reach worst;
  for (int frame = 1; frame <= 120; ++frame) {
    // ±0.3 m at 3 Hz sideways (peak acceleration ≈ 100 m/s², ten g) plus ±1 rad of yaw at 2 Hz.
    const double t = frame / 60.0;
    const float sway = static_cast<float>(0.3 * std::sin(2.0 * 3.14159265358979 * 3.0 * t));
    const float yaw = static_cast<float>(1.0 * std::sin(2.0 * 3.14159265358979 * 2.0 * t));
    glm::mat4 head = glm::translate(glm::mat4(1.0f), glm::vec3(sway, 0.0f, 0.0f));
    head = glm::rotate(head, yaw, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_TRUE(hair->setHeadTransform(head));
    EXPECT_TRUE(hair->advance(1.0 / 60.0, 1));
    for (std::size_t s = 0; s < hair->strandCount(); ++s) {
      const auto x = hair->strandPositions(s);
      const auto reach = hair->strandRestDistances(s);
      for (std::size_t i = 1; i < x.size(); ++i) {
        worst.ratio = std::max(worst.ratio, distance(x[0], x[i]) / reach[i]);
        worst.excess = std::max(worst.excess, distance(x[0], x[i]) - reach[i]);
      }
    }
  }
  return worst;
}

TEST(Tether, NoParticleEverExceedsItsRestDistanceFromTheRootDuringAViolentShake) {
  // Control: without tethers the same shake stretches the strands visibly (> 1 %), so the
  // scenario is violent enough to test something.
  const Reach loose = worstReachDuringShake(false);
  EXPECT_GT(loose.ratio, 1.01f);
  // With tethers every sweep ends with each particle inside its sphere; the only slack left is
  // the rounding of one projection and of the distance measured here, a few ulps of the
  // coordinates (|x| < 1 m, ulp ≤ 1.2e-7 m): allowed 1e-6 m.
  const Reach tethered = worstReachDuringShake(true);
  EXPECT_LE(tethered.excess, 1e-6f);
  RecordProperty("worst_reach_ratio_without_tethers", std::to_string(loose.ratio));
  RecordProperty("worst_excess_m_with_tethers", std::to_string(tethered.excess));
}

TEST(Pin, PinnedParticlesSitOnTheirTargets) {
  SolverSettings settings;
  auto solver = ParticleSolver::create(settings);
  ASSERT_TRUE(solver);
  solver->particles.add({0.0f, 0.0f, 0.0f}, 0.0f);
  solver->particles.add({0.1f, 0.0f, 0.0f}, 1.0f);
  solver->distances.push_back({0, 1, 0.1f});
  solver->pins.push_back({0, {0.5f, 1.0f, 0.0f}});
  for (int n = 0; n < 10; ++n) solver->step();
  EXPECT_EQ(solver->particles.positions[0], glm::vec3(0.5f, 1.0f, 0.0f));
  EXPECT_NEAR(distance(solver->particles.positions[0], solver->particles.positions[1]), 0.1f, 1e-6f);
}

}  // namespace
}  // namespace mane::physics
