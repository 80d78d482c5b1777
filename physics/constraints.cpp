#include "physics/constraints.hpp"

#include <algorithm>
#include <cmath>

namespace mane::physics {

void solveDistanceConstraints(Particles& particles, std::span<const DistanceConstraint> constraints) {
  glm::vec3* positions = particles.positions.data();
  const float* inverseMasses = particles.inverseMasses.data();
  for (const DistanceConstraint& c : constraints) {
    assert(c.a < particles.size() && c.b < particles.size());
    projectDistance(positions[c.a], positions[c.b], inverseMasses[c.a], inverseMasses[c.b], c.restLength);
  }
}

void solveTethers(Particles& particles, std::span<const Tether> tethers) {
  glm::vec3* positions = particles.positions.data();
  const float* inverseMasses = particles.inverseMasses.data();
  for (const Tether& t : tethers) {
    assert(t.particle < particles.size() && t.anchor < particles.size());
    if (inverseMasses[t.particle] <= 0.0f) continue;
    projectTether(positions[t.particle], positions[t.anchor], t.maxDistance);
  }
}

void applyPins(Particles& particles, std::span<const Pin> pins) {
  for (const Pin& pin : pins) {
    assert(pin.particle < particles.size());
    particles.positions[pin.particle] = pin.target;
  }
}

float maxRelativeStretch(const Particles& particles, std::span<const DistanceConstraint> constraints) {
  float worst = 0.0f;
  for (const DistanceConstraint& c : constraints) {
    const glm::vec3 d = particles.positions[c.b] - particles.positions[c.a];
    const float length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    worst = std::max(worst, std::abs(length - c.restLength) / c.restLength);
  }
  return worst;
}

}  // namespace mane::physics
