#pragma once
// Guide hair strands simulated as Verlet particle chains (Jakobsen 2001): the root particle of
// each strand is kinematic and follows a rigid head transform; the others fall under gravity and
// are held together by distance constraints and long-range attachments to the root.
//
// Strands do not interact (there are no hair–hair forces), so a frame is simulated strand by strand,
// in parallel over whole strands: every strand runs the same sequence of floating-point
// operations whichever thread runs it, and no value is reduced across threads, so the state is
// bit-identical for any thread count.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>
#include <optional>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/error.hpp"
#include "physics/colliders.hpp"
#include "physics/particles.hpp"
#include "physics/solver.hpp"
#include "physics/task_runner.hpp"
#include "physics/wind.hpp"

namespace mane::physics {

namespace detail {
struct HairLaneKernel;
}  // namespace detail

/// Smallest accepted distance between consecutive input points, metres. Shorter segments give
/// the distance constraint no usable direction (it divides by the current length).
inline constexpr float kMinSegmentLength = 1e-6f;

/// One simulated guide strand: a contiguous run of particles, root first.
struct GuideStrand {
  std::uint32_t firstParticle = 0;  ///< index of the root particle in `HairSystem::particles()`
  std::uint32_t particleCount = 0;  ///< root included; at least 2
  glm::vec3 rootLocal{0.0f};        ///< root position in head-local space, metres
};

/// Where and when the simulation broke: the first (lowest-index) strand with a non-finite
/// (NaN or infinite) particle position.
struct SimulationFault {
  std::size_t strand = 0;    ///< strand index, as in the input
  std::size_t particle = 0;  ///< particle index within the strand (0 = root)
  std::uint64_t step = 0;    ///< fixed step (counted from creation, 1-based) that produced it
};

/// Everything a `HairSystem` is made from. Plain data: fill it, keep it, make several systems
/// from it. Lengths in metres, positions in head-local space unless said otherwise.
struct HairSettings {
  /// The guide strands, points root first: at least one strand, each with ≥ 2 finite points no
  /// closer than `kMinSegmentLength` to the previous one.
  std::vector<std::vector<glm::vec3>> strands;
  /// Step length, gravity, damping, iterations, tethers, shape stiffness, speed clamp.
  SolverSettings solver;
  /// Head-local → world transform at rest (finite; rigid expected).
  glm::mat4 headTransform{1.0f};
  /// Shapes every non-root particle collides with (head-local; empty: no collisions).
  ColliderSet colliders;
  /// Wind blowing through the hair from the first step (none: still air).
  std::optional<WindSettings> wind;
  /// Per strand, the direction of its root's normal at rest (head-local; normalised here), for
  /// `setRootTargets`; empty: the direction of each strand's first segment.
  std::vector<glm::vec3> rootRestNormals;
  /// Whether the step may use the AVX2 strand kernel (same bits as the scalar one).
  bool vectorised = true;
  /// What runs the step's parallel loop (task_runner.hpp); by default the built-in pool with one
  /// worker per hardware thread. The state does not depend on it.
  TaskRunner tasks = defaultTaskRunner();
};

/// A set of guide strands attached to a rigid head.
///
/// Per frame: `setHeadTransform` (where the head is at the end of the frame), then `advance`.
/// Each fixed step inside the frame places the roots on the straight line between their
/// positions under the previous and the new head transform, at the step's time in the frame.
/// Within one fixed step each strand runs, in order:
/// 1. root placement and Verlet integration under gravity plus, when `setWind` was called, the
///    wind's drag on each non-root particle's segment (see `setWind`);
/// 2. `constraintIterations` sweeps, each: local shape constraints root → tip (when
///    `SolverSettings::shapeStiffness` > 0), distance constraints root → tip, then tethers;
/// 3. one collision pass root → tip (as TressFX: constraints first, then the colliders have the
///    last word) that settles each particle against both the colliders and its tether: a push
///    out of the colliders with friction against the particle's motion during the step, then,
///    when that left the particle beyond its tether, alternating tether projections and
///    frictionless collision pushes (up to `kSettleRounds`), and if they do not meet, the rounds'
///    last point pulled back onto its tether where that lies outside the colliders (if not by
///    their whole thickness), else the point nearest the particle on the segment from its
///    (already settled) parent for which both hold, found by bisection. So after every step no
///    particle is inside a collider and none is farther from its root than its rest length along
///    the strand (both within `kSettleSlack`), whenever the root itself is outside the colliders;
/// 4. the velocity clamp (`SolverSettings::maxSpeed`), which only moves previous positions.
///
/// The head's pose at each fixed step, used by colliders and shape constraints, is a rigid
/// interpolation between the frame's start and end transforms (rotation by normalised linear
/// quaternion interpolation, translation linearly); at the end of the frame it is the new head
/// transform. Roots themselves move on the straight lines described above.
class HairSystem {
public:
  /// Builds the system from `settings`: the strands placed in the world by
  /// `settings.headTransform` at rest, with its colliders, wind, rest normals and task runner.
  /// Fails with a message that names the settings field (and the strand and particle) when the
  /// groom is empty, a strand has fewer than 2 points, a point is NaN or infinite, two
  /// consecutive points are closer than `kMinSegmentLength`, or the solver settings, head
  /// transform, colliders, wind, rest normals or task runner are invalid.
  [[nodiscard]] static Result<HairSystem> create(const HairSettings& settings);

