// The hair system's fixed step: per block of strands, Verlet, constraints, collisions
// (hair.hpp documents the order); a scalar path and an AVX2 path that gives the same bits.

#include <algorithm>
#include <cmath>

#include "physics/constraints.hpp"
#include "physics/detail/hair_math.hpp"
#include "physics/detail/collision_lanes.hpp"
#include "physics/detail/tether_lanes.hpp"
#include "physics/detail/hair_lanes.hpp"
#include "physics/detail/lane_transfer.hpp"
#include "physics/detail/strand_lanes.hpp"
#include "physics/detail/strand_lanes_avx512.hpp"
#include "physics/hair.hpp"

namespace mane::physics {

using namespace detail;

namespace {

glm::vec3 toHeadLocal(const glm::vec3 (&axes)[3], const glm::vec3& translation, const glm::vec3& world) {
  const glm::vec3 d = world - translation;
  return glm::vec3(axes[0].x * d.x + axes[0].y * d.y + axes[0].z * d.z,
                   axes[1].x * d.x + axes[1].y * d.y + axes[1].z * d.z,
                   axes[2].x * d.x + axes[2].y * d.y + axes[2].z * d.z);
}

glm::vec3 toWorld(const glm::vec3 (&axes)[3], const glm::vec3& translation, const glm::vec3& local) {
  return axes[0] * local.x + axes[1] * local.y + axes[2] * local.z + translation;
}

// Halvings of bisectTether's search (its AVX2 twin takes the same count).
constexpr int kTetherHalvings = 12;

float distanceSquared(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = a - b;
  return d.x * d.x + d.y * d.y + d.z * d.z;
}

}  // namespace

// Collisions in head-local space, where the colliders are fixed: x_local = Rᵀ(x − t) with the
// step's pose, the previous position with the step before's, so friction acts on the motion
// relative to the head (colliders.hpp). Particles outside the colliders' bounding ball are
// skipped: no collider can reach them.
bool HairSystem::collidePoint(const HeadPose& pose, const HeadPose& before, glm::vec3& x, const glm::vec3& previous,
                              float friction) const noexcept {
  const glm::vec3 centre = pose.axes[0] * colliderBounds_.centre.x + pose.axes[1] * colliderBounds_.centre.y +
                           pose.axes[2] * colliderBounds_.centre.z + pose.translation;
  const glm::vec3 offset = x - centre;
  if (offset.x * offset.x + offset.y * offset.y + offset.z * offset.z > colliderBounds_.radius * colliderBounds_.radius)
    return false;
  glm::vec3 local = toHeadLocal(pose.axes, pose.translation, x);
  if (!colliderCull_.mayTouch(local)) return false;  // collideParticle would find no contact
  const glm::vec3 previousLocal = friction > 0.0f ? toHeadLocal(before.axes, before.translation, previous) : local;
  if (!collideParticle(colliders_, local, previousLocal, friction)) return false;
  x = toWorld(pose.axes, pose.translation, local);
  return true;
}

void HairSystem::settlePoint(const HeadPose& pose, const HeadPose& before, glm::vec3& x, const glm::vec3& previous,
                             const glm::vec3& root, const glm::vec3& parent, float reach) const noexcept {
  collidePoint(pose, before, x, previous, colliders_.friction);
  if (!settings_.tethers) return;
  const float limit = (reach + kSettleSlack) * (reach + kSettleSlack);
  if (distanceSquared(x, root) > limit) settleTether(pose, x, root, parent, reach);
}

void HairSystem::settleTether(const HeadPose& pose, glm::vec3& x, const glm::vec3& root, const glm::vec3& parent,
                              float reach) const noexcept {
  const float limit = (reach + kSettleSlack) * (reach + kSettleSlack);
  // Beyond the tether after the push: alternate projections onto the tether ball (convex) and
  // out of the colliders; near a smooth surface they meet within a round or two.
  glm::vec3 p = x;
  for (int round = 0; round < kSettleRounds; ++round) {
    projectTether(p, root, reach);
    if (!collidePoint(pose, pose, p, p, 0.0f) || !(distanceSquared(p, root) > limit)) {
      x = p;
      return;
    }
  }
  // They did not meet: the nearest point to p within the tether, where that lies outside the
  // colliders if not by their whole thickness, before a search that may give up length. This is
  // the rule, not a rare crease, for particles lying over the convex scalp.
  glm::vec3 tethered = p;
  projectTether(tethered, root, reach);
  if (!(distanceSquared(tethered, root) > limit) &&
      signedDistance(colliders_, toHeadLocal(pose.axes, pose.translation, tethered)) >= 0.0f) {
    x = tethered;
    return;
  }
  bisectTether(pose, x, p, root, parent, reach);
}

// Neither the rounds nor p pulled back onto its tether met (a crease between colliders): the
// parent, settled first with a shorter tether, satisfies both conditions (unless it is a root
// inside the thickness), so keep the farthest point found by bisection on the segment from the
// parent towards p, the rounds' last point, for which both hold.
void HairSystem::bisectTether(const HeadPose& pose, glm::vec3& x, const glm::vec3& p, const glm::vec3& root,
                              const glm::vec3& parent, float reach) const noexcept {
  const float limit = (reach + kSettleSlack) * (reach + kSettleSlack);
  const auto clear = [&](const glm::vec3& q) {
    return !(distanceSquared(q, root) > limit) &&
           signedDistance(colliders_, toHeadLocal(pose.axes, pose.translation, q)) >=
               colliders_.thickness - kSettleSlack;
  };
  float good = 0.0f, bad = 1.0f;
  for (int halving = 0; halving < kTetherHalvings; ++halving) {
    const float middle = 0.5f * (good + bad);
    (clear(parent + (p - parent) * middle) ? good : bad) = middle;
  }
  x = parent + (p - parent) * good;
}

// Relaxing a strand is a chain of dependent sqrt and divide operations (each projection needs
// the previous one's result), so one strand at a time leaves the CPU waiting on latency. Up to
// kStrandLanes independent strands are therefore advanced side by side, their loops
// interleaved. Each strand still sees exactly the same operations in the same order as if it
// were simulated alone, so the grouping changes speed only, never a bit of the result.
void HairSystem::simulateStrandBlock(std::size_t firstStrand, std::size_t lanes, const StepPlan& plan) {
  struct Lane {
    glm::vec3* x;
    glm::vec3* previous;
    const float* w;
    const float* segment;
    const float* reach;
    const glm::vec3* rest;  // head-local rest positions
    std::size_t count;
    glm::vec3 rootFrom;
    glm::vec3 rootTravel;
    bool active;
  };
  Lane lane[kStrandLanes];
  std::size_t longest = 0;
  for (std::size_t b = 0; b < lanes; ++b) {
    const GuideStrand& strand = strands_[firstStrand + b];
    const std::size_t first = strand.firstParticle;
    glm::vec3 rootFrom, rootTravel;
    rootMotion(firstStrand + b, rootFrom, rootTravel);
    lane[b] = Lane{particles_.positions.data() + first,
                   particles_.previousPositions.data() + first,
                   particles_.inverseMasses.data() + first,
                   segmentLengths_.data() + first,
                   restDistances_.data() + first,
                   restLocal_.data() + first,
                   strand.particleCount,
                   rootFrom,
                   rootTravel,
                   true};
    longest = std::max(longest, lane[b].count);
  }
  const float step = static_cast<float>(plan.fixedStep);
  const float keep = 1.0f - settings_.damping;
  const glm::vec3 kick = settings_.gravity * (step * step);
  const std::uint64_t stepsBefore = accumulator_.stepsTaken() - static_cast<std::uint64_t>(plan.substeps);
  const float stiffness = settings_.shapeStiffness;
  const bool collide = !colliders_.empty();
  const bool clampSpeed = settings_.maxSpeed < std::numeric_limits<float>::infinity();
  const float maxDisplacement = settings_.maxSpeed * step;

  // The step's collision pass against colliders and tethers, root → tip (class comment, item 3).
  const auto settleLanes = [&](int k) {
    const HeadPose& pose = poses_[static_cast<std::size_t>(k)];
    const HeadPose& before = poses_[static_cast<std::size_t>(k - 1)];
    for (std::size_t b = 0; b < lanes; ++b) {
      const Lane& l = lane[b];
      if (!l.active) continue;
      for (std::size_t i = 1; i < l.count; ++i)
        if (l.w[i] > 0.0f) settlePoint(pose, before, l.x[i], l.previous[i], l.x[0], l.x[i - 1], l.reach[i]);
    }
  };
  const bool windy = wind_.has_value();

  for (int k = 1; k <= plan.substeps; ++k) {
    const float fraction = plan.fractionAt(k);
    for (std::size_t b = 0; b < lanes; ++b) {
      if (!lane[b].active) continue;
      glm::vec3* x = lane[b].x;
      glm::vec3* previous = lane[b].previous;
      // The root is kinematic: it sits where the head puts it at this step's time.
      previous[0] = x[0];
      x[0] = lane[b].rootFrom + lane[b].rootTravel * fraction;
      // Position Verlet with damping (Jakobsen 2001, §2), as integrateVerlet().
      if (!windy) {
        for (std::size_t i = 1; i < lane[b].count; ++i) {
          if (lane[b].w[i] <= 0.0f) continue;
          const glm::vec3 current = x[i];
          x[i] = verletPosition(current, previous[i], keep, kick);
          previous[i] = current;
        }
        continue;
      }
      // With wind: drag on each segment from the state at the start of the step (setWind).
      const double time = static_cast<double>(stepsBefore + static_cast<std::uint64_t>(k) - 1) * plan.fixedStep;
      glm::vec3 parent = previous[0];  // the root where it was at the start of the step
      for (std::size_t i = 1; i < lane[b].count; ++i) {
        const glm::vec3 current = x[i];
        if (lane[b].w[i] > 0.0f) {
          const glm::vec3 segment = current - parent;
          const float length = std::sqrt(segment.x * segment.x + segment.y * segment.y + segment.z * segment.z);
          const glm::vec3 axis = length > 0.0f ? segment / length : glm::vec3(0.0f);
          const glm::vec3 velocity = (current - previous[i]) / step;
          const glm::vec3 drag =
              windAcceleration(wind_->velocityAt(current, time), velocity, axis, wind_->settings().dragPerSecond);
          x[i] = verletPosition(current, previous[i], keep, (settings_.gravity + drag) * (step * step));
          previous[i] = current;
        }
        parent = current;
      }
    }

    for (int iteration = 0; iteration < settings_.constraintIterations; ++iteration) {
      // Local shape constraints (Han & Harada 2012, "Real-time Hair Simulation with Efficient
      // Hair Style Preservation", VRIPHYS, §4.2; TressFX's LocalShapeConstraints): a frame is
      // carried from the root (the head's orientation) to the tip; particle i is pulled towards
      // x[i−1] + F·(rest[i] − rest[i−1]), F the frame of its parent segment, by `stiffness` of
      // the gap. Only the child moves, as in follow-the-leader (Müller, Kim & Chentanez 2012,
      // "Fast Simulation of Inextensible Hair and Fur", §4): the parent is already placed by this
      // sweep, so stiffness 1 holds the strand rigid in the head's frame and the error cannot
      // flow back towards the root. F then turns by the shortest arc from the rest segment it
      // predicted onto the segment as it now is, so the frames follow the strand without twist.
      // The frames follow the deformation (a follower load), so the constraint is not
      // conservative: measured on curly grooms, stiffness ≥ 0.4 settles to the rest shape, while
      // 0.05–0.2 can flutter away from it even with strong damping (SolverSettings notes this).
      if (stiffness > 0.0f) {
        glm::vec4 frame[kStrandLanes];
        for (std::size_t b = 0; b < lanes; ++b) frame[b] = shapeFrame(firstStrand + b, k, fraction);
        for (std::size_t i = 1; i < longest; ++i)
          for (std::size_t b = 0; b < lanes; ++b) {
            const Lane& l = lane[b];
            if (!l.active || i >= l.count) continue;
            const glm::vec3 restSegment = rotate(frame[b], l.rest[i] - l.rest[i - 1]);
            if (l.w[i] > 0.0f) l.x[i] += (l.x[i - 1] + restSegment - l.x[i]) * stiffness;
            frame[b] = multiply(shortestArc(restSegment, l.x[i] - l.x[i - 1]), frame[b]);
          }
      }
      // Root to tip: the root's position reaches the tip within one sweep (Jakobsen 2001, §3).
      for (std::size_t i = 1; i < longest; ++i)
        for (std::size_t b = 0; b < lanes; ++b) {
          const Lane& l = lane[b];
          if (l.active && i < l.count) projectDistance(l.x[i - 1], l.x[i], l.w[i - 1], l.w[i], l.segment[i]);
        }
      // Long-range attachments last, so every sweep ends with no particle farther from the
      // root than its rest distance along the strand (Kim, Chentanez & Müller 2012).
      if (settings_.tethers)
        for (std::size_t i = 1; i < longest; ++i)
          for (std::size_t b = 0; b < lanes; ++b) {
            const Lane& l = lane[b];
            if (l.active && i < l.count) projectTether(l.x[i], l.x[0], l.reach[i]);
          }
    }

    // Collisions last: whatever gravity, inertia or the constraints put inside a collider comes
    // out, with friction (Macklin et al. 2014, §6.1), without breaking the tethers, so no
    // particle ends the step inside a collider or stretched.
    if (collide) settleLanes(k);

    if (clampSpeed)
      for (std::size_t b = 0; b < lanes; ++b) {
        if (!lane[b].active) continue;
        for (std::size_t i = 1; i < lane[b].count; ++i)
          if (lane[b].w[i] > 0.0f) clampDisplacement(lane[b].x[i], lane[b].previous[i], maxDisplacement);
      }

    for (std::size_t b = 0; b < lanes; ++b) {
      if (!lane[b].active) continue;
      const glm::vec3* x = lane[b].x;
      const std::size_t count = lane[b].count;
      // 0·v is 0 for every finite v and NaN for NaN or ±∞, so one sum tells whether any
      // coordinate of the strand went bad; find which one only when it did. A bad strand stops
      // where it is; the others carry on.
      float probe = 0.0f;
      for (std::size_t i = 0; i < count; ++i) probe += 0.0f * x[i].x + 0.0f * x[i].y + 0.0f * x[i].z;
      if (probe != 0.0f) {
        std::size_t bad = 0;
        while (bad < count && isFinite(x[bad])) ++bad;
        faultParticle_[firstStrand + b] = static_cast<std::uint32_t>(std::min(bad, count - 1));
        faultStep_[firstStrand + b] = stepsBefore + static_cast<std::uint64_t>(k);
        lane[b].active = false;
      }
    }
  }
}

// The AVX2 path. The strands' particles live lane by lane in laneState_ (so a register holds
// one coordinate of 8 strands; detail/lane_transfer.hpp), copied in only when something other
// than this path moved them; their constants are laid out that way once at creation
// (layOutBlockConstants). They are stepped with the kernels of detail/strand_lanes.hpp (the
// constraint sweeps with AVX-512 registers where the CPU has them, strand_lanes_avx512.hpp) —
// the same operations per strand and in the same order as HairSystem::simulateStrandBlock — and
// the positions are copied back to the particles' arrays after every frame, which also checks
// them for non-finite values after the frame's last step. The collision pass (settlePoint for
// every particle) runs in three sweeps over the block, with the same result: the pushes (each
// reads and writes only its own particle), packed 8 to a register from the whole block
// (collideBlockAvx2); then settleTether's rounds for those left beyond their tether, 8 at a time
// (they read only the particle and its root; repairTethersAvx2); then, root to tip, the few
// bisections, which read the parent's final position (bisectTethersAvx2). The velocity
// clamp runs per particle with the scalar path's code. Only without shape constraints and wind
// (see vectorised()).
void HairLaneKernel::simulateBlock(HairSystem& self, std::size_t firstStrand, std::size_t lanes,
                                   const StepPlan& plan, HairSystem::LaneFloats& scratch, bool intoPrevious) {
#if MANE_STRAND_LANES_AVX2
  constexpr std::size_t W = detail::kBlockLanes;
  // The block's constants are laid out once (layOutBlockConstants); its particles stay lane by
  // lane in laneState_ between steps, copied in only when something else moved them.
  const std::size_t blockIndex = firstStrand / W;
  const std::size_t longest = (self.blockConstantsAt_[blockIndex + 1] - self.blockConstantsAt_[blockIndex]) / (3 * W);
  const std::size_t n = longest * W;
  const float* w = self.blockConstants_.data() + self.blockConstantsAt_[blockIndex];
  const float *segment = w + n, *reach = w + 2 * n;
  const int iterations = self.settings_.constraintIterations;
  scratch.resize(n + W + detail::collideBlockStorage(longest) + detail::stepStorage(iterations) + 6 * W);
  float* unmetSlots = scratch.data() + W;  // the tether repairs left to bisection
  float* collisionWork = unmetSlots + n;   // collideBlockAvx2's lists
  float* stepWork = collisionWork + detail::collideBlockStorage(longest);  // stepAvx2's root copies
  float* rootFrom = stepWork + detail::stepStorage(iterations);  // x, y, z rows of W floats
  float* rootTravel = rootFrom + 3 * W;
  float* base = self.laneState_.data() + 2 * self.blockConstantsAt_[blockIndex];
  float *x = base, *y = base + n, *z = base + 2 * n, *px = base + 3 * n, *py = base + 4 * n, *pz = base + 5 * n;
  detail::LaneStrands where{};
  std::int32_t count[W] = {};
  for (std::size_t b = 0; b < lanes; ++b) {
    const GuideStrand& strand = self.strands_[firstStrand + b];
    where.first[b] = strand.firstParticle;
    where.count[b] = strand.particleCount;
    count[b] = static_cast<std::int32_t>(strand.particleCount);
  }
  const std::size_t groups = (lanes + detail::kSimdWidth - 1) / detail::kSimdWidth;
  // Where each root is at the frame's start and how far it moves by its end (rootMotion).
  if (self.rootTargets_.empty()) {
    const float* rootsLocal = self.blockRootsLocal_.data() + blockIndex * 3 * W;
    detail::transformRootsAvx2(self.previousHead_, rootsLocal, rootFrom, groups);
    detail::transformRootsAvx2(self.head_, rootsLocal, rootTravel, groups);
    for (std::size_t k = 0; k < 3 * W; ++k) rootTravel[k] -= rootFrom[k];
  } else {
    for (std::size_t b = 0; b < lanes; ++b) {
      glm::vec3 from, travel;
      self.rootMotion(firstStrand + b, from, travel);
      for (std::size_t c = 0; c < 3; ++c) rootFrom[c * W + b] = from[c], rootTravel[c * W + b] = travel[c];
    }
  }
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "positions are read as packed xyz floats");
  float* positions = &self.particles_.positions.data()->x;
  float* previous = &self.particles_.previousPositions.data()->x;
  if (!self.lanesCurrent_) detail::loadLanePositions(where, longest, groups, positions, previous, base);
  detail::StrandLanes block{x, y, z, px, py, pz, w, segment, reach, count, longest, groups};
  std::copy_n(self.blockPlainRows_.begin() + static_cast<std::ptrdiff_t>(blockIndex * detail::kSimdGroups),
              detail::kSimdGroups, block.plainRows);
  const auto get = [&](const float* cx, const float* cy, const float* cz, std::size_t at) {
    return glm::vec3(cx[at], cy[at], cz[at]);
  };
  const auto put = [&](float* cx, float* cy, float* cz, std::size_t at, const glm::vec3& v) {
    cx[at] = v.x, cy[at] = v.y, cz[at] = v.z;
  };

