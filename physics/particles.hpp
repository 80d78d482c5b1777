#pragma once
// Particle storage for the Verlet solver: structure of arrays, one entry per particle.
//
// Position Verlet (Jakobsen 2001, "Advanced Character Physics", §2) keeps no velocity: the
// velocity is implied by the current and previous positions, so the state of a particle is
// exactly (position, previous position, inverse mass).

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace mane::physics {

/// Index of a particle inside a `Particles` store.
using ParticleIndex = std::uint32_t;

/// Structure-of-arrays particle state. All three arrays always have the same length.
///
/// - `positions`: current positions, metres, in the simulation (world) frame.
/// - `previousPositions`: positions one fixed step earlier, metres. `position − previous` is the
///   displacement over the last step, i.e. velocity × step.
/// - `inverseMasses`: 1 / mass, 1/kg. Zero marks a kinematic particle (infinite mass): the
///   integrator and the constraints never move it; only pins or the owner (e.g. a head
///   transform) place it.
struct Particles {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> previousPositions;
  std::vector<float> inverseMasses;

  /// Number of particles.
  [[nodiscard]] std::size_t size() const noexcept { return positions.size(); }

  /// True when there are no particles.
  [[nodiscard]] bool empty() const noexcept { return positions.empty(); }

  /// Reserves room for `count` particles in every array.
  void reserve(std::size_t count) {
    positions.reserve(count);
    previousPositions.reserve(count);
    inverseMasses.reserve(count);
  }

  /// Appends a particle at rest at `position` (metres) with `inverseMass` (1/kg, 0 = kinematic)
  /// and returns its index.
  ParticleIndex add(const glm::vec3& position, float inverseMass) {
    assert(inverseMass >= 0.0f);
    positions.push_back(position);
    previousPositions.push_back(position);
    inverseMasses.push_back(inverseMass);
    return static_cast<ParticleIndex>(positions.size() - 1);
  }

  /// Appends a particle at `position` moving with `velocity` (m/s) for a solver stepping with
  /// `step` seconds under constant acceleration `acceleration` (m/s²). The previous position is
  /// the exact trajectory x(t) = x0 + v0·t + ½·a·t² evaluated at t = −step, so that position
  /// Verlet without damping reproduces that trajectory at every step (up to rounding).
  ParticleIndex addMoving(const glm::vec3& position, const glm::vec3& velocity, float step,
                          const glm::vec3& acceleration, float inverseMass) {
    const ParticleIndex index = add(position, inverseMass);
    previousPositions[index] = position - velocity * step + acceleration * (0.5f * step * step);
    return index;
  }
};

}  // namespace mane::physics