  /// Shorthand: `create` with a `HairSettings` holding a copy of `strands`, `settings` and
  /// `headTransform` and everything else at its default.
  [[nodiscard]] static Result<HairSystem> create(std::span<const std::vector<glm::vec3>> strands,
                                                 const SolverSettings& settings,
                                                 const glm::mat4& headTransform = glm::mat4(1.0f));

  /// Sets the head-local → world transform that holds at the end of the next `advance` (a rigid
  /// transform is expected; roots are interpolated linearly between frames). Fails, changing
  /// nothing, when an entry is NaN or infinite.
  [[nodiscard]] Result<void> setHeadTransform(const glm::mat4& headTransform);

  /// Roots on a skinned mesh: where each strand's root is at the end of the next `advance`
  /// (world space, metres; one per strand, in strand order) and the skin's unit normal there.
  /// During the frame each root moves on the straight line from where it is to its target.
  /// The normal turns the strand's shape frame (shape constraints): the head's rotation, then
  /// the shortest arc from the root's rest normal (`rootRestNormals`, carried by the head) to
  /// the given normal, interpolated through the frame like the positions. Colliders keep
  /// following the head transform (the skull under the skin). From the first call on, roots
  /// follow the targets (the last ones given, until new ones come) instead of the head
  /// transform; `teleport` returns them to the head. Fails, changing nothing, on a count that is
  /// not `strandCount()`, a NaN or infinite entry, or a normal shorter than 1e-6 (naming the
  /// strand).
  [[nodiscard]] Result<void> setRootTargets(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);
  /// True when roots follow per-root targets (`setRootTargets`) rather than the head transform.
  [[nodiscard]] bool rootsSkinned() const noexcept { return !rootTargets_.empty(); }
  /// Per strand, the direction its root's normal has in head-local space at rest, against which
  /// `setRootTargets` normals turn the shape frame: the direction of the strand's first rest
  /// segment unless `setRootRestNormals` gave others.
  [[nodiscard]] std::span<const glm::vec3> rootRestNormals() const noexcept { return rootRestNormals_; }
  /// Replaces the rest normals (head-local, one per strand, normalised here). Fails, changing
  /// nothing, on a wrong count, a non-finite entry or one shorter than 1e-6.
  [[nodiscard]] Result<void> setRootRestNormals(std::span<const glm::vec3> normals);

  /// Sets the shapes every non-root particle collides with, in head-local space (metres): they
  /// follow the head transform each step. An empty set (the default) disables collisions. Fails,
  /// changing nothing, when `validateColliders` rejects the set.
  [[nodiscard]] Result<void> setColliders(ColliderSet colliders);
  /// The colliders in use (head-local space).
  [[nodiscard]] const ColliderSet& colliders() const noexcept { return colliders_; }