  const float step = static_cast<float>(plan.fixedStep);
  const float keep = 1.0f - self.settings_.damping;
  const glm::vec3 kick = self.settings_.gravity * (step * step);
  const std::uint64_t stepsBefore = self.accumulator_.stepsTaken() - static_cast<std::uint64_t>(plan.substeps);
  const bool collide = !self.colliders_.empty();
  const bool clampSpeed = self.settings_.maxSpeed < std::numeric_limits<float>::infinity();
  const float maxDisplacement = self.settings_.maxSpeed * step;
  // A strand with a non-finite coordinate after step k stops where it is; the others carry on.
  const auto stopFaulty = [&](const float (&probe)[W], int k) {
    for (std::size_t b = 0; b < lanes; ++b) {
      const auto particles = static_cast<std::size_t>(count[b]);
      if (particles == 0 || probe[b] == 0.0f) continue;
      std::size_t bad = 0;
      while (bad < particles && isFinite(get(x, y, z, bad * W + b))) ++bad;
      self.faultParticle_[firstStrand + b] = static_cast<std::uint32_t>(std::min(bad, particles - 1));
      self.faultStep_[firstStrand + b] = stepsBefore + static_cast<std::uint64_t>(k);
      count[b] = 0;
      detail::markPlainRows(block);
    }
  };

