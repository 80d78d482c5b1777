#include "physics/hair.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <system_error>
#include <thread>

#include <glm/vec4.hpp>

#include "physics/constraints.hpp"
#include "physics/detail/strand_lanes.hpp"
#include "physics/hash.hpp"

namespace mane::physics {

namespace {

constexpr std::uint32_t kNoFault = std::numeric_limits<std::uint32_t>::max();

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

std::string describe(const glm::vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", static_cast<double>(v.x), static_cast<double>(v.y),
                static_cast<double>(v.z));
  return text;
}

Result<void> checkTransform(const glm::mat4& m, const char* what) {
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(m[column][row]))
        return fail(std::string("Hair system: ") + what + " has a non-finite entry at column " +
                    std::to_string(column) + ", row " + std::to_string(row) + ".");
  return {};
}

// Validates one input strand (index `s`): enough points, finite, no zero-length segments.
Result<void> validateStrand(std::size_t s, std::span<const glm::vec3> points) {
  if (points.size() < 2)
    return fail("Hair strand " + std::to_string(s) + " has " + std::to_string(points.size()) +
                " point(s); a guide strand needs at least 2 (a root and a tip).");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!isFinite(points[i]))
      return fail("Hair strand " + std::to_string(s) + ", particle " + std::to_string(i) +
                  " is not finite (NaN or infinite): " + describe(points[i]) + ".");
  for (std::size_t i = 1; i < points.size(); ++i) {
    const glm::vec3 d = points[i] - points[i - 1];
    const float length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    if (!std::isfinite(length))
      return fail("Hair strand " + std::to_string(s) + ", particle " + std::to_string(i) +
                  ": the segment from particle " + std::to_string(i - 1) +
                  " is too long to represent in single precision.");
    if (length < kMinSegmentLength)
      return fail("Hair strand " + std::to_string(s) + ", particle " + std::to_string(i) + " is " +
                  std::to_string(length) + " m from particle " + std::to_string(i - 1) +
                  " (zero-length segment); consecutive points must be at least " + std::to_string(kMinSegmentLength) +
                  " m apart.");
  }
  return {};
}

// Quaternions as (x, y, z, w). Only + − × ÷ and sqrt: no libm trigonometry in the step.
float dot4(const glm::vec4& a, const glm::vec4& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}