  /// Blows `wind` (world space) through the hair from the next step on. Each non-root particle
  /// gets the drag acceleration of its segment, `windAcceleration(w, v, axis, dragPerSecond)`
  /// (wind.hpp: linear drag on the velocity component normal to the segment), added to gravity
  /// in the Verlet kick. The axis runs from the parent particle to the particle, the velocity is
  /// (x − x_prev)/h, both at the start of the step, and the air velocity is
  /// `WindField::velocityAt(x, t)` with t the simulated time at the start of the step
  /// (`simulatedTime()` before it). Fails, changing nothing, when `validateWind` rejects it.
  [[nodiscard]] Result<void> setWind(const WindSettings& wind);
  /// Removes the wind (the default: no wind).
  void clearWind() noexcept { wind_.reset(); }
  /// The wind in use, if any.
  [[nodiscard]] std::optional<WindSettings> wind() const;

  /// Whether the step may use the AVX2 strand kernel when the CPU has it (default: true), with
  /// AVX-512 registers for the constraint sweeps where the CPU has those too. It gives the same
  /// bits as the scalar kernel; the switch exists for tests and benchmarks. The vector kernel
  /// runs the steps without wind and shape constraints; others stay scalar.
  void setVectorised(bool allowed) noexcept { vectorise_ = allowed; }
  /// True when the next step would run the AVX2 kernel.
  [[nodiscard]] bool vectorised() const noexcept;

  /// Collision–tether settling rounds in the final pass of a step (see the class comment).
  static constexpr int kSettleRounds = 2;
  /// Slack of the final pass's checks, metres: a particle counts as outside a collider when its
  /// signed distance is ≥ thickness − slack and within its tether when at most rest + slack.
  static constexpr float kSettleSlack = 1e-5f;

  /// Places every strand in its rest shape under `headTransform`, at rest (zero velocity), and
  /// clears a recorded fault. For cuts and resets; fails when an entry is NaN or infinite.
  [[nodiscard]] Result<void> teleport(const glm::mat4& headTransform);

  /// Replaces the particles' Verlet state (`particles()` order, world space, metres): the
  /// current positions, and the positions one fixed step earlier, whose difference is the
  /// displacement the next step carries on (velocity × fixed step; pass the same positions twice
  /// to leave the particles at rest). Roots take the positions too, but the next step places them
  /// on their head or targets again. For scripts and perturbation tests; the step count, the
  /// fixed-step backlog and a recorded fault stay. Fails, changing nothing, on a count that is not
  /// `particles().size()` or a NaN or infinite entry (naming the particle).
  [[nodiscard]] Result<void> setParticleState(std::span<const glm::vec3> positions,
                                              std::span<const glm::vec3> previousPositions);

  /// Advances the simulation by a frame of `frameDt` seconds, split into whole fixed steps (the
  /// remainder carries over to the next frame), its parallel loop run by `taskRunner()`: up to
  /// `concurrency` tasks that take blocks of whole strands in turn; the result does not depend
  /// on the runner. Fails when `frameDt` is negative or not finite; when the runner fails (the
  /// frame is then completed on the calling thread, so the state is still right); or when a
  /// particle position becomes NaN or infinite: the message names the strand and the system
  /// stops advancing (see `fault()`) until `teleport` resets it.
  [[nodiscard]] Result<void> advance(double frameDt);
  /// Shorthand for a caller that counts workers: `advance` on `builtInTaskRunner(threads)` for
  /// this frame (0 counts as 1).
  [[nodiscard]] Result<void> advance(double frameDt, unsigned threads);

  /// Replaces the task runner (`HairSettings::tasks`). Fails, changing nothing, when
  /// `validateTaskRunner` rejects it.
  [[nodiscard]] Result<void> setTaskRunner(TaskRunner tasks);
  /// The task runner that `advance(frameDt)` uses.
  [[nodiscard]] const TaskRunner& taskRunner() const noexcept { return tasks_; }

  /// 64-bit FNV-1a hash (see hash.hpp) of the simulated state: all positions, all previous
  /// positions, then the accumulator's backlog (double, seconds) and the fixed-step count.
  [[nodiscard]] std::uint64_t stateHash() const noexcept;

