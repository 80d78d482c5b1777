#pragma once
// What every simulated body shares: the solver settings, the fixed-step accumulator and the
// position-Verlet integrator. Hair (`hair.hpp`) and cloth (`cloth.hpp`) step with them and with
// the constraint functions of `constraints.hpp`.
//
// Determinism: results depend only on the settings, the initial state and the sequence of frame
// durations handed to `advance`, never on wall-clock time or thread count
// (docs/design.md#determinism).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/particles.hpp"

namespace mane::physics {

/// Shared settings of the Verlet solver. Plain data: copy it, keep it in a scene file.
struct SolverSettings {
  /// Length of one fixed simulation step, seconds. Frames are split into whole steps of this.
  double fixedStep = 1.0 / 120.0;
  /// Constant acceleration applied to every non-kinematic particle, m/s² (+Y is up).
  glm::vec3 gravity{0.0f, -9.81f, 0.0f};
  /// Velocity damping d per fixed step, dimensionless in [0, 1): the implied velocity is scaled
  /// by (1 − d) every step (Jakobsen 2001, §2 with a drag term). Because it acts per step, the
  /// same d damps more per second at a smaller fixed step.
  float damping = 0.01f;
  /// Constraint relaxation sweeps per fixed step (Jakobsen 2001, §3). More sweeps = stiffer.
  int constraintIterations = 4;
  /// Most fixed steps run for one frame; time beyond that is dropped so that a long frame (a
  /// hitch, a breakpoint) cannot make the next frame even longer ("spiral of death").
  int maxSubstepsPerFrame = 8;
  /// Whether systems that define long-range attachments (hair: every particle to its root)
  /// enforce them. They guarantee no stretch beyond rest length at any iteration count.
  bool tethers = true;
  /// Local shape (bending) stiffness in [0, 1], dimensionless: the fraction of the gap between a
  /// strand particle and its rest position in its parent segment's frame that each constraint
  /// iteration closes (Han & Harada 2012, local shape constraints; see HairSystem). 0 disables
  /// it. Per iteration, so the same value is stiffer with more iterations (Müller et al. 2007, §3.3).
  /// 1 holds strands rigid in the head's frame. Use 0 or ≥ 0.4: the frames follow the strand, so
  /// the constraint is not conservative, and low values (measured 0.05–0.2) let curls flutter.
  float shapeStiffness = 0.0f;
  /// Largest speed a particle keeps into the next step, m/s (> 0; +∞, the default, disables the
  /// clamp). Applied at the end of each step to the implied velocity (x − x_prev)/h by moving
  /// x_prev, so positions, constraints and collisions are untouched.
  float maxSpeed = std::numeric_limits<float>::infinity();
};

/// Checks that `settings` are usable: a positive finite fixed step, finite gravity, damping in
/// [0, 1), at least one constraint iteration and at least one substep per frame, shape stiffness
/// in [0, 1] and a positive (possibly infinite) maximum speed.
[[nodiscard]] Result<void> validateSettings(const SolverSettings& settings);

/// What one frame turns into: a whole number of fixed steps, and where each of them falls
/// inside the frame (for interpolating kinematic targets such as hair roots).
struct StepPlan {
  int substeps = 0;        ///< fixed steps to run this frame
  double fixedStep = 0.0;  ///< seconds per step
  double frameDt = 0.0;    ///< the frame's duration, seconds
  double backlog = 0.0;    ///< seconds the simulation lagged the frame's start by
  bool clamped = false;    ///< true when time was dropped to respect the substep limit

  /// Where fixed step `k` (1-based, 1..substeps) ends inside the frame, as a fraction in (0, 1]
  /// of the frame: 0 is the previous frame's end, 1 this frame's end. Step k ends at
  /// k·fixedStep − backlog seconds after the previous frame's end. When time was dropped the
  /// steps are spread evenly (k / substeps), so kinematic targets still arrive on time.
  [[nodiscard]] float fractionAt(int k) const;
};

/// Turns arbitrary frame durations into whole fixed steps (Fiedler, "Fix Your Timestep!").
/// The leftover (less than one step) carries over to the next frame, so the simulated time
/// tracks the sum of frame durations exactly except where the substep limit drops time.
class FixedStepAccumulator {
public:
  /// `fixedStep` in seconds (> 0); `maxSubsteps` ≥ 1.
  FixedStepAccumulator(double fixedStep, int maxSubsteps);

  /// Adds a frame of `frameDt` seconds (finite, ≥ 0) and returns the steps to run for it.
  [[nodiscard]] StepPlan plan(double frameDt);

  /// Seconds accumulated but not yet simulated (0 ≤ backlog < fixed step).
  [[nodiscard]] double backlog() const noexcept { return backlog_; }

  /// Total fixed steps handed out so far.
  [[nodiscard]] std::uint64_t stepsTaken() const noexcept { return stepsTaken_; }

private:
  double fixedStep_;
  int maxSubsteps_;
  double backlog_ = 0.0;
  std::uint64_t stepsTaken_ = 0;
};

/// One position-Verlet update (Jakobsen 2001, eq. 1 with drag): the new position
/// x + (1 − d)(x − x_prev) + a·h², given `keep` = 1 − d and `kick` = a·h² (metres). Shared by
/// every integrator in the module so that they agree to the bit.
inline glm::vec3 verletPosition(const glm::vec3& current, const glm::vec3& previous, float keep,
                                const glm::vec3& kick) {
  return current + (current - previous) * keep + kick;
}

/// Velocity clamp: when the displacement over the last step, x − x_prev, is longer than
/// `maxDisplacement` (metres; max speed × step), moves `previous` so that it is exactly that long,
/// keeping its direction. Positions are not moved.
inline void clampDisplacement(const glm::vec3& position, glm::vec3& previous, float maxDisplacement) {
  const glm::vec3 d = position - previous;
  const float lengthSquared = d.x * d.x + d.y * d.y + d.z * d.z;
  if (!(lengthSquared > maxDisplacement * maxDisplacement)) return;
  previous = position - d * (maxDisplacement / std::sqrt(lengthSquared));
}

/// Position Verlet with damping for particles [first, first + count) (Jakobsen 2001, eq. 1 with
/// drag): x' = x + (1 − d)(x − x_prev) + a·h², x_prev' = x. Kinematic particles (inverse mass
/// 0) are left untouched. `step` h in seconds, `acceleration` a in m/s², `damping` d per step.
void integrateVerlet(Particles& particles, std::size_t first, std::size_t count, const glm::vec3& acceleration,
                     float damping, float step);

}  // namespace mane::physics
