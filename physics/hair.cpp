#include "physics/hair.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <string>
#include <utility>

#include <glm/vec4.hpp>

#include "physics/constraints.hpp"
#include "physics/detail/hair_lanes.hpp"
#include "physics/detail/hair_math.hpp"
#include "physics/detail/parallel_tasks.hpp"
#include "physics/detail/strand_lanes.hpp"
#include "physics/hash.hpp"

namespace mane::physics {

using namespace detail;

namespace {

constexpr std::uint32_t kNoFault = std::numeric_limits<std::uint32_t>::max();

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

}  // namespace

HairSystem::HairSystem(const SolverSettings& settings)
    : settings_(settings), accumulator_(settings.fixedStep, settings.maxSubstepsPerFrame) {}

Result<HairSystem> HairSystem::create(std::span<const std::vector<glm::vec3>> strands, const SolverSettings& settings,
                                      const glm::mat4& headTransform) {
  HairSettings hair;
  hair.strands.assign(strands.begin(), strands.end());
  hair.solver = settings;
  hair.headTransform = headTransform;
  return create(hair);
}

Result<HairSystem> HairSystem::create(const HairSettings& hair) {
  // Every message starts with the settings field at fault.
  const auto inField = [](const char* field, const Error& error) {
    return std::unexpected(Error{std::string(field) + ": " + error.message});
  };
  const SolverSettings& settings = hair.solver;
  const std::span<const std::vector<glm::vec3>> strands = hair.strands;
  if (auto valid = validateSettings(settings); !valid) return inField("HairSettings.solver", valid.error());
  if (auto valid = checkTransform(hair.headTransform, "the initial head transform"); !valid)
    return inField("HairSettings.headTransform", valid.error());
  if (auto valid = validateTaskRunner(hair.tasks, "HairSettings.tasks"); !valid) return std::unexpected(valid.error());
  if (strands.empty()) return fail("HairSettings.strands: the hair groom is empty: no guide strands were given.");

  std::size_t total = 0;
  for (std::size_t s = 0; s < strands.size(); ++s) {
    if (auto valid = validateStrand(s, strands[s]); !valid) return inField("HairSettings.strands", valid.error());
    total += strands[s].size();
  }
  if (total > std::numeric_limits<std::uint32_t>::max() - 1)
    return fail("HairSettings.strands: the hair groom has " + std::to_string(total) +
                " particles; at most 2^32 − 2 fit.");

  HairSystem system(settings);
  system.tasks_ = hair.tasks;
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
  system.rootRestNormals_.reserve(strands.size());
  for (const std::vector<glm::vec3>& points : strands) {
    const glm::vec3 d = points[1] - points[0];  // validateStrand: at least kMinSegmentLength long
    system.rootRestNormals_.push_back(d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
  }
  system.faultParticle_.assign(strands.size(), kNoFault);
  system.faultStep_.assign(strands.size(), 0);
  system.layOutBlockConstants();
  system.placeAtRest(hair.headTransform);
  if (!hair.colliders.empty())
    if (auto set = system.setColliders(hair.colliders); !set) return inField("HairSettings.colliders", set.error());
  if (hair.wind)
    if (auto set = system.setWind(*hair.wind); !set) return inField("HairSettings.wind", set.error());
  if (!hair.rootRestNormals.empty())
    if (auto set = system.setRootRestNormals(hair.rootRestNormals); !set)
      return inField("HairSettings.rootRestNormals", set.error());
  system.setVectorised(hair.vectorised);
  return system;
}

Result<void> HairSystem::setTaskRunner(TaskRunner tasks) {
  if (auto valid = validateTaskRunner(tasks, "HairSystem::setTaskRunner: the runner"); !valid) return valid;
  tasks_ = std::move(tasks);
  return {};
}

void HairSystem::layOutBlockConstants() {
  constexpr std::size_t W = detail::kBlockLanes;
  const std::size_t blocks = (strands_.size() + W - 1) / W;
  blockConstants_.clear();
  blockConstantsAt_.assign(blocks + 1, 0);
  for (std::size_t k = 0; k < blocks; ++k) {
    const std::span<const GuideStrand> block(strands_.data() + k * W, std::min(W, strands_.size() - k * W));
    std::size_t rows = 0;
    for (const GuideStrand& strand : block) rows = std::max<std::size_t>(rows, strand.particleCount);
    const std::size_t at = blockConstants_.size(), n = rows * W;
    blockConstantsAt_[k] = at;
    blockConstants_.resize(at + 3 * n, 0.0f);  // rows past a strand's end: no mass, length 0
    float* lanes = blockConstants_.data() + at;
    for (std::size_t b = 0; b < block.size(); ++b)
      for (std::size_t i = 0; i < block[b].particleCount; ++i) {
        const std::size_t from = block[b].firstParticle + i;
        lanes[i * W + b] = particles_.inverseMasses[from];
        lanes[n + i * W + b] = segmentLengths_[from];
        lanes[2 * n + i * W + b] = restDistances_[from];
      }
  }
  blockConstantsAt_[blocks] = blockConstants_.size();

  blockPlainRows_.assign(blocks * detail::kSimdGroups, 0);
  allMoving_ = true;
  blockRootsLocal_.assign(blocks * 3 * W, 0.0f);
  for (std::size_t k = 0; k < blocks; ++k) {
    const std::size_t rows = (blockConstantsAt_[k + 1] - blockConstantsAt_[k]) / (3 * W);
    std::int32_t count[W] = {};
    for (std::size_t b = 0; b < W && k * W + b < strands_.size(); ++b)
      count[b] = static_cast<std::int32_t>(strands_[k * W + b].particleCount);
    const float* w = blockConstants_.data() + blockConstantsAt_[k];
    detail::StrandLanes lanes{};
    lanes.w = w;
    lanes.count = count;
    lanes.longest = rows;
    lanes.groups = (std::min(W, strands_.size() - k * W) + detail::kSimdWidth - 1) / detail::kSimdWidth;
    detail::markPlainRows(lanes);
    std::copy(std::begin(lanes.plainRows), std::end(lanes.plainRows), blockPlainRows_.begin() + k * detail::kSimdGroups);
    for (std::size_t b = 0; b < W; ++b)
      for (std::size_t i = 1; i < static_cast<std::size_t>(count[b]); ++i)
        if (!(w[i * W + b] > 0.0f)) allMoving_ = false;
    float* rootsLocal = blockRootsLocal_.data() + k * 3 * W;
    for (std::size_t b = 0; b < W && k * W + b < strands_.size(); ++b) {
      const glm::vec3& root = strands_[k * W + b].rootLocal;
      rootsLocal[b] = root.x, rootsLocal[W + b] = root.y, rootsLocal[2 * W + b] = root.z;
    }
  }
  laneState_.assign(2 * blockConstants_.size(), 0.0f);
  lanesCurrent_ = false;
}

void HairSystem::placeAtRest(const glm::mat4& headTransform) {
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    particles_.positions[i] = transformPoint(headTransform, restLocal_[i]);
    particles_.previousPositions[i] = particles_.positions[i];
  }
  lanesCurrent_ = false;
  previousHead_ = headTransform;
  head_ = headTransform;
  rootTargets_.clear();
  rootNormals_.clear();
  previousRootNormals_.clear();
}

namespace {

// Checks one normal per strand and writes them normalised to `unit` (resized; its storage is
// reused, as per-frame targets come every step); `what` names the list in errors.
Result<void> unitNormals(std::span<const glm::vec3> normals, std::size_t strands, const char* what,
                         std::vector<glm::vec3>& unit) {
  if (normals.size() != strands)
    return fail(std::string("Hair system: ") + what + " has " + std::to_string(normals.size()) + " normals for " +
                std::to_string(strands) + " strands.");
  unit.resize(normals.size());
  for (std::size_t s = 0; s < normals.size(); ++s) {
    const glm::vec3 n = normals[s];
    const float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!isFinite(n) || !(length >= 1e-6f))
      return fail(std::string("Hair system: ") + what + ", strand " + std::to_string(s) +
                  ": the normal must be finite and at least 1e-6 long, got (" + std::to_string(n.x) + ", " +
                  std::to_string(n.y) + ", " + std::to_string(n.z) + ").");
    unit[s] = n / length;
  }
  return {};
}

}  // namespace

