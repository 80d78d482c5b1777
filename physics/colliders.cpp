#include "physics/colliders.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/common.hpp>

namespace mane::physics {

namespace {

float dot(const glm::vec3& a, const glm::vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
float length(const glm::vec3& v) {
  return std::sqrt(dot(v, v));
}
bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Closest point to `p` on the segment ab (Ericson 2005, §5.1.2).
glm::vec3 closestOnSegment(const glm::vec3& a, const glm::vec3& b, const glm::vec3& p) {
  const glm::vec3 ab = b - a;
  const float lengthSquared = dot(ab, ab);
  if (!(lengthSquared > 0.0f)) return a;
  const float t = std::clamp(dot(p - a, ab) / lengthSquared, 0.0f, 1.0f);
  return a + ab * t;
}

// Coulomb friction after a contact whose outward unit normal is `normal` and whose penetration
// was `depth` (Macklin et al. 2014, §6.1, eq. 24 with a static body and μs = μk = μ): the
// tangential part of the displacement since `previous` is shortened by μ·depth, or removed.
void applyFriction(glm::vec3& position, const glm::vec3& previous, const glm::vec3& normal, float depth, float mu) {
  if (!(mu > 0.0f)) return;
  const glm::vec3 displacement = position - previous;
  const glm::vec3 tangential = displacement - normal * dot(displacement, normal);
  const float slide = length(tangential);
  if (!(slide > 0.0f)) return;
  const float stop = mu * depth;
  position -= stop >= slide ? tangential : tangential * (stop / slide);
}

// Pushes `position` out of the ball (centre, reach) along the radius; returns the depth.
float pushOutOfBall(glm::vec3& position, const glm::vec3& centre, float reach, glm::vec3& normal) {
  const glm::vec3 offset = position - centre;
  const float distanceSquared = dot(offset, offset);
  if (!(distanceSquared < reach * reach)) return 0.0f;
  const float distance = std::sqrt(distanceSquared);
  // A particle exactly at the centre has no outward direction; +Y is an arbitrary fixed choice.
  normal = distance > 0.0f ? offset / distance : glm::vec3(0.0f, 1.0f, 0.0f);
  position = centre + normal * reach;
  return reach - distance;
}

}  // namespace

Result<void> validateColliders(const ColliderSet& colliders) {
  for (std::size_t i = 0; i < colliders.spheres.size(); ++i) {
    const SphereCollider& s = colliders.spheres[i];
    if (!isFinite(s.centre) || !(std::isfinite(s.radius) && s.radius > 0.0f))
      return fail("Colliders: sphere " + std::to_string(i) + " needs a finite centre and a radius > 0 m (got " +
                  std::to_string(s.radius) + ").");
  }
  for (std::size_t i = 0; i < colliders.capsules.size(); ++i) {
    const CapsuleCollider& c = colliders.capsules[i];
    if (!isFinite(c.a) || !isFinite(c.b) || !(std::isfinite(c.radius) && c.radius > 0.0f))
      return fail("Colliders: capsule " + std::to_string(i) + " needs finite ends and a radius > 0 m (got " +
                  std::to_string(c.radius) + ").");
  }
  if (!(std::isfinite(colliders.friction) && colliders.friction >= 0.0f))
    return fail("Colliders: friction must be a finite coefficient ≥ 0, got " + std::to_string(colliders.friction) +
                ".");
  if (!(std::isfinite(colliders.thickness) && colliders.thickness >= 0.0f))
    return fail("Colliders: thickness must be finite and ≥ 0 m, got " + std::to_string(colliders.thickness) + ".");
  return {};
}

float signedDistance(const SphereCollider& sphere, const glm::vec3& p) noexcept {
  return length(p - sphere.centre) - sphere.radius;
}

float signedDistance(const CapsuleCollider& capsule, const glm::vec3& p) noexcept {
  return length(p - closestOnSegment(capsule.a, capsule.b, p)) - capsule.radius;
}

float signedDistance(const ColliderSet& colliders, const glm::vec3& p) noexcept {
  float nearest = std::numeric_limits<float>::infinity();
  for (const SphereCollider& s : colliders.spheres) nearest = std::min(nearest, signedDistance(s, p));
  for (const CapsuleCollider& c : colliders.capsules) nearest = std::min(nearest, signedDistance(c, p));
  if (colliders.sdf) nearest = std::min(nearest, colliders.sdf->sample(p));
  return nearest;
}

ColliderBounds boundingSphere(const ColliderSet& colliders) noexcept {
  if (colliders.empty()) return {};
  glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  const auto grow = [&](const glm::vec3& centre, float radius) {
    lo = glm::min(lo, centre - glm::vec3(radius));
    hi = glm::max(hi, centre + glm::vec3(radius));
  };
  for (const SphereCollider& s : colliders.spheres) grow(s.centre, s.radius);
  for (const CapsuleCollider& c : colliders.capsules) grow(c.a, c.radius), grow(c.b, c.radius);
  if (colliders.sdf) grow(colliders.sdf->origin(), 0.0f), grow(colliders.sdf->upperCorner(), 0.0f);
  const glm::vec3 centre = (lo + hi) * 0.5f;
  // Rounding margin: a particle just outside the ball by rounding must still be tested.
  return {centre, length(hi - centre) * 1.0001f + colliders.thickness + 1e-6f};
}

ColliderCull cullBoxes(const ColliderSet& colliders) {
  // 1e-4 m: far above the rounding of any distance computed here at head scale (≈ 1e-7 m).
  constexpr float kMargin = 1e-4f;
  ColliderCull cull;
  const float grow = colliders.thickness + kMargin;
  const auto add = [&](const glm::vec3& lo, const glm::vec3& hi) {
    cull.lower.push_back(lo);
    cull.upper.push_back(hi);
  };
  for (const SphereCollider& s : colliders.spheres)
    add(s.centre - glm::vec3(s.radius + grow), s.centre + glm::vec3(s.radius + grow));
  for (const CapsuleCollider& c : colliders.capsules)
    add(glm::min(c.a, c.b) - glm::vec3(c.radius + grow), glm::max(c.a, c.b) + glm::vec3(c.radius + grow));
  cull.shapeBoxes = cull.lower.size();
  if (colliders.sdf) {
    const SignedDistanceField& f = *colliders.sdf;
    if (colliders.thickness < f.contactLevel() - 1e-6f) {
      if (f.contactLower().x <= f.contactUpper().x) add(f.contactLower(), f.contactUpper());
    } else {
      constexpr float kInf = std::numeric_limits<float>::infinity();
      add(glm::vec3(-kInf), glm::vec3(kInf));
    }
  }
  return cull;
}

bool collideParticle(const ColliderSet& colliders, glm::vec3& position, const glm::vec3& previous,
                     float friction) noexcept {
  const float mu = friction;
  const float thickness = colliders.thickness;
  bool touched = false;
  // The field is often sampled again exactly where it was last sampled (after friction that did
  // not move the particle, in the next round when no other shape moved it): reuse that sample,
  // bit for bit what sampling again would return (the same point, byte for byte).
  glm::vec3 sampledAt(0.0f), sampledGradient(0.0f);
  float sampledValue = 0.0f;
  bool sampled = false;
  const auto sampleField = [&](glm::vec3& gradient) {
    if (!(sampled && std::memcmp(&sampledAt, &position, sizeof position) == 0)) {
      sampledValue = colliders.sdf->sampleWithGradient(position, sampledGradient);
      sampledAt = position;
      sampled = true;
    }
    gradient = sampledGradient;
    return sampledValue;
  };
  for (int round = 0; round < kCollisionRounds; ++round) {
    bool contact = false;
    glm::vec3 normal;
    for (const SphereCollider& s : colliders.spheres)
      if (const float depth = pushOutOfBall(position, s.centre, s.radius + thickness, normal); depth > 0.0f) {
        applyFriction(position, previous, normal, depth, mu);  // a tangential step stays outside a ball
        contact = true;
      }
    for (const CapsuleCollider& c : colliders.capsules) {
      const glm::vec3 axis = closestOnSegment(c.a, c.b, position);
      if (const float depth = pushOutOfBall(position, axis, c.radius + thickness, normal); depth > 0.0f) {
        applyFriction(position, previous, normal, depth, mu);  // ... and outside a convex capsule
        contact = true;
      }
    }
    glm::vec3 gradient;
    float d;  // sampleWithGradient's value is bit for bit sample's
    if (colliders.sdf && colliders.sdf->mayBeBelow(position, thickness) && (d = sampleField(gradient)) < thickness) {
      // A Newton step along the field's gradient onto the level set thickness + kContactSkin,
      // then friction, then Newton steps until the particle is out (the trilinear field is
      // smooth inside a cell, so one or two steps land there; the sample after friction checks
      // the first step too). Aiming just past the contact level lets the loop and the next
      // round end at once: aiming at it exactly lands half the time a rounding error inside,
      // which is another contact.
      const float target = thickness + kContactSkin;
      const float depth = thickness - d;
      const float gradientSquared = dot(gradient, gradient);
      if (gradientSquared > 1e-12f) {
        normal = gradient / std::sqrt(gradientSquared);
        position += gradient * ((target - d) / gradientSquared);
        applyFriction(position, previous, normal, depth, mu);
        d = sampleField(gradient);
        for (int newton = 0; newton < 4 && d < thickness; ++newton) {
          const float g2 = dot(gradient, gradient);
          if (!(g2 > 1e-12f)) break;
          position += gradient * ((target - d) / g2);
          d = sampleField(gradient);
        }
        contact = true;
      }
    }
    if (!contact) break;
    touched = true;
  }
  return touched;
}

}  // namespace mane::physics
