#pragma once
// Collision shapes for particles — spheres, capsules and a signed distance field (sdf.hpp) —
// and the position-based contact response: a particle found inside a shape is moved to its
// surface along the outward normal (Müller, Heidelberger, Hennix & Ratcliff 2007, "Position
// Based Dynamics", §3.5 and §4.4: inequality collision constraints projected on the positions),
// then Coulomb friction removes tangential motion (Macklin, Müller, Chentanez & Kim 2014,
// "Unified Particle Physics for Real-Time Applications", §6.1, eq. 24): the tangential
// displacement since the previous position, Δx⊥, shrinks by μ·d (d the penetration depth) and
// vanishes when it is shorter than that (static friction, with μs = μk = μ).
//
// Shapes are described in the frame of the body that carries them (for hair: head-local space;
// the hair system transforms particles into that frame each step). Units: metres.
// Everything that runs in the step here is allocation- and exception-free.

#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/sdf.hpp"

namespace mane::physics {

/// A solid ball.
struct SphereCollider {
  glm::vec3 centre{0.0f};  ///< metres, in the body's frame
  float radius = 0.0f;     ///< metres, > 0
};

/// A solid capsule: all points within `radius` of the segment from `a` to `b` (a neck, a limb).
struct CapsuleCollider {
  glm::vec3 a{0.0f};    ///< one end of the axis, metres, in the body's frame
  glm::vec3 b{0.0f};    ///< other end of the axis, metres (may equal `a`: a sphere)
  float radius = 0.0f;  ///< metres, > 0
};

/// Everything a particle collides with on one body: plain data, cheap to copy (the field is
/// shared, immutable).
struct ColliderSet {
  std::vector<SphereCollider> spheres;
  std::vector<CapsuleCollider> capsules;
  /// Optional signed distance field (e.g. of the head mesh), in the body's frame.
  std::shared_ptr<const SignedDistanceField> sdf;
  /// Coulomb friction coefficient μ ≥ 0, dimensionless (0: frictionless sliding).
  float friction = 0.0f;
  /// Particles are kept at least this far outside every surface, metres ≥ 0 (a strand's radius).
  float thickness = 0.0f;

  /// True when there is nothing to collide with.
  [[nodiscard]] bool empty() const noexcept { return spheres.empty() && capsules.empty() && !sdf; }
};

/// Checks that every radius is positive, every coordinate finite, friction and thickness finite
/// and ≥ 0; the message names the collider.
[[nodiscard]] Result<void> validateColliders(const ColliderSet& colliders);

/// Signed distance from `p` to the sphere's surface, metres (negative inside).
[[nodiscard]] float signedDistance(const SphereCollider& sphere, const glm::vec3& p) noexcept;
/// Signed distance from `p` to the capsule's surface, metres (negative inside).
[[nodiscard]] float signedDistance(const CapsuleCollider& capsule, const glm::vec3& p) noexcept;
/// Smallest signed distance from `p` to any collider of the set, metres (+∞ for an empty set).
/// `thickness` is not subtracted.
[[nodiscard]] float signedDistance(const ColliderSet& colliders, const glm::vec3& p) noexcept;

/// A ball that contains every collider of a set (with its thickness): particles outside it
/// cannot touch any of them.
struct ColliderBounds {
  glm::vec3 centre{0.0f};  ///< metres, in the body's frame
  float radius = -1.0f;    ///< metres; negative when the set is empty
};

/// The bounding ball of a set (around the box that holds every shape, grown by the thickness).
[[nodiscard]] ColliderBounds boundingSphere(const ColliderSet& colliders) noexcept;

/// Axis-aligned boxes (in the set's frame) around each collider of a set, grown by its thickness
/// and a rounding margin; for the SDF, its contact box (sdf.hpp) when the thickness allows. A
/// particle outside every box touches nothing: `collideParticle` would leave it as it is.
struct ColliderCull {
  std::vector<glm::vec3> lower;  ///< per box, metres
  std::vector<glm::vec3> upper;  ///< per box, metres
  /// The first `shapeBoxes` boxes hold the spheres and capsules; the field's box, if any, follows.
  std::size_t shapeBoxes = 0;

  /// False only when `p` is outside every box.
  [[nodiscard]] bool mayTouch(const glm::vec3& p) const noexcept {
    for (std::size_t b = 0; b < lower.size(); ++b)
      if (p.x >= lower[b].x && p.y >= lower[b].y && p.z >= lower[b].z && p.x <= upper[b].x && p.y <= upper[b].y &&
          p.z <= upper[b].z)
        return true;
    return false;
  }
};

/// The cull boxes of a set.
[[nodiscard]] ColliderCull cullBoxes(const ColliderSet& colliders);

/// Resolves one particle against every collider of the set, in order: spheres, capsules, the
/// field; the whole sequence runs up to `kCollisionRounds` times while it still finds contacts,
/// since leaving one shape can push a particle into an overlapping one. Each contact moves
/// `position` to the surface (plus thickness) and applies friction with coefficient `friction`
/// against the displacement since `previous` (both in the set's frame; `previous` is the
/// position one step earlier; unused when `friction` is 0). Returns true when the particle
/// touched anything.
bool collideParticle(const ColliderSet& colliders, glm::vec3& position, const glm::vec3& previous,
                     float friction) noexcept;

/// `collideParticle` with the set's own friction coefficient.
inline bool collideParticle(const ColliderSet& colliders, glm::vec3& position, const glm::vec3& previous) noexcept {
  return collideParticle(colliders, position, previous, colliders.friction);
}

/// How many times `collideParticle` runs through the set at most.
inline constexpr int kCollisionRounds = 3;

/// How far past its contact level `collideParticle` moves a particle out of the field, metres:
/// far above the rounding of a field sample at body scale (about 1e-9 m), far below anything
/// visible.
inline constexpr float kContactSkin = 1e-6f;

}  // namespace mane::physics