  /// Number of strands.
  [[nodiscard]] std::size_t strandCount() const noexcept { return strands_.size(); }
  /// Layout of every strand.
  [[nodiscard]] std::span<const GuideStrand> strands() const noexcept { return strands_; }
  /// Current world positions (metres) of strand `strand`'s particles, root first. The view is
  /// good until the next `advance`, `teleport` or `setParticleState` (a step may hand the
  /// positions' storage to the previous positions): ask again after those.
  [[nodiscard]] std::span<const glm::vec3> strandPositions(std::size_t strand) const;
  /// Rest distance (metres) from strand `strand`'s root to each of its particles along the
  /// strand (0 for the root): the tether lengths.
  [[nodiscard]] std::span<const float> strandRestDistances(std::size_t strand) const;
  /// All particles, strands one after another. The reference stays good; pointers into its
  /// arrays (and views of them) only until the next `advance`, `teleport` or `setParticleState`.
  [[nodiscard]] const Particles& particles() const noexcept { return particles_; }
  /// The settings this system was created with.
  [[nodiscard]] const SolverSettings& settings() const noexcept { return settings_; }
  /// The recorded fault, if a particle has become non-finite.
  [[nodiscard]] const std::optional<SimulationFault>& fault() const noexcept { return fault_; }
  /// Fixed steps simulated since creation.
  [[nodiscard]] std::uint64_t stepCount() const noexcept { return accumulator_.stepsTaken(); }
  /// Simulated time since creation, seconds (step count × fixed step).
  [[nodiscard]] double simulatedTime() const noexcept;

private:
  explicit HairSystem(const SolverSettings& settings);