  for (int k = 1; k <= plan.substeps; ++k) {
    detail::placeRootsAvx2(block, rootFrom, rootTravel, plan.fractionAt(k));
    // Verlet, then the constraint sweeps, in one wavefront over the block (stepAvx2; the same
    // bits in fewer instructions with AVX-512).
    if (detail::cpuHasAvx512())
      detail::stepAvx512(block, keep, kick, iterations, self.settings_.tethers, stepWork);
    else
      detail::stepAvx2(block, keep, kick, iterations, self.settings_.tethers, stepWork);

    // settlePoint, 8 particles at a time: the push with friction, then the rare tether repair
    // one particle at a time. Each particle's parent is settled first, as in the scalar path.
    if (collide) {
      const HairSystem::HeadPose &pose = self.poses_[static_cast<std::size_t>(k)], &before = self.poses_[static_cast<std::size_t>(k - 1)];
      const detail::LaneColliders contacts{&self.colliders_,
                                           &self.colliderBounds_,
                                           &self.colliderCull_,
                                           {pose.axes, pose.translation},
                                           {before.axes, before.translation}};
      detail::collideBlockAvx2(contacts, block, self.colliders_.friction, collisionWork);
      if (self.settings_.tethers) {
        const std::size_t unmet = detail::repairTethersAvx2(contacts, block, HairSystem::kSettleRounds, HairSystem::kSettleSlack, unmetSlots);
        // Ascending: each parent is final before its child.
        detail::bisectTethersAvx2(contacts, block, kTetherHalvings, HairSystem::kSettleSlack, unmetSlots, unmet);
      }
    }

    if (clampSpeed)
      for (std::size_t b = 0; b < lanes; ++b)
        for (std::size_t i = 1; i < static_cast<std::size_t>(count[b]); ++i) {
          const std::size_t at = i * W + b;
          if (w[at] <= 0.0f) continue;
          glm::vec3 q = get(px, py, pz, at);
          clampDisplacement(get(x, y, z, at), q, maxDisplacement);
          put(px, py, pz, at, q);
        }

    if (k == plan.substeps) break;  // the write-back below checks the last step
    float probe[W] = {};
    detail::nonFiniteProbeAvx2(block, probe);
    stopFaulty(probe, k);
  }

  // After a single step whose previous positions are where the particles started, the previous
  // positions' array still holds them: the new positions go there and the caller swaps the two
  // arrays (advanceWith), instead of a second transposition.
  float probe[W] = {};
  if (intoPrevious)
    detail::storeLanePositions(where, longest, groups, base, previous, nullptr, probe);
  else
    detail::storeLanePositions(where, longest, groups, base, positions, previous, probe);
  stopFaulty(probe, plan.substeps);
#else
  (void)scratch, (void)intoPrevious;
  for (std::size_t s = firstStrand; s < firstStrand + lanes; s += HairSystem::kStrandLanes)
    self.simulateStrandBlock(s, std::min(HairSystem::kStrandLanes, firstStrand + lanes - s), plan);
#endif
}

}  // namespace mane::physics
