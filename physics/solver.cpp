#include "physics/solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

namespace mane::physics {

namespace {

// A frame of exactly n fixed steps (1/60 s at 1/120 s) must give n steps even though
// 1/60 − 1/120 − 1/120 is not exactly zero in binary floating point. Treating a remainder within
// this fraction of a step as a whole step makes such frames split as a person expects; the
// rule depends only on the inputs, so it stays deterministic.
constexpr double kWholeStepTolerance = 1e-9;

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Result<void> validateSettings(const SolverSettings& settings) {
  if (!(std::isfinite(settings.fixedStep) && settings.fixedStep > 0.0))
    return fail("Solver settings: fixedStep must be a positive number of seconds, got " +
                std::to_string(settings.fixedStep) + ".");
  if (!isFinite(settings.gravity)) return fail("Solver settings: gravity must be finite (m/s²).");
  if (!(settings.damping >= 0.0f && settings.damping < 1.0f))
    return fail("Solver settings: damping must lie in [0, 1), got " + std::to_string(settings.damping) + ".");
  if (settings.constraintIterations < 1)
    return fail("Solver settings: constraintIterations must be at least 1, got " +
                std::to_string(settings.constraintIterations) + ".");
  if (settings.maxSubstepsPerFrame < 1)
    return fail("Solver settings: maxSubstepsPerFrame must be at least 1, got " +
                std::to_string(settings.maxSubstepsPerFrame) + ".");
  if (!(settings.shapeStiffness >= 0.0f && settings.shapeStiffness <= 1.0f))
    return fail("Solver settings: shapeStiffness must lie in [0, 1], got " + std::to_string(settings.shapeStiffness) +
                ".");
  if (!(settings.maxSpeed > 0.0f))
    return fail("Solver settings: maxSpeed must be a positive speed in m/s (or +infinity for no clamp), got " +
                std::to_string(settings.maxSpeed) + ".");
  return {};
}

float StepPlan::fractionAt(int k) const {
  assert(k >= 1 && k <= substeps);
  if (clamped || !(frameDt > 0.0)) return static_cast<float>(static_cast<double>(k) / static_cast<double>(substeps));
  const double fraction = (static_cast<double>(k) * fixedStep - backlog) / frameDt;
  return static_cast<float>(std::clamp(fraction, 0.0, 1.0));
}

FixedStepAccumulator::FixedStepAccumulator(double fixedStep, int maxSubsteps)
    : fixedStep_(fixedStep), maxSubsteps_(maxSubsteps) {
  assert(fixedStep > 0.0 && maxSubsteps >= 1);
}

StepPlan FixedStepAccumulator::plan(double frameDt) {
  assert(std::isfinite(frameDt) && frameDt >= 0.0);
  StepPlan plan;
  plan.fixedStep = fixedStep_;
  plan.frameDt = frameDt;
  plan.backlog = backlog_;

  const double available = backlog_ + frameDt;
  const double whole = std::floor(available / fixedStep_ + kWholeStepTolerance);
  if (whole > static_cast<double>(maxSubsteps_)) {
    plan.substeps = maxSubsteps_;
    plan.clamped = true;
    backlog_ = 0.0;  // drop the rest: see SolverSettings::maxSubstepsPerFrame
  } else {
    plan.substeps = static_cast<int>(whole);
    backlog_ = std::max(0.0, available - whole * fixedStep_);
  }
  stepsTaken_ += static_cast<std::uint64_t>(plan.substeps);
  return plan;
}

void integrateVerlet(Particles& particles, std::size_t first, std::size_t count, const glm::vec3& acceleration,
                     float damping, float step) {
  assert(first + count <= particles.size());
  glm::vec3* x = particles.positions.data() + first;
  glm::vec3* previous = particles.previousPositions.data() + first;
  const float* inverseMass = particles.inverseMasses.data() + first;
  const float keep = 1.0f - damping;
  const glm::vec3 kick = acceleration * (step * step);
  for (std::size_t i = 0; i < count; ++i) {
    if (inverseMass[i] <= 0.0f) continue;
    const glm::vec3 current = x[i];
    x[i] = verletPosition(current, previous[i], keep, kick);
    previous[i] = current;
  }
}

}  // namespace mane::physics
