#pragma once
// Position-based constraints relaxed one at a time (Gauss–Seidel), after Jakobsen 2001,
// "Advanced Character Physics", §3: each constraint moves its particles directly onto its rest
// configuration, weighted by inverse mass; repeating the sweep converges to a state that
// satisfies all of them at once.
//
// Every function here is allocation-free and exception-free: they run inside the step.

#include <cmath>
#include <cstddef>
#include <span>

#include <glm/vec3.hpp>

#include "physics/particles.hpp"

namespace mane::physics {

/// Keeps two particles at a fixed distance (a stick in Jakobsen's terms, a hair segment).
struct DistanceConstraint {
  ParticleIndex a = 0;      ///< first particle
  ParticleIndex b = 0;      ///< second particle
  float restLength = 0.0f;  ///< target distance, metres (> 0)
};

/// Long-range attachment (Kim, Chentanez & Müller 2012, "Long Range Attachments — A Method to
/// Simulate Inextensible Clothing in Computer Games", SCA): a one-sided constraint that keeps `particle` within
/// `maxDistance` of a kinematic `anchor` (the strand's root). `maxDistance` is the rest length measured along the
/// strand, so a strand can bend freely but can never stretch beyond its rest length, whatever the iteration count: the
/// anti-stretch guarantee behind fast head motion.
struct Tether {
  ParticleIndex particle = 0;  ///< the constrained particle (moved)
  ParticleIndex anchor = 0;    ///< the attachment point; treated as infinitely heavy (never moved)
  float maxDistance = 0.0f;    ///< largest allowed distance, metres
};

/// Places a particle exactly at a target position (a kinematic attachment: cloth corners,
/// chain ends). Pinned particles should have inverse mass 0 so other constraints leave them be.
struct Pin {
  ParticleIndex particle = 0;  ///< the pinned particle
  glm::vec3 target{0.0f};      ///< where it is held, metres
};

/// Relaxes one distance constraint between positions `pa` and `pb` with inverse masses `wa` and
/// `wb` (1/kg). Jakobsen 2001, §3: move both ends along their difference so that the distance
/// becomes `restLength`, each by its share wa/(wa+wb) resp. wb/(wa+wb) of the error. Does
/// nothing when both ends are kinematic or the particles coincide (no direction to push in).
inline void projectDistance(glm::vec3& pa, glm::vec3& pb, float wa, float wb, float restLength) {
  const float weightSum = wa + wb;
  if (weightSum <= 0.0f) return;
  const glm::vec3 delta = pb - pa;
  const float lengthSquared = delta.x * delta.x + delta.y * delta.y + delta.z * delta.z;
  if (!(lengthSquared > 0.0f)) return;
  const float length = std::sqrt(lengthSquared);
  // (|d| − L) / (|d| · (wa + wb)): the fraction of d that closes the error when scaled by w.
  const float scale = (length - restLength) / (length * weightSum);
  pa += delta * (wa * scale);
  pb -= delta * (wb * scale);
}

/// Enforces one tether: if `p` is farther than `maxDistance` from `anchor`, moves it radially
/// back onto the sphere of that radius. The anchor is not moved (long-range attachments hang
/// from a kinematic root; Kim, Chentanez & Müller 2012, §3).
inline void projectTether(glm::vec3& p, const glm::vec3& anchor, float maxDistance) {
  const glm::vec3 delta = p - anchor;
  const float lengthSquared = delta.x * delta.x + delta.y * delta.y + delta.z * delta.z;
  if (!(lengthSquared > maxDistance * maxDistance)) return;
  const float length = std::sqrt(lengthSquared);
  p = anchor + delta * (maxDistance / length);
}

/// Relaxes every distance constraint once, in order (one Gauss–Seidel sweep).
void solveDistanceConstraints(Particles& particles, std::span<const DistanceConstraint> constraints);

/// Enforces every tether once, in order. Applied after the distance sweep of an iteration so
/// that the iteration ends with no particle farther from its anchor than allowed.
void solveTethers(Particles& particles, std::span<const Tether> tethers);

/// Moves every pinned particle onto its target; the previous position is left alone, so a pin
/// that moves gives its particle a velocity (a kinematic drive).
void applyPins(Particles& particles, std::span<const Pin> pins);

/// Largest relative length error |(|pb − pa| − L)| / L over `constraints`; 0 when empty.
/// A diagnostic for tests and tuning, not used in the step.
[[nodiscard]] float maxRelativeStretch(const Particles& particles, std::span<const DistanceConstraint> constraints);

}  // namespace mane::physics
