#pragma once
// A general particle system for tests: particles joined by distance constraints, tethers and
// pins, stepped one after another with the physics module's own integrator and constraint
// functions. The analytic tests (free fall, pendulum, catenary) check those functions through it,
// and the hair tests hold HairSystem's strand kernel against it bit for bit. The engine itself
// simulates with HairSystem and Cloth.

#include <vector>

#include "common/error.hpp"
#include "physics/colliders.hpp"
#include "physics/constraints.hpp"
#include "physics/particles.hpp"
#include "physics/solver.hpp"

namespace mane::testing {

/// Step order (Jakobsen 2001): Verlet integration, collisions against `colliders` (world space,
/// static) with friction, then `constraintIterations` sweeps of pins → distance constraints →
/// tethers (tethers last so each sweep ends stretch-free), then collisions again without
/// friction (so that no particle ends a step inside a collider), then the velocity clamp
/// (`SolverSettings::maxSpeed`). The shape stiffness applies to hair only.
class ParticleSolver {
public:
  /// Creates an empty system; fails when `settings` do not pass `physics::validateSettings`.
  [[nodiscard]] static Result<ParticleSolver> create(const physics::SolverSettings& settings);

  /// Runs one fixed step of `settings().fixedStep` seconds.
  void step();

  /// Advances by a frame of `frameDt` seconds (finite, ≥ 0) in whole fixed steps; returns how
  /// many were run.
  int advance(double frameDt);

  /// The settings this system was created with.
  [[nodiscard]] const physics::SolverSettings& settings() const noexcept { return settings_; }

  physics::Particles particles;                        ///< the simulated state
  std::vector<physics::DistanceConstraint> distances;  ///< relaxed in order every sweep
  std::vector<physics::Tether> tethers;                ///< enforced after the distances every sweep
  std::vector<physics::Pin> pins;                      ///< applied first every sweep
  physics::ColliderSet colliders;                      ///< world space; resolved after the sweeps

private:
  explicit ParticleSolver(const physics::SolverSettings& settings);

  physics::SolverSettings settings_;
  physics::FixedStepAccumulator accumulator_;
};

}  // namespace mane::testing