  // Allocates on cache-line boundaries, so that no lane row of the vector path (32 bytes in an
  // AVX2 register, 64 in an AVX-512 one) straddles two lines (a split store is not forwarded to
  // the load that follows it).
  template <class T>
  struct CacheLineAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlignment{64};
    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
    void deallocate(T* p, std::size_t n) noexcept { ::operator delete(p, n * sizeof(T), kAlignment); }
    friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) noexcept { return true; }
  };
  using LaneFloats = std::vector<float, CacheLineAllocator<float>>;

  // One task: simulates blocks of strands taken from `nextBlock` until none are left.
  // `scratch`: the task's lane storage for the AVX2 path, kept between frames.
  // `intoPrevious` (AVX2 path only): write the new positions into the previous positions' array,
  // whose contents the caller then swaps with the positions' (see advanceWith).
  void simulateStrands(std::atomic<std::size_t>& nextBlock, const StepPlan& plan, LaneFloats& scratch,
                       bool intoPrevious);
  void simulateStrandBlock(std::size_t firstStrand, std::size_t lanes, const StepPlan& plan);
  // The AVX2 path lives in physics/detail/hair_lanes.hpp, away from this header; it steps
  // blocks of this object's strands.
  friend struct detail::HairLaneKernel;

  // The head's rigid pose at one fixed step: world = rotation · local + translation.
  struct HeadPose {
    glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};  // unit quaternion (x, y, z, w)
    glm::vec3 axes[3];                           // the rotation's matrix columns
    glm::vec3 translation{0.0f};
  };
  void planPoses(const StepPlan& plan);
  // Where strand s's root is at the start of the frame and how far it moves by the frame's end.
  void rootMotion(std::size_t s, glm::vec3& from, glm::vec3& travel) const noexcept;
  // The shape frame strand s starts from at fixed step k (fraction f of the frame).
  glm::vec4 shapeFrame(std::size_t s, int k, float f) const noexcept;
  // One particle (world space) against the colliders in pose `pose`, friction against the motion
  // since `previous` (in pose `before`); true when it touched anything.
  bool collidePoint(const HeadPose& pose, const HeadPose& before, glm::vec3& x, const glm::vec3& previous,
                    float friction) const noexcept;
  // The collision pass for one particle: colliders with friction against the motion since
  // `previous` (in pose `before`), then its tether (class comment, item 3).
  void settlePoint(const HeadPose& pose, const HeadPose& before, glm::vec3& x, const glm::vec3& previous,
                   const glm::vec3& root, const glm::vec3& parent, float reach) const noexcept;
  // The rest of settlePoint once the push left `x` beyond its tether: alternate projections.
  void settleTether(const HeadPose& pose, glm::vec3& x, const glm::vec3& root, const glm::vec3& parent,
                    float reach) const noexcept;
  // settleTether's last resort, where its rounds ended at `p`: x on the segment parent → p.
  void bisectTether(const HeadPose& pose, glm::vec3& x, const glm::vec3& p, const glm::vec3& root,
                    const glm::vec3& parent, float reach) const noexcept;

  static constexpr std::size_t kStrandLanes = 8;  // strands advanced side by side (scalar path)
  void placeAtRest(const glm::mat4& headTransform);
  // Fills blockConstants_ from the strands (at creation: they never change).
  void layOutBlockConstants();
  [[nodiscard]] Error faultError() const;

  [[nodiscard]] Result<void> advanceWith(double frameDt, const TaskRunner& tasks);

  SolverSettings settings_;
  TaskRunner tasks_;
  FixedStepAccumulator accumulator_;
  Particles particles_;
  std::vector<GuideStrand> strands_;
  std::vector<glm::vec3> restLocal_;            // rest positions in head-local space, per particle
  std::vector<float> segmentLengths_;           // rest distance to the previous particle (0 at roots)
  std::vector<float> restDistances_;            // rest distance to the root along the strand
  std::vector<std::uint32_t> faultParticle_;    // per strand: first bad particle, or kNoFault
  std::vector<std::uint64_t> faultStep_;        // per strand: step that made it bad
  std::vector<glm::vec3> rootRestNormals_;      // per strand, head-local, unit
  std::vector<glm::vec3> rootTargets_;          // per strand, world: empty while roots follow the head
  std::vector<glm::vec3> rootNormals_;          // per strand, world, unit: at the end of the next advance
  std::vector<glm::vec3> pendingRootNormals_;   // setRootTargets' checked normals, swapped in on success
  std::vector<glm::vec3> previousRootNormals_;  // ... and at the end of the last one
  glm::mat4 previousHead_{1.0f};                // head transform at the end of the last advance
  glm::mat4 head_{1.0f};                        // head transform at the end of the next advance
  std::optional<SimulationFault> fault_;
  ColliderSet colliders_;          // head-local
  ColliderBounds colliderBounds_;  // head-local bounding ball of colliders_
  ColliderCull colliderCull_;      // head-local boxes around each of colliders_
  std::vector<HeadPose> poses_;    // per advance: pose at the end of fixed step k (0: frame start)
  std::optional<WindField> wind_;  // none: no wind
  bool vectorise_ = true;
  std::vector<LaneFloats> scratch_;  // per task: work space of the AVX2 path
  // The AVX2 path's constants per block of detail::kBlockLanes strands, lane by lane: inverse
  // masses, segment lengths, reaches (3 arrays of rows × kBlockLanes floats) for block k from
  // blockConstants_[blockConstantsAt_[k]] on.
  LaneFloats blockConstants_;
  std::vector<std::size_t> blockConstantsAt_;
  // Per block, what the AVX2 kernels may assume (StrandLanes::plainRows, kSimdGroups each); and
  // whether every particle but the roots moves (inverse mass > 0).
  std::vector<std::size_t> blockPlainRows_;
  bool allMoving_ = true;
  // Per block, the strands' roots in head-local space, lane by lane (x, y, z rows of
  // detail::kBlockLanes floats), for the AVX2 path's root motion.
  LaneFloats blockRootsLocal_;
  // The AVX2 path's particle state, lane by lane (positions, then previous positions: 6 arrays of
  // rows × kBlockLanes floats) for block k from laneState_[2 · blockConstantsAt_[k]] on. Kept
  // between steps so that a step only writes the particles back, not reads them in again;
  // `lanesCurrent_` says whether it still equals `particles_` (anything else that moves the
  // particles clears it).
  LaneFloats laneState_;
  bool lanesCurrent_ = false;
};

}  // namespace mane::physics
