#pragma once
// Cloth from any triangle mesh (the Nalu demo's "fins": a mesh turned into cloth by
// constraining its edges). Same Verlet solver and constraints as the hair:
// - a distance constraint on every edge (Jakobsen 2001, §3);
// - a bending constraint across every edge shared by two triangles: a distance constraint
//   between the two vertices opposite the edge, relaxed with a stiffness in [0, 1] (the
//   "bend spring" of Provot 1995 in position-based form; 0 folds freely, 1 keeps the rest
//   dihedral as well as the iteration count allows);
// - shape holds: vertices pulled each step part of the way to where the body carries their rest
//   position (TressFX's global shape constraints, Han & Harada 2012), so that a fin's rays keep
//   its shape as the muscle at their base does, while the membrane between them moves;
// - pinned vertices with infinite mass that follow the body transform, or per-pin targets (a
//   host's skinned vertices);
// - optionally, each free vertex kept off the cloth's other triangles and each edge in a fold off
//   the edges near it (cloth_self_collision.hpp);
// - long-range attachments (Kim, Chentanez & Müller 2012): every free vertex may stray from its
//   nearest pin no farther than the shortest path along the mesh's edges at rest, so hanging
//   cloth cannot stretch visibly however few the iterations (on with `solver.tethers`). Over a
//   body the cloth's path is longer than that straight line, and they go slack.
//
// Parallel and deterministic: constraints are greedily graph-coloured so that no two in a
// colour share a particle; colours are relaxed one after another, the constraints of a colour
// in any split across threads. Since no particle is written twice within a colour, the result
// is bit-identical for every thread count (docs/design.md#determinism).

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/cloth_self_collision.hpp"
#include "physics/cloth_wind.hpp"
#include "physics/colliders.hpp"
#include "physics/constraints.hpp"
#include "physics/particles.hpp"
#include "physics/solver.hpp"
#include "physics/task_runner.hpp"

namespace mane::physics {

/// A vertex pulled after each step's integration by `stiffness` of the way to where the body
/// carries its rest position (`ClothSettings::positions`).
struct ClothShapeHold {
  std::uint32_t vertex = 0;
  float stiffness = 0.0f;  ///< share of the gap closed per step, (0, 1]
};

/// Everything a `Cloth` is made from. Plain data: fill it, keep it, make several cloths from it.
struct ClothSettings {
  SolverSettings solver;          ///< step, gravity, damping, iterations, tethers (to the pins)
  float bendingStiffness = 0.5f;  ///< fraction of the bending error corrected per sweep, [0, 1]
  /// Metres ≥ 0 that each free vertex keeps from the cloth's other triangles, on the side it came
  /// from, once per step (cloth_self_collision.hpp); 0: the cloth may pass through itself.
  float selfCollisionThickness = 0.0f;
  /// The mesh in body-local space, metres: finite vertex positions, at least one triangle.
  std::vector<glm::vec3> positions;
  /// Three vertex indices per triangle; each triangle's corners distinct and not collinear.
  std::vector<std::uint32_t> triangles;
  /// The cloth's rest shape, one point per vertex (any frame, metres: only distances between
  /// vertices are read): the constraints' rest lengths. Empty: the mesh as placed by
  /// `bodyTransform`, so the cloth rests in the shape it starts in. A sewing pattern laid flat
  /// gives cloth that starts curved and still hangs in folds rather than keeping its curve.
  std::vector<glm::vec3> pattern;
  /// Free vertices held towards their rest position on the body, each at most once.
  std::vector<ClothShapeHold> shapeHolds;
  /// Vertices that follow the body (or `Cloth::setPinTargets`); repeats count once.
  std::vector<std::uint32_t> pinnedVertices;
  /// Body-local → world transform at rest (finite).
  glm::mat4 bodyTransform{1.0f};
  /// Shapes the cloth collides with, body-local (empty: none).
  ColliderSet colliders;
  /// Air blowing on the cloth's triangles (cloth_wind.hpp); none: still air.
  std::optional<ClothWind> wind;
  /// What runs the step's parallel loops (task_runner.hpp); by default the built-in pool with
  /// one worker per hardware thread. The state does not depend on it.
  TaskRunner tasks = defaultTaskRunner();
};

/// A distance constraint relaxed with a stiffness (1 = fully, as DistanceConstraint).
struct SoftDistanceConstraint {
  DistanceConstraint constraint;
  float stiffness = 1.0f;
};

class Cloth {
public:
  /// Builds cloth from `settings`' triangle mesh, pins, body transform, colliders and task
  /// runner. Fails with a message that starts with the settings field at fault and names the
  /// triangle or vertex: an index out of range, a degenerate triangle (repeated vertex or zero
  /// area), a non-finite position, an empty mesh, a pattern whose size is not the mesh's or with
  /// a non-finite point, a shape hold out of range, repeated, on a pin or of a stiffness outside (0, 1],
  /// or invalid solver settings, bending stiffness, self-collision thickness,
  /// body transform, colliders or task runner.
  [[nodiscard]] static Result<Cloth> create(const ClothSettings& settings);

  /// Shorthand: `create` with `settings`' mesh, pins and body transform replaced by these
  /// arguments (copied).
  [[nodiscard]] static Result<Cloth> create(std::span<const glm::vec3> positions,
                                            std::span<const std::uint32_t> triangles,
                                            std::span<const std::uint32_t> pinnedVertices,
                                            const ClothSettings& settings,
                                            const glm::mat4& bodyTransform = glm::mat4(1.0f));

  /// Body-local → world transform at the end of the next `advance`; pins move along the straight
  /// line between the previous and this placement over the frame's steps (until
  /// `setPinTargets` is first called), colliders with it. NaN/Inf: error.
  [[nodiscard]] Result<void> setBodyTransform(const glm::mat4& bodyTransform);