glm::vec4 normalized(const glm::vec4& q) {
  const float n = std::sqrt(dot4(q, q));
  return n > 0.0f ? q / n : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

// Rotation of a rigid transform as a unit quaternion (Shoemake 1985, "Animating Rotation with
// Quaternion Curves", the largest-diagonal branch for accuracy). Columns are normalised first so
// that a uniform scale does not leak in.
glm::vec4 rotationOf(const glm::mat4& transform) {
  glm::vec3 c[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = glm::vec3(transform[i]);
    const float n = std::sqrt(c[i].x * c[i].x + c[i].y * c[i].y + c[i].z * c[i].z);
    if (n > 0.0f) c[i] /= n;
  }
  // mRC: row R, column C.
  const float m00 = c[0].x, m10 = c[0].y, m20 = c[0].z, m01 = c[1].x, m11 = c[1].y, m21 = c[1].z;
  const float m02 = c[2].x, m12 = c[2].y, m22 = c[2].z;
  const float trace = m00 + m11 + m22;
  glm::vec4 q;
  if (trace > 0.0f) {
    const float s = std::sqrt(trace + 1.0f) * 2.0f;
    q = {(m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25f * s};
  } else if (m00 > m11 && m00 > m22) {
    const float s = std::sqrt(1.0f + m00 - m11 - m22) * 2.0f;
    q = {0.25f * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s};
  } else if (m11 > m22) {
    const float s = std::sqrt(1.0f + m11 - m00 - m22) * 2.0f;
    q = {(m01 + m10) / s, 0.25f * s, (m12 + m21) / s, (m02 - m20) / s};
  } else {
    const float s = std::sqrt(1.0f + m22 - m00 - m11) * 2.0f;
    q = {(m02 + m20) / s, (m12 + m21) / s, 0.25f * s, (m10 - m01) / s};
  }
  return normalized(q);
}

// Hamilton product a ⊗ b (apply b, then a).
glm::vec4 multiply(const glm::vec4& a, const glm::vec4& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

glm::vec3 cross(const glm::vec3& a, const glm::vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// v rotated by unit quaternion q: v + w·t + u × t with t = 2·(u × v).
glm::vec3 rotate(const glm::vec4& q, const glm::vec3& v) {
  const glm::vec3 u(q.x, q.y, q.z);
  const glm::vec3 t = cross(u, v) * 2.0f;
  return v + t * q.w + cross(u, t);
}

// The shortest-arc rotation taking direction a onto direction b, as a unit quaternion
// (|a||b| + a·b, a × b) normalised; identity when a and b are opposite or zero (no unique arc).
glm::vec4 shortestArc(const glm::vec3& a, const glm::vec3& b) {
  const float aa = a.x * a.x + a.y * a.y + a.z * a.z, bb = b.x * b.x + b.y * b.y + b.z * b.z;
  const glm::vec3 axis = cross(a, b);
  const float w = std::sqrt(aa * bb) + (a.x * b.x + a.y * b.y + a.z * b.z);
  const float n2 = w * w + axis.x * axis.x + axis.y * axis.y + axis.z * axis.z;
  if (!(n2 > 1e-12f * aa * bb)) return {0.0f, 0.0f, 0.0f, 1.0f};
  const float inverse = 1.0f / std::sqrt(n2);
  return {axis.x * inverse, axis.y * inverse, axis.z * inverse, w * inverse};
}

}  // namespace

HairSystem::HairSystem(const SolverSettings& settings)
    : settings_(settings), accumulator_(settings.fixedStep, settings.maxSubstepsPerFrame) {}

Result<HairSystem> HairSystem::create(std::span<const std::vector<glm::vec3>> strands, const SolverSettings& settings,
                                      const glm::mat4& headTransform) {
  if (auto valid = validateSettings(settings); !valid)
    return std::unexpected(Error{"Hair system: " + valid.error().message});
  if (auto valid = checkTransform(headTransform, "the initial head transform"); !valid)
    return std::unexpected(valid.error());
  if (strands.empty()) return fail("Hair groom is empty: no guide strands were given.");

  std::size_t total = 0;
  for (std::size_t s = 0; s < strands.size(); ++s) {
    if (auto valid = validateStrand(s, strands[s]); !valid) return std::unexpected(valid.error());
    total += strands[s].size();
  }
  if (total > std::numeric_limits<std::uint32_t>::max() - 1)
    return fail("Hair groom has " + std::to_string(total) + " particles; at most 2^32 − 2 fit.");

  HairSystem system(settings);
  system.particles_.reserve(total);
  system.restLocal_.reserve(total);
  system.segmentLengths_.reserve(total);
  system.restDistances_.reserve(total);
  system.strands_.reserve(strands.size());
  for (const std::vector<glm::vec3>& points : strands) {
    GuideStrand strand;
    strand.firstParticle = static_cast<std::uint32_t>(system.particles_.size());
    strand.particleCount = static_cast<std::uint32_t>(points.size());
    strand.rootLocal = points.front();
    float alongStrand = 0.0f;
    for (std::size_t i = 0; i < points.size(); ++i) {
      float segment = 0.0f;
      if (i > 0) {
        const glm::vec3 d = points[i] - points[i - 1];
        segment = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        alongStrand += segment;
      }
      // Roots have infinite mass (Jakobsen 2001, §3: "infinite mass" particles are moved only by
      // the animation); every other particle weighs the same, 1 kg, as only mass ratios matter.
      system.particles_.add(points[i], i == 0 ? 0.0f : 1.0f);
      system.restLocal_.push_back(points[i]);
      system.segmentLengths_.push_back(segment);
      system.restDistances_.push_back(alongStrand);
    }
    system.strands_.push_back(strand);
  }
  system.faultParticle_.assign(strands.size(), kNoFault);
  system.faultStep_.assign(strands.size(), 0);
  system.placeAtRest(headTransform);
  return system;
}

void HairSystem::placeAtRest(const glm::mat4& headTransform) {
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    particles_.positions[i] = transformPoint(headTransform, restLocal_[i]);
    particles_.previousPositions[i] = particles_.positions[i];
  }
  previousHead_ = headTransform;
  head_ = headTransform;
}

Result<void> HairSystem::setHeadTransform(const glm::mat4& headTransform) {
  if (auto valid = checkTransform(headTransform, "the head transform"); !valid) return valid;
  head_ = headTransform;
  return {};
}

Result<void> HairSystem::setColliders(ColliderSet colliders) {
  if (auto valid = validateColliders(colliders); !valid)
    return std::unexpected(Error{"Hair system: " + valid.error().message});
  colliderBounds_ = boundingSphere(colliders);
  colliderCull_ = cullBoxes(colliders);
  colliders_ = std::move(colliders);
  return {};
}

Result<void> HairSystem::setWind(const WindSettings& wind) {
  if (auto valid = validateWind(wind); !valid) return std::unexpected(Error{"Hair system: " + valid.error().message});
  wind_.emplace(wind);
  return {};
}

std::optional<WindSettings> HairSystem::wind() const {
  if (!wind_) return std::nullopt;
  return wind_->settings();
}

bool HairSystem::vectorised() const noexcept {
  return vectorise_ && detail::cpuHasAvx2() && !wind_ && !(settings_.shapeStiffness > 0.0f);
}

void HairSystem::planPoses(const StepPlan& plan) {
  const glm::vec4 from = rotationOf(previousHead_);
  glm::vec4 to = rotationOf(head_);
  if (dot4(from, to) < 0.0f) to = -to;  // the shorter way round
  const glm::vec3 start(previousHead_[3]), travel = glm::vec3(head_[3]) - start;
  poses_.resize(static_cast<std::size_t>(plan.substeps) + 1);
  for (int k = 0; k <= plan.substeps; ++k) {
    const float f = k == 0 ? 0.0f : plan.fractionAt(k);
    HeadPose& pose = poses_[static_cast<std::size_t>(k)];
    pose.rotation = normalized(from * (1.0f - f) + to * f);
    pose.axes[0] = rotate(pose.rotation, {1.0f, 0.0f, 0.0f});
    pose.axes[1] = rotate(pose.rotation, {0.0f, 1.0f, 0.0f});
    pose.axes[2] = rotate(pose.rotation, {0.0f, 0.0f, 1.0f});
    pose.translation = start + travel * f;  // as the roots move
  }
}

Result<void> HairSystem::teleport(const glm::mat4& headTransform) {
  if (auto valid = checkTransform(headTransform, "the teleport transform"); !valid) return valid;
  placeAtRest(headTransform);
  std::fill(faultParticle_.begin(), faultParticle_.end(), kNoFault);
  fault_.reset();
  return {};
}

std::span<const glm::vec3> HairSystem::strandPositions(std::size_t strand) const {
  assert(strand < strands_.size());
  return {particles_.positions.data() + strands_[strand].firstParticle, strands_[strand].particleCount};
}

std::span<const float> HairSystem::strandRestDistances(std::size_t strand) const {
  assert(strand < strands_.size());
  return {restDistances_.data() + strands_[strand].firstParticle, strands_[strand].particleCount};
}

double HairSystem::simulatedTime() const noexcept {
  return static_cast<double>(accumulator_.stepsTaken()) * settings_.fixedStep;
}

Error HairSystem::faultError() const {
  assert(fault_);
  const double time = static_cast<double>(fault_->step) * settings_.fixedStep;
  return Error{"Hair strand " + std::to_string(fault_->strand) + ", particle " + std::to_string(fault_->particle) +
               " became non-finite (NaN or infinite) at fixed step " + std::to_string(fault_->step) + " (t = " +
               std::to_string(time) + " s); the hair system has stopped advancing until teleport() resets it."};
}

Result<void> HairSystem::advance(double frameDt, unsigned threads) {
  if (fault_) return std::unexpected(faultError());
  if (!(std::isfinite(frameDt) && frameDt >= 0.0))
    return fail("Hair system: frame duration must be a finite number of seconds ≥ 0, got " + std::to_string(frameDt) +
                ".");

  const StepPlan plan = accumulator_.plan(frameDt);
  if (plan.substeps > 0) {
    if (!colliders_.empty() || settings_.shapeStiffness > 0.0f) planPoses(plan);
    // A fixed partition into contiguous ranges of whole strands. Each strand's arithmetic is the
    // same whichever worker runs it, so the partition affects speed only, never the result.
    const std::size_t workers = std::clamp<std::size_t>(threads == 0 ? 1 : threads, 1, strands_.size());
    const auto rangeBegin = [&](std::size_t w) { return strands_.size() * w / workers; };
    std::vector<std::jthread> pool;
    pool.reserve(workers - 1);
    std::size_t inlineFrom = workers;  // ranges the calling thread runs itself
    for (std::size_t w = 1; w < workers; ++w) {
      try {
        pool.emplace_back([this, &plan, b = rangeBegin(w), e = rangeBegin(w + 1)] { simulateStrands(b, e, plan); });
      } catch (const std::system_error&) {
        inlineFrom = w;  // no more threads available: run the remaining ranges here
        break;
      }
    }
    simulateStrands(rangeBegin(0), rangeBegin(1), plan);
    if (inlineFrom < workers) simulateStrands(rangeBegin(inlineFrom), strands_.size(), plan);
    pool.clear();  // joins

    // Lowest strand index first, so the report does not depend on which worker saw it first.
    for (std::size_t s = 0; s < strands_.size(); ++s) {
      if (faultParticle_[s] == kNoFault) continue;
      fault_ = SimulationFault{s, faultParticle_[s], faultStep_[s]};
      break;
    }
  }
  previousHead_ = head_;
  if (fault_) return std::unexpected(faultError());
  return {};
}

void HairSystem::simulateStrands(std::size_t firstStrand, std::size_t endStrand, const StepPlan& plan) {
  if (vectorised()) {
    std::vector<float> scratch;  // once per worker and frame, reused by every block
    for (std::size_t s = firstStrand; s < endStrand; s += detail::kBlockLanes)
      simulateStrandBlockLanes(s, std::min(detail::kBlockLanes, endStrand - s), plan, scratch);
    return;
  }
  for (std::size_t s = firstStrand; s < endStrand; s += kStrandLanes)
    simulateStrandBlock(s, std::min(kStrandLanes, endStrand - s), plan);
}

namespace {

glm::vec3 toHeadLocal(const glm::vec3 (&axes)[3], const glm::vec3& translation, const glm::vec3& world) {
  const glm::vec3 d = world - translation;
  return glm::vec3(axes[0].x * d.x + axes[0].y * d.y + axes[0].z * d.z, axes[1].x * d.x + axes[1].y * d.y + axes[1].z * d.z,
                   axes[2].x * d.x + axes[2].y * d.y + axes[2].z * d.z);
}

glm::vec3 toWorld(const glm::vec3 (&axes)[3], const glm::vec3& translation, const glm::vec3& local) {
  return axes[0] * local.x + axes[1] * local.y + axes[2] * local.z + translation;
}

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

void HairSystem::settlePoint(const HeadPose& pose, glm::vec3& x, const glm::vec3& root, const glm::vec3& parent,
                             float reach) const noexcept {
  collidePoint(pose, pose, x, x, 0.0f);
  if (!settings_.tethers) return;
  const float limit = (reach + kSettleSlack) * (reach + kSettleSlack);
  if (!(distanceSquared(x, root) > limit)) return;
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
  // They did not meet (a crease between colliders): the parent satisfies both conditions (it
  // was settled first and its tether is shorter), so keep the farthest point found by bisection
  // on the segment from the parent towards p for which both hold.
  const auto clear = [&](const glm::vec3& q) {
    return !(distanceSquared(q, root) > limit) &&
           signedDistance(colliders_, toHeadLocal(pose.axes, pose.translation, q)) >=
               colliders_.thickness - kSettleSlack;
  };
  float good = 0.0f, bad = 1.0f;
  for (int halving = 0; halving < 12; ++halving) {
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
    const glm::vec3 rootFrom = transformPoint(previousHead_, strand.rootLocal);
    lane[b] = Lane{particles_.positions.data() + first,
                   particles_.previousPositions.data() + first,
                   particles_.inverseMasses.data() + first,
                   segmentLengths_.data() + first,
                   restDistances_.data() + first,
                   restLocal_.data() + first,
                   strand.particleCount,
                   rootFrom,
                   transformPoint(head_, strand.rootLocal) - rootFrom,
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

  const auto collideLanes = [&](int k, float friction) {
    const HeadPose& pose = poses_[static_cast<std::size_t>(k)];
    const HeadPose& before = poses_[static_cast<std::size_t>(k - 1)];
    for (std::size_t b = 0; b < lanes; ++b) {
      const Lane& l = lane[b];
      if (!l.active) continue;
      for (std::size_t i = 1; i < l.count; ++i)
        if (l.w[i] > 0.0f) collidePoint(pose, before, l.x[i], l.previous[i], friction);
    }
  };
  // The step's final pass against colliders and tethers, root → tip (class comment, item 4).
  const auto settleLanes = [&](int k) {
    const HeadPose& pose = poses_[static_cast<std::size_t>(k)];
    for (std::size_t b = 0; b < lanes; ++b) {
      const Lane& l = lane[b];
      if (!l.active) continue;
      for (std::size_t i = 1; i < l.count; ++i)
        if (l.w[i] > 0.0f) settlePoint(pose, l.x[i], l.x[0], l.x[i - 1], l.reach[i]);
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
          const glm::vec3 drag = windAcceleration(wind_->velocityAt(current, time), velocity, axis,
                                                  wind_->settings().dragPerSecond);
          x[i] = verletPosition(current, previous[i], keep, (settings_.gravity + drag) * (step * step));
          previous[i] = current;
        }
        parent = current;
      }
    }

    // Contacts of the predicted positions, with friction (Macklin et al. 2014, §6.1), before the
    // constraints so that the strand's constraints see the contact.
    if (collide) collideLanes(k, colliders_.friction);

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
        for (std::size_t b = 0; b < lanes; ++b) frame[b] = poses_[static_cast<std::size_t>(k)].rotation;
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

    // Final pass: whatever the constraints pushed into a collider comes out, frictionless,
    // without breaking the tethers, so no particle ends the step inside a collider or stretched.
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

// The AVX2 path. The strands of the block are copied into lane-by-lane scratch storage (so a
// register holds one coordinate of 8 strands), stepped with the kernels of
// detail/strand_lanes.hpp — the same operations per strand and in the same order as
// simulateStrandBlock — and copied back. Collisions, the final settling pass, the velocity
// clamp and the fault check run per particle on the same storage with the same code as the
// scalar path. Only without shape constraints and wind (see vectorised()).
void HairSystem::simulateStrandBlockLanes(std::size_t firstStrand, std::size_t lanes, const StepPlan& plan,
                                          std::vector<float>& scratch) {
#if MANE_STRAND_LANES_AVX2
  constexpr std::size_t W = detail::kBlockLanes;
  std::size_t longest = 0;
  for (std::size_t b = 0; b < lanes; ++b) longest = std::max<std::size_t>(longest, strands_[firstStrand + b].particleCount);
  const std::size_t n = longest * W;
  scratch.resize(9 * n + W);
  float* base = scratch.data();
  float *x = base, *y = base + n, *z = base + 2 * n, *px = base + 3 * n, *py = base + 4 * n, *pz = base + 5 * n;
  float *w = base + 6 * n, *segment = base + 7 * n, *reach = base + 8 * n;
  std::int32_t count[W] = {};
  glm::vec3 rootFrom[W], rootTravel[W];
  std::fill(w, w + 3 * n, 0.0f);
  for (std::size_t b = 0; b < lanes; ++b) {
    const GuideStrand& strand = strands_[firstStrand + b];
    const std::size_t first = strand.firstParticle;
    count[b] = static_cast<std::int32_t>(strand.particleCount);
    rootFrom[b] = transformPoint(previousHead_, strand.rootLocal);
    rootTravel[b] = transformPoint(head_, strand.rootLocal) - rootFrom[b];
    for (std::size_t i = 0; i < strand.particleCount; ++i) {
      const std::size_t at = i * W + b;
      const glm::vec3 p = particles_.positions[first + i], q = particles_.previousPositions[first + i];
      x[at] = p.x, y[at] = p.y, z[at] = p.z, px[at] = q.x, py[at] = q.y, pz[at] = q.z;
      w[at] = particles_.inverseMasses[first + i];
      segment[at] = segmentLengths_[first + i];
      reach[at] = restDistances_[first + i];
    }
  }
  const detail::StrandLanes block{x, y, z, px, py, pz, w, segment, reach, count, longest};
  const auto get = [&](const float* cx, const float* cy, const float* cz, std::size_t at) {
    return glm::vec3(cx[at], cy[at], cz[at]);
  };
  const auto put = [&](float* cx, float* cy, float* cz, std::size_t at, const glm::vec3& v) {
    cx[at] = v.x, cy[at] = v.y, cz[at] = v.z;
  };

  const float step = static_cast<float>(plan.fixedStep);
  const float keep = 1.0f - settings_.damping;
  const glm::vec3 kick = settings_.gravity * (step * step);
  const std::uint64_t stepsBefore = accumulator_.stepsTaken() - static_cast<std::uint64_t>(plan.substeps);
  const bool collide = !colliders_.empty();
  const bool clampSpeed = settings_.maxSpeed < std::numeric_limits<float>::infinity();
  const float maxDisplacement = settings_.maxSpeed * step;

  for (int k = 1; k <= plan.substeps; ++k) {
    const float fraction = plan.fractionAt(k);
    for (std::size_t b = 0; b < lanes; ++b) {
      if (count[b] == 0) continue;
      put(px, py, pz, b, get(x, y, z, b));
      put(x, y, z, b, rootFrom[b] + rootTravel[b] * fraction);
    }
    detail::integrateAvx2(block, keep, kick);

    const HeadPose* pose = collide ? &poses_[static_cast<std::size_t>(k)] : nullptr;
    if (collide) {
      const HeadPose& before = poses_[static_cast<std::size_t>(k - 1)];
      for (std::size_t i = 1; i < longest; ++i)
        for (std::size_t b = 0; b < lanes; ++b) {
          const std::size_t at = i * W + b;
          if (static_cast<std::int32_t>(i) >= count[b] || w[at] <= 0.0f) continue;
          glm::vec3 p = get(x, y, z, at);
          if (collidePoint(*pose, before, p, get(px, py, pz, at), colliders_.friction)) put(x, y, z, at, p);
        }
    }

    for (int iteration = 0; iteration < settings_.constraintIterations; ++iteration) {
      detail::relaxDistancesAvx2(block);
      if (settings_.tethers) detail::tethersAvx2(block);
    }

    if (collide)
      for (std::size_t b = 0; b < lanes; ++b)
        for (std::size_t i = 1; i < static_cast<std::size_t>(count[b]); ++i) {
          const std::size_t at = i * W + b;
          if (w[at] <= 0.0f) continue;
          glm::vec3 p = get(x, y, z, at);
          settlePoint(*pose, p, get(x, y, z, b), get(x, y, z, at - W), reach[at]);
          put(x, y, z, at, p);
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

    for (std::size_t b = 0; b < lanes; ++b) {
      const auto particles = static_cast<std::size_t>(count[b]);
      if (particles == 0) continue;
      float probe = 0.0f;
      for (std::size_t i = 0; i < particles; ++i) probe += 0.0f * x[i * W + b] + 0.0f * y[i * W + b] + 0.0f * z[i * W + b];
      if (probe != 0.0f) {
        std::size_t bad = 0;
        while (bad < particles && isFinite(get(x, y, z, bad * W + b))) ++bad;
        faultParticle_[firstStrand + b] = static_cast<std::uint32_t>(std::min(bad, particles - 1));
        faultStep_[firstStrand + b] = stepsBefore + static_cast<std::uint64_t>(k);
        count[b] = 0;  // the strand stops where it is
      }
    }
  }

  for (std::size_t b = 0; b < lanes; ++b) {
    const GuideStrand& strand = strands_[firstStrand + b];
    for (std::size_t i = 0; i < strand.particleCount; ++i) {
      const std::size_t at = i * W + b;
      particles_.positions[strand.firstParticle + i] = get(x, y, z, at);
      particles_.previousPositions[strand.firstParticle + i] = get(px, py, pz, at);
    }
  }
#else
  (void)scratch;
  for (std::size_t s = firstStrand; s < firstStrand + lanes; s += kStrandLanes)
    simulateStrandBlock(s, std::min(kStrandLanes, firstStrand + lanes - s), plan);
#endif
}

std::uint64_t HairSystem::stateHash() const noexcept {
  StateHasher hasher;
  hasher.add(std::span<const glm::vec3>(particles_.positions));
  hasher.add(std::span<const glm::vec3>(particles_.previousPositions));
  const double backlog = accumulator_.backlog();
  const std::uint64_t steps = accumulator_.stepsTaken();
  hasher.addValue(backlog);
  hasher.addValue(steps);
  return hasher.value();
}

}  // namespace mane::physics