Result<void> HairSystem::setRootTargets(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
  if (positions.size() != strands_.size())
    return fail("Hair system: root targets have " + std::to_string(positions.size()) + " positions for " +
                std::to_string(strands_.size()) + " strands.");
  for (std::size_t s = 0; s < positions.size(); ++s)
    if (!isFinite(positions[s]))
      return fail("Hair system: root target of strand " + std::to_string(s) + " is NaN or infinite.");
  if (auto unit = unitNormals(normals, strands_.size(), "root targets", pendingRootNormals_); !unit) return unit;
  if (rootTargets_.empty()) {
    // The first targets: the frame starts from the normals the head gives the roots now.
    previousRootNormals_.resize(strands_.size());
    const glm::vec4 rotation = rotationOf(previousHead_);
    for (std::size_t s = 0; s < strands_.size(); ++s) previousRootNormals_[s] = rotate(rotation, rootRestNormals_[s]);
  }
  rootTargets_.assign(positions.begin(), positions.end());
  std::swap(rootNormals_, pendingRootNormals_);
  return {};
}

Result<void> HairSystem::setRootRestNormals(std::span<const glm::vec3> normals) {
  std::vector<glm::vec3> unit;
  if (auto valid = unitNormals(normals, strands_.size(), "rest root normals", unit); !valid) return valid;
  rootRestNormals_ = std::move(unit);
  return {};
}

void HairSystem::rootMotion(std::size_t s, glm::vec3& from, glm::vec3& travel) const noexcept {
  const GuideStrand& strand = strands_[s];
  if (rootTargets_.empty()) {
    from = transformPoint(previousHead_, strand.rootLocal);
    travel = transformPoint(head_, strand.rootLocal) - from;
    return;
  }
  from = particles_.positions[strand.firstParticle];
  travel = rootTargets_[s] - from;
}

