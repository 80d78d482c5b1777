// A chain hung between two pinned points settles into a catenary, y = a·cosh(x/a) + c. The
// parameter a follows from the chain length S and the span D alone (ends at equal height):
// S = 2a·sinh(D / 2a), solved here by bisection. The simulated chain must lie within 1 % of
// the span of that curve at every particle.

#include <cmath>

#include <gtest/gtest.h>

#include "physics/solver.hpp"
#include "tests/support/particle_solver.hpp"

namespace mane::physics {
namespace {

using mane::testing::ParticleSolver;

// Solves S = 2a·sinh(D/(2a)) for a > 0. The left side falls monotonically from ∞ (a → 0) to
// D (a → ∞), so bisection on [1e-3·D, 1e3·D] converges for any S > D.
double catenaryParameter(double span, double length) {
  double lo = 1e-3 * span;
  double hi = 1e3 * span;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (2.0 * mid * std::sinh(span / (2.0 * mid)) > length)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(Catenary, HangingChainSettlesOntoTheCatenary) {
  constexpr int kLinks = 40;
  constexpr double kSpan = 1.5;    // m between the pins
  constexpr double kLength = 2.0;  // m of chain
  constexpr double kHeight = 1.0;  // m, height of both pins

  SolverSettings settings;
  settings.fixedStep = 1.0 / 240.0;
  settings.damping = 0.02f;  // settles in a few seconds; does not change the rest shape
  // A 40-link chain needs many Gauss–Seidel sweeps for the residual stretch to vanish
  // (convergence slows as links²); 200 keeps the stretch below 0.1 % at rest.
  settings.constraintIterations = 200;
  auto solver = ParticleSolver::create(settings);
  ASSERT_TRUE(solver);

  // Start straight between the pins (compressed: the links are longer than the spacing);
  // gravity makes it sag.
  for (int i = 0; i <= kLinks; ++i) {
    const float x = static_cast<float>(-0.5 * kSpan + kSpan * i / kLinks);
    const bool end = i == 0 || i == kLinks;
    solver->particles.add({x, static_cast<float>(kHeight), 0.0f}, end ? 0.0f : 1.0f);
  }
  const float rest = static_cast<float>(kLength / kLinks);
  for (int i = 0; i < kLinks; ++i)
    solver->distances.push_back({static_cast<ParticleIndex>(i), static_cast<ParticleIndex>(i + 1), rest});
  solver->pins.push_back({0, solver->particles.positions[0]});
  solver->pins.push_back({kLinks, solver->particles.positions[kLinks]});

  for (int n = 0; n < 240 * 4; ++n) solver->step();  // 4 s

  EXPECT_LT(maxRelativeStretch(solver->particles, solver->distances), 1e-3);
  const double a = catenaryParameter(kSpan, kLength);
  const double c = kHeight - a * std::cosh(0.5 * kSpan / a);
  double worst = 0.0;
  for (int i = 0; i <= kLinks; ++i) {
    const glm::vec3 p = solver->particles.positions[i];
    const double expected = a * std::cosh(p.x / a) + c;
    worst = std::max(worst, std::abs(p.y - expected));
    EXPECT_NEAR(p.y, expected, 0.01 * kSpan) << "particle " << i << " at x = " << p.x;
    EXPECT_NEAR(p.z, 0.0, 1e-6);
  }
  // Symmetric chain: the lowest point is in the middle at the catenary's vertex height a + c.
  EXPECT_NEAR(solver->particles.positions[kLinks / 2].x, 0.0, 0.01 * kSpan);
  RecordProperty("worst_deviation_m", std::to_string(worst));
}

}  // namespace
}  // namespace mane::physics