  /// Pins bound to a skinned mesh: where each pinned vertex is at the end of the next `advance`
  /// (world space, metres; one per pin, in `pinnedVertices()` order). During the frame each pin
  /// moves on the straight line from where it is to its target, as the roots of
  /// `HairSystem::setRootTargets`. Colliders keep following the body transform. From the first
  /// call on, pins follow the targets (the last ones given, until new ones come) instead of the
  /// body transform. Fails, changing nothing, on a count that is not `pinnedVertices().size()`
  /// or a NaN or infinite entry (naming the pin and its vertex).
  [[nodiscard]] Result<void> setPinTargets(std::span<const glm::vec3> positions);
  /// The air's velocity from the next `advance` on (world m/s, finite; an error otherwise). A
  /// cloth made without `ClothSettings::wind` takes the wind's defaults for the rest.
  [[nodiscard]] Result<void> setWind(const glm::vec3& velocity);
  /// The air's push on the cloth in its last step (none without wind or before the first), each
  /// triangle's at its centroid where it is now; the moment about `about` (world). What the
  /// pins hand on to the body that holds them.
  [[nodiscard]] WindPush windPush(const glm::vec3& about) const;
  /// True when pins follow `setPinTargets` targets rather than the body transform.
  [[nodiscard]] bool pinsFollowTargets() const noexcept { return !pinTargets_.empty(); }
  /// The pinned vertices, each once, in the order they first appear in `create`'s list: the
  /// order `setPinTargets` takes.
  [[nodiscard]] std::span<const std::uint32_t> pinnedVertices() const noexcept { return pinned_; }

  /// What the cloth collides with, in body-local space (it moves with the body transform).
  /// Step order: Verlet, collisions with friction, the coloured constraint sweeps, tethers, self
  /// collision, then a frictionless collision pass so that no particle ends a step inside a
  /// collider.
  [[nodiscard]] Result<void> setColliders(ColliderSet colliders);

  /// Advances by `frameDt` seconds in whole fixed steps (the remainder carries over), each
  /// phase of a step (integration, every colour of every sweep, tethers, collisions) one batch
  /// of tasks on `taskRunner()` over fixed slices; the result does not depend on the runner.
  /// Fails when `frameDt` is negative or not finite, when the runner fails (the frame is then
  /// completed on the calling thread, so the state is still right), or when a particle becomes
  /// non-finite (naming it).
  [[nodiscard]] Result<void> advance(double frameDt);
  /// Shorthand for a caller that counts workers: `advance` on `builtInTaskRunner(threads)` for
  /// this frame (0 counts as 1).
  [[nodiscard]] Result<void> advance(double frameDt, unsigned threads);

  /// Replaces the task runner (`ClothSettings::tasks`); fails, changing nothing, when
  /// `validateTaskRunner` rejects it.
  [[nodiscard]] Result<void> setTaskRunner(TaskRunner tasks);
  /// The task runner that `advance(frameDt)` uses.
  [[nodiscard]] const TaskRunner& taskRunner() const noexcept { return settings_.tasks; }

  /// FNV-1a over positions, previous positions, the accumulator's backlog and step count.
  [[nodiscard]] std::uint64_t stateHash() const noexcept;

  [[nodiscard]] const Particles& particles() const noexcept { return particles_; }
  [[nodiscard]] std::span<const SoftDistanceConstraint> constraints() const noexcept { return constraints_; }
  /// Constraints [colourStarts[c], colourStarts[c + 1]) form colour c.
  [[nodiscard]] std::span<const std::uint32_t> colourStarts() const noexcept { return colourStarts_; }
  /// The mesh-edge constraints alone (no bending), in edge order: for measuring stretch.
  [[nodiscard]] std::span<const DistanceConstraint> edges() const noexcept { return edges_; }
  [[nodiscard]] std::size_t edgeCount() const noexcept { return edges_.size(); }
  [[nodiscard]] std::size_t bendingCount() const noexcept { return constraints_.size() - edges_.size(); }
  /// One per free vertex that a path of edges connects to a pin (when tethers are on).
  [[nodiscard]] std::span<const Tether> tethers() const noexcept { return tethers_; }

private:
  Cloth(const ClothSettings& settings);
  [[nodiscard]] Result<void> advanceWith(double frameDt, const TaskRunner& tasks);
  void relaxColour(std::size_t colour, std::size_t first, std::size_t end);
  static std::vector<Tether> attachToPins(const Cloth& cloth);

  ClothSettings settings_;
  FixedStepAccumulator accumulator_;
  Particles particles_;
  std::vector<SoftDistanceConstraint> constraints_;  // sorted by colour
  std::vector<std::uint32_t> colourStarts_;
  std::vector<DistanceConstraint> edges_;
  std::vector<Tether> tethers_;  // sorted by particle
  std::optional<ClothSelfCollision> selfCollision_;
  std::optional<ClothWindLoad> wind_;
  std::vector<std::uint32_t> triangles_;  // kept for a wind set after creation
  std::vector<std::uint32_t> pinned_;
  std::vector<glm::vec3> pinnedLocal_;
  std::vector<ClothShapeHold> shapeHolds_;
  std::vector<glm::vec3> heldLocal_;   // per shape hold, body-local rest position
  std::vector<glm::vec3> pinTargets_;  // per pin, world: empty while pins follow the body
  std::vector<glm::vec3> pinFrom_;     // per pin, world: where the current advance starts it ...
  std::vector<glm::vec3> pinTo_;       // ... and ends it
  ColliderSet colliders_;
  glm::mat4 previousBody_{1.0f};
  glm::mat4 body_{1.0f};
};

}  // namespace mane::physics