glm::vec4 HairSystem::shapeFrame(std::size_t s, int k, float f) const noexcept {
  const glm::vec4& head = poses_[static_cast<std::size_t>(k)].rotation;
  if (rootTargets_.empty()) return head;
  const glm::vec3 normal = previousRootNormals_[s] + (rootNormals_[s] - previousRootNormals_[s]) * f;
  return multiply(shortestArc(rotate(head, rootRestNormals_[s]), normal), head);
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

Result<void> HairSystem::setParticleState(std::span<const glm::vec3> positions,
                                          std::span<const glm::vec3> previousPositions) {
  const std::size_t count = particles_.size();
  const std::pair<std::span<const glm::vec3>, const char*> lists[] = {{positions, "positions"},
                                                                      {previousPositions, "previous positions"}};
  for (const auto& [list, name] : lists) {
    if (list.size() != count)
      return fail(std::string("Hair system: ") + name + " has " + std::to_string(list.size()) + " entries for " +
                  std::to_string(count) + " particles.");
    for (std::size_t i = 0; i < count; ++i)
      if (!isFinite(list[i]))
        return fail(std::string("Hair system: ") + name + " entry " + std::to_string(i) +
                    " is not finite (NaN or infinite): " + describe(list[i]) + ".");
  }
  std::copy(positions.begin(), positions.end(), particles_.positions.begin());
  std::copy(previousPositions.begin(), previousPositions.end(), particles_.previousPositions.begin());
  lanesCurrent_ = false;
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

Result<void> HairSystem::advance(double frameDt) {
  return advanceWith(frameDt, tasks_);
}

Result<void> HairSystem::advance(double frameDt, unsigned threads) {
  return advanceWith(frameDt, builtInTaskRunner(threads));
}

Result<void> HairSystem::advanceWith(double frameDt, const TaskRunner& tasks) {
  if (fault_) return std::unexpected(faultError());
  if (!(std::isfinite(frameDt) && frameDt >= 0.0))
    return fail("Hair system: frame duration must be a finite number of seconds ≥ 0, got " + std::to_string(frameDt) +
                ".");

  Result<void> ran;
  const StepPlan plan = accumulator_.plan(frameDt);
  if (plan.substeps > 0) {
    if (!colliders_.empty() || settings_.shapeStiffness > 0.0f) planPoses(plan);
    // Each task takes blocks of kBlockLanes whole strands from a shared counter, so the load
    // balances however the contacts are spread. Each strand's arithmetic is the same whichever
    // task runs it, so who runs which block affects speed only, never the result. Task t keeps
    // its lane storage in scratch_[t]: a task runs on one thread at a time.
    const std::uint32_t taskCount = taskCountFor(tasks, strands_.size());
    if (scratch_.size() < taskCount) scratch_.resize(taskCount);
    // After a single step with every particle but the roots moving and no velocity clamp, each
    // previous position is where the particle was at the step's start, which the positions'
    // array still holds: the AVX2 path then writes the new positions into the previous array and
    // the two trade places, instead of copying one array into the other.
    const bool intoPrevious = vectorised() && plan.substeps == 1 && allMoving_ &&
                              !(settings_.maxSpeed < std::numeric_limits<float>::infinity());
    std::atomic<std::size_t> nextBlock{0};
    auto task = [&](std::uint32_t t) { simulateStrands(nextBlock, plan, scratch_[t], intoPrevious); };
    ran = runTasks(tasks, taskCount, task);
    // Every block ran (a failing runner's leftovers run here), through the lanes or not.
    lanesCurrent_ = vectorised();
    if (intoPrevious) std::swap(particles_.positions, particles_.previousPositions);

    // Lowest strand index first, so the report does not depend on which worker saw it first.
    for (std::size_t s = 0; s < strands_.size(); ++s) {
      if (faultParticle_[s] == kNoFault) continue;
      fault_ = SimulationFault{s, faultParticle_[s], faultStep_[s]};
      break;
    }
  }
  previousHead_ = head_;
  previousRootNormals_ = rootNormals_;
  if (!ran) return fail("Hair system: " + ran.error().message);
  if (fault_) return std::unexpected(faultError());
  return {};
}

void HairSystem::simulateStrands(std::atomic<std::size_t>& nextBlock, const StepPlan& plan, LaneFloats& scratch,
                                 bool intoPrevious) {
  constexpr std::size_t kBlock = detail::kBlockLanes;
  const bool lanes = vectorised();
  for (std::size_t first = nextBlock.fetch_add(kBlock); first < strands_.size(); first = nextBlock.fetch_add(kBlock)) {
    const std::size_t end = std::min(first + kBlock, strands_.size());
    if (lanes) {
      HairLaneKernel::simulateBlock(*this, first, end - first, plan, scratch, intoPrevious);
      continue;
    }
    for (std::size_t s = first; s < end; s += kStrandLanes)
      simulateStrandBlock(s, std::min(kStrandLanes, end - s), plan);
  }
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
