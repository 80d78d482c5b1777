#include "tests/support/particle_solver.hpp"

#include <cstddef>
#include <limits>

namespace mane::testing {

ParticleSolver::ParticleSolver(const physics::SolverSettings& settings)
    : settings_(settings), accumulator_(settings.fixedStep, settings.maxSubstepsPerFrame) {}

Result<ParticleSolver> ParticleSolver::create(const physics::SolverSettings& settings) {
  if (auto valid = physics::validateSettings(settings); !valid) return std::unexpected(valid.error());
  return ParticleSolver(settings);
}

void ParticleSolver::step() {
  physics::integrateVerlet(particles, 0, particles.size(), settings_.gravity, settings_.damping,
                           static_cast<float>(settings_.fixedStep));
  if (!colliders.empty())  // contacts of the predicted positions, with friction
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (particles.inverseMasses[i] > 0.0f)
        physics::collideParticle(colliders, particles.positions[i], particles.previousPositions[i]);
  for (int iteration = 0; iteration < settings_.constraintIterations; ++iteration) {
    physics::applyPins(particles, pins);
    physics::solveDistanceConstraints(particles, distances);
    if (settings_.tethers) physics::solveTethers(particles, tethers);
  }
  if (!colliders.empty())  // frictionless: what the constraints pushed in comes out
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (particles.inverseMasses[i] > 0.0f)
        physics::collideParticle(colliders, particles.positions[i], particles.previousPositions[i], 0.0f);
  if (settings_.maxSpeed < std::numeric_limits<float>::infinity()) {
    const float reach = settings_.maxSpeed * static_cast<float>(settings_.fixedStep);
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (particles.inverseMasses[i] > 0.0f)
        physics::clampDisplacement(particles.positions[i], particles.previousPositions[i], reach);
  }
}

int ParticleSolver::advance(double frameDt) {
  const physics::StepPlan plan = accumulator_.plan(frameDt);
  for (int k = 0; k < plan.substeps; ++k) step();
  return plan.substeps;
}

}  // namespace mane::testing
