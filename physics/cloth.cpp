#include "physics/cloth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "physics/detail/parallel_tasks.hpp"
#include "physics/hash.hpp"

namespace mane::physics {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

// Greedy colouring in constraint order: each constraint takes the lowest colour in which
// neither of its particles is used yet. Returns the colour of every constraint.
std::vector<std::uint32_t> colourConstraints(std::span<const SoftDistanceConstraint> constraints,
                                             std::size_t particleCount) {
  std::vector<std::vector<bool>> used;  // used[colour][particle]
  std::vector<std::uint32_t> colours(constraints.size());
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const auto a = constraints[i].constraint.a, b = constraints[i].constraint.b;
    std::uint32_t colour = 0;
    while (colour < used.size() && (used[colour][a] || used[colour][b])) ++colour;
    if (colour == used.size()) used.emplace_back(particleCount, false);
    used[colour][a] = used[colour][b] = true;
    colours[i] = colour;
  }
  return colours;
}

}  // namespace

// Multi-source Dijkstra over the edge constraints from every pin: each free vertex's nearest pin
// along the mesh and the length of that path at rest, which bounds its distance to the pin.
std::vector<Tether> Cloth::attachToPins(const Cloth& cloth) {
  const std::size_t count = cloth.particles_.size();
  std::vector<std::vector<std::pair<std::uint32_t, float>>> neighbours(count);
  for (const DistanceConstraint& edge : cloth.edges_) {
    neighbours[edge.a].push_back({edge.b, edge.restLength});
    neighbours[edge.b].push_back({edge.a, edge.restLength});
  }
  constexpr float kUnreached = std::numeric_limits<float>::infinity();
  std::vector<float> distance(count, kUnreached);
  std::vector<std::uint32_t> nearestPin(count, 0);
  using Entry = std::pair<float, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::uint32_t pin : cloth.pinned_) {
    distance[pin] = 0.0f;
    nearestPin[pin] = pin;
    queue.push({0.0f, pin});
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    for (const auto& [next, length] : neighbours[v])
      if (d + length < distance[next]) {
        distance[next] = d + length;
        nearestPin[next] = nearestPin[v];
        queue.push({distance[next], next});
      }
  }
  std::vector<Tether> tethers;
  for (std::uint32_t v = 0; v < count; ++v)
    if (cloth.particles_.inverseMasses[v] > 0.0f && distance[v] != kUnreached)
      tethers.push_back({v, nearestPin[v], distance[v]});
  return tethers;
}

Cloth::Cloth(const ClothSettings& settings)
    : settings_{.solver = settings.solver, .bendingStiffness = settings.bendingStiffness, .tasks = settings.tasks},
      accumulator_(settings.solver.fixedStep, settings.solver.maxSubstepsPerFrame) {}

Result<void> Cloth::setWind(const glm::vec3& velocity) {
  if (!wind_) {
    // The vertices' masses from the cloth's shape now: its area is its rest area to the
    // constraints' tolerance.
    auto wind = ClothWindLoad::create({.velocity = velocity}, triangles_, particles_.positions);
    if (!wind) return std::unexpected(wind.error());
    wind_ = std::move(*wind);
    return {};
  }
  return wind_->setVelocity(velocity);
}

Result<Cloth> Cloth::create(std::span<const glm::vec3> positions, std::span<const std::uint32_t> triangles,
                            std::span<const std::uint32_t> pinnedVertices, const ClothSettings& settings,
                            const glm::mat4& bodyTransform) {
  ClothSettings cloth = settings;
  cloth.positions.assign(positions.begin(), positions.end());
  cloth.triangles.assign(triangles.begin(), triangles.end());
  cloth.pinnedVertices.assign(pinnedVertices.begin(), pinnedVertices.end());
  cloth.bodyTransform = bodyTransform;
  return create(cloth);
}

Result<Cloth> Cloth::create(const ClothSettings& settings) {
  const std::span<const glm::vec3> positions = settings.positions;
  const std::span<const std::uint32_t> triangles = settings.triangles;
  const std::span<const std::uint32_t> pinnedVertices = settings.pinnedVertices;
  const glm::mat4& bodyTransform = settings.bodyTransform;
  if (auto valid = validateSettings(settings.solver); !valid)
    return fail("ClothSettings.solver: " + valid.error().message);
  if (!(settings.bendingStiffness >= 0.0f && settings.bendingStiffness <= 1.0f))
    return fail("ClothSettings.bendingStiffness must be in [0, 1], got " + std::to_string(settings.bendingStiffness));
  if (!(settings.selfCollisionThickness >= 0.0f && settings.selfCollisionThickness <= 1.0f))
    return fail("ClothSettings.selfCollisionThickness must be in [0, 1] metres, got " +
                std::to_string(settings.selfCollisionThickness));
  if (!finite(bodyTransform)) return fail("ClothSettings.bodyTransform: cloth body transform has a NaN or infinite entry");
  if (auto valid = validateTaskRunner(settings.tasks, "ClothSettings.tasks"); !valid)
    return std::unexpected(valid.error());
  if (positions.empty()) return fail("ClothSettings.positions: the cloth mesh is empty (no vertices)");
  if (triangles.empty()) return fail("ClothSettings.triangles: the cloth mesh is empty (no triangles)");
  if (triangles.size() % 3 != 0)
    return fail("ClothSettings.triangles: cloth triangle index count " + std::to_string(triangles.size()) +
                " is not a multiple of 3");
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (!finite(positions[v]))
      return fail("ClothSettings.positions: cloth vertex " + std::to_string(v) + " is NaN or infinite");
  if (!settings.pattern.empty() && settings.pattern.size() != positions.size())
    return fail("ClothSettings.pattern: " + std::to_string(settings.pattern.size()) + " points for " +
                std::to_string(positions.size()) + " vertices");
  for (std::size_t v = 0; v < settings.pattern.size(); ++v)
    if (!finite(settings.pattern[v]))
      return fail("ClothSettings.pattern: point " + std::to_string(v) + " is NaN or infinite");

  // Edge (low, high) → the vertices opposite it in the triangles that share it.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> edges;
  for (std::size_t t = 0; t < triangles.size() / 3; ++t) {
    const std::uint32_t* corner = &triangles[3 * t];
    const std::string name = "ClothSettings.triangles: cloth triangle " + std::to_string(t);
    for (int i = 0; i < 3; ++i)
      if (corner[i] >= positions.size())
        return fail(name + " uses vertex " + std::to_string(corner[i]) + " but the mesh has " +
                    std::to_string(positions.size()));
    if (corner[0] == corner[1] || corner[1] == corner[2] || corner[0] == corner[2])
      return fail(name + " repeats a vertex");
    const glm::vec3 normal =
        glm::cross(positions[corner[1]] - positions[corner[0]], positions[corner[2]] - positions[corner[0]]);
    if (!(glm::dot(normal, normal) > 0.0f)) return fail(name + " has zero area");
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = corner[i], b = corner[(i + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(corner[(i + 2) % 3]);
    }
  }

  Cloth cloth(settings);
  cloth.body_ = cloth.previousBody_ = bodyTransform;
  std::vector<bool> isPinned(positions.size(), false);
  for (std::uint32_t v : pinnedVertices) {
    if (v >= positions.size())
      return fail("ClothSettings.pinnedVertices: pinned cloth vertex " + std::to_string(v) + " is out of range (the mesh has " +
                  std::to_string(positions.size()) + ")");
    if (!isPinned[v]) {
      isPinned[v] = true;
      cloth.pinned_.push_back(v);
      cloth.pinnedLocal_.push_back(positions[v]);
    }
  }
  cloth.particles_.reserve(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v)
    cloth.particles_.add(transformPoint(bodyTransform, positions[v]), isPinned[v] ? 0.0f : 1.0f);

  const std::span<const glm::vec3> restShape =
      settings.pattern.empty() ? std::span<const glm::vec3>(cloth.particles_.positions) : settings.pattern;
  auto addConstraint = [&](std::uint32_t a, std::uint32_t b, float stiffness) {
    if (isPinned[a] && isPinned[b]) return;  // nothing can move
    const float rest = glm::distance(restShape[a], restShape[b]);
    if (rest > 0.0f) cloth.constraints_.push_back({{a, b, rest}, stiffness});
  };
  for (const auto& [edge, opposite] : edges) addConstraint(edge.first, edge.second, 1.0f);
  for (const auto& edge : cloth.constraints_) cloth.edges_.push_back(edge.constraint);
  if (settings.bendingStiffness > 0.0f)
    for (const auto& [edge, opposite] : edges)
      if (opposite.size() == 2 && opposite[0] != opposite[1])
        addConstraint(std::min(opposite[0], opposite[1]), std::max(opposite[0], opposite[1]),
                      settings.bendingStiffness);

  std::vector<bool> isHeld(positions.size(), false);
  for (std::size_t i = 0; i < settings.shapeHolds.size(); ++i) {
    const ClothShapeHold& hold = settings.shapeHolds[i];
    const std::string name = "ClothSettings.shapeHolds[" + std::to_string(i) + "]";
    if (hold.vertex >= positions.size())
      return fail(name + " holds vertex " + std::to_string(hold.vertex) + " but the mesh has " +
                  std::to_string(positions.size()));
    if (isPinned[hold.vertex] || isHeld[hold.vertex])
      return fail(name + ": vertex " + std::to_string(hold.vertex) +
                  (isHeld[hold.vertex] ? " is held twice" : " is pinned"));
    if (!(hold.stiffness > 0.0f && hold.stiffness <= 1.0f))
      return fail(name + ".stiffness must be in (0, 1], got " + std::to_string(hold.stiffness));
    isHeld[hold.vertex] = true;
    cloth.shapeHolds_.push_back(hold);
    cloth.heldLocal_.push_back(positions[hold.vertex]);
  }

  if (settings.solver.tethers && !cloth.pinned_.empty()) cloth.tethers_ = attachToPins(cloth);
  if (settings.selfCollisionThickness > 0.0f)
    cloth.selfCollision_.emplace(triangles, positions.size(), settings.selfCollisionThickness);

  // Sort by colour (stable: within a colour the build order stays, though it cannot matter).
  const auto colours = colourConstraints(cloth.constraints_, positions.size());
  std::vector<std::uint32_t> order(cloth.constraints_.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](auto x, auto y) { return colours[x] < colours[y]; });
  std::vector<SoftDistanceConstraint> sorted;
  sorted.reserve(order.size());
  for (std::uint32_t i : order) sorted.push_back(cloth.constraints_[i]);
  cloth.constraints_ = std::move(sorted);
  const std::uint32_t colourCount = colours.empty() ? 0 : *std::max_element(colours.begin(), colours.end()) + 1;
  cloth.colourStarts_.assign(colourCount + 1, 0);
  for (std::uint32_t c : colours) ++cloth.colourStarts_[c + 1];
  for (std::uint32_t c = 0; c < colourCount; ++c) cloth.colourStarts_[c + 1] += cloth.colourStarts_[c];
  if (!settings.colliders.empty())
    if (auto set = cloth.setColliders(settings.colliders); !set)
      return fail("ClothSettings.colliders: " + set.error().message);
  cloth.triangles_.assign(triangles.begin(), triangles.end());
  if (settings.wind) {
    auto wind = ClothWindLoad::create(*settings.wind, triangles, restShape);
    if (!wind) return std::unexpected(wind.error());
    cloth.wind_ = std::move(*wind);
  }
  return cloth;
}

Result<void> Cloth::setTaskRunner(TaskRunner tasks) {
  if (auto valid = validateTaskRunner(tasks, "Cloth::setTaskRunner: the runner"); !valid) return valid;
  settings_.tasks = std::move(tasks);
  return {};
}

Result<void> Cloth::setColliders(ColliderSet colliders) {
  if (auto valid = validateColliders(colliders); !valid) return fail("cloth colliders: " + valid.error().message);
  colliders_ = std::move(colliders);
  return {};
}

Result<void> Cloth::setBodyTransform(const glm::mat4& bodyTransform) {
  if (!finite(bodyTransform)) return fail("cloth body transform has a NaN or infinite entry");
  body_ = bodyTransform;
  return {};
}

Result<void> Cloth::setPinTargets(std::span<const glm::vec3> positions) {
  if (positions.size() != pinned_.size())
    return fail("cloth pin targets: " + std::to_string(positions.size()) + " positions for " +
                std::to_string(pinned_.size()) + " pinned vertices");
  for (std::size_t p = 0; p < positions.size(); ++p)
    if (!finite(positions[p]))
      return fail("cloth pin target " + std::to_string(p) + " (vertex " + std::to_string(pinned_[p]) +
                  ") is NaN or infinite");
  pinTargets_.assign(positions.begin(), positions.end());
  return {};
}

void Cloth::relaxColour(std::size_t colour, std::size_t first, std::size_t end) {
  auto& positions = particles_.positions;
  const auto& weights = particles_.inverseMasses;
  const std::size_t base = colourStarts_[colour];
  for (std::size_t i = base + first; i < base + end; ++i) {
    const auto& [c, stiffness] = constraints_[i];
    glm::vec3 pa = positions[c.a], pb = positions[c.b];
    projectDistance(pa, pb, weights[c.a], weights[c.b], c.restLength);
    if (stiffness == 1.0f) {
      positions[c.a] = pa;
      positions[c.b] = pb;
    } else {
      positions[c.a] += (pa - positions[c.a]) * stiffness;
      positions[c.b] += (pb - positions[c.b]) * stiffness;
    }
  }
}

Result<void> Cloth::advance(double frameDt) {
  return advanceWith(frameDt, settings_.tasks);
}

WindPush Cloth::windPush(const glm::vec3& about) const {
  return wind_ ? wind_->total(particles_.positions, about) : WindPush{};
}

Result<void> Cloth::advance(double frameDt, unsigned threads) {
  return advanceWith(frameDt, builtInTaskRunner(threads));
}

Result<void> Cloth::advanceWith(double frameDt, const TaskRunner& tasks) {
  if (!(frameDt >= 0.0) || !std::isfinite(frameDt)) return fail("cloth frame time must be finite and ≥ 0");
  const StepPlan plan = accumulator_.plan(frameDt);
  // A task is split off only with enough particles to pay for its share of the batches (one
  // per colour and iteration); a small cape runs far slower on two threads than on one.
  constexpr std::size_t kParticlesPerWorker = 4096;
  const std::uint32_t workers = detail::taskCountFor(tasks, particles_.size(), kParticlesPerWorker);
  const auto step = static_cast<float>(settings_.solver.fixedStep);
  const std::size_t colourCount = colourStarts_.empty() ? 0 : colourStarts_.size() - 1;

  // Task w owns a fixed slice of the particles (integration) and of every colour (relaxation);
  // each phase is one batch and the next starts when it has finished, so nothing is read while
  // another task writes it.
  auto slice = [&](std::size_t count, std::uint32_t w) {
    return std::pair{detail::taskRangeBegin(count, workers, w), detail::taskRangeBegin(count, workers, w + 1)};
  };
  Result<void> ran;  // the first failure of the task runner, if any
  const auto runPhase = [&](auto&& phase) {
    if (auto done = detail::runTasks(tasks, workers, phase); !done && ran) ran = std::move(done);
  };
  // The body's placement at fraction t of the frame: the two frame-end placements blended (exact
  // at the frame's end). Colliders live in body space: particles are taken there with the step's
  // placement, collided, and brought back; shape holds pull towards it.
  const auto placementAt = [&](float t) { return previousBody_ + (body_ - previousBody_) * t; };
  std::vector<glm::mat4> bodyAt, worldToBody;
  if (!colliders_.empty())
    for (int k = 0; k <= plan.substeps; ++k) {
      const float t = k == 0 ? 0.0f : plan.fractionAt(k);
      bodyAt.push_back(placementAt(t));
      worldToBody.push_back(glm::inverse(bodyAt.back()));
    }
  auto collide = [&](int k, std::size_t first, std::size_t end, bool withFriction) {
    const glm::mat4& toBody = worldToBody[static_cast<std::size_t>(k)];
    const glm::mat4& toWorld = bodyAt[static_cast<std::size_t>(k)];
    for (std::size_t i = first; i < end; ++i) {
      if (particles_.inverseMasses[i] == 0.0f) continue;
      glm::vec3 position = transformPoint(toBody, particles_.positions[i]);
      const glm::vec3 previous = transformPoint(toBody, particles_.previousPositions[i]);
      if (collideParticle(colliders_, position, previous, withFriction ? colliders_.friction : 0.0f))
        particles_.positions[i] = transformPoint(toWorld, position);
    }
  };
  // Each pin's straight path over the frame: between the body's two placements, or from where
  // it is to its target.
  pinFrom_.resize(pinned_.size());
  pinTo_.resize(pinned_.size());
  for (std::size_t p = 0; p < pinned_.size(); ++p) {
    pinFrom_[p] =
        pinTargets_.empty() ? transformPoint(previousBody_, pinnedLocal_[p]) : particles_.positions[pinned_[p]];
    pinTo_[p] = pinTargets_.empty() ? transformPoint(body_, pinnedLocal_[p]) : pinTargets_[p];
  }
  for (int k = 1; k <= plan.substeps; ++k) {
    const float t = plan.fractionAt(k);
    for (std::size_t p = 0; p < pinned_.size(); ++p) {
      // At the frame's end exactly on the placement (from + (to − from)·1 may round off it),
      // so a pin that follows targets starts the next frame where a body-carried one would.
      const glm::vec3 from = pinFrom_[p], to = pinTo_[p];
      particles_.positions[pinned_[p]] = t >= 1.0f ? to : from + (to - from) * t;
      particles_.previousPositions[pinned_[p]] = particles_.positions[pinned_[p]];
    }
    if (wind_)
      runPhase([&](std::uint32_t w) {
        const auto [first, end] = slice(wind_->triangleCount(), w);
        wind_->computeForces(particles_.positions, particles_.previousPositions, step, first, end);
      });
    runPhase([&](std::uint32_t w) {
      const auto [first, end] = slice(particles_.size(), w);
      integrateVerlet(particles_, first, end - first, settings_.solver.gravity, settings_.solver.damping, step);
      if (wind_)
        for (std::size_t i = first; i < end; ++i)
          if (particles_.inverseMasses[i] > 0.0f)
            particles_.positions[i] += wind_->acceleration(static_cast<std::uint32_t>(i)) * (step * step);
      if (!colliders_.empty()) collide(k, first, end, true);
    });
    if (!shapeHolds_.empty()) {
      const glm::mat4 placement = placementAt(t);
      for (std::size_t h = 0; h < shapeHolds_.size(); ++h) {
        glm::vec3& position = particles_.positions[shapeHolds_[h].vertex];
        position += (transformPoint(placement, heldLocal_[h]) - position) * shapeHolds_[h].stiffness;
      }
    }
    for (int iteration = 0; iteration < settings_.solver.constraintIterations; ++iteration)
      for (std::size_t colour = 0; colour < colourCount; ++colour)
        runPhase([&](std::uint32_t w) {
          const auto [from, to] = slice(colourStarts_[colour + 1] - colourStarts_[colour], w);
          relaxColour(colour, from, to);
        });
    // Tethers last in the step (one particle each, sorted: a slice per task), so no free vertex
    // ends it beyond its path length from its pin.
    if (!tethers_.empty())
      runPhase([&](std::uint32_t w) {
        const auto [from, to] = slice(tethers_.size(), w);
        for (std::size_t i = from; i < to; ++i)
          projectTether(particles_.positions[tethers_[i].particle], particles_.positions[tethers_[i].anchor],
                        tethers_[i].maxDistance);
      });
    if (selfCollision_) selfCollision_->resolve(particles_);
    if (!colliders_.empty())
      runPhase([&](std::uint32_t w) {
        const auto [first, end] = slice(particles_.size(), w);
        collide(k, first, end, false);
      });
  }
  previousBody_ = body_;

  if (!ran) return fail("cloth: " + ran.error().message);
  for (std::size_t i = 0; i < particles_.size(); ++i)
    if (!finite(particles_.positions[i]))
      return fail("cloth particle " + std::to_string(i) + " became NaN or infinite by fixed step " +
                  std::to_string(accumulator_.stepsTaken()));
  return {};
}

std::uint64_t Cloth::stateHash() const noexcept {
  StateHasher hasher;
  hasher.add(std::span<const glm::vec3>(particles_.positions));
  hasher.add(std::span<const glm::vec3>(particles_.previousPositions));
  hasher.addValue(accumulator_.backlog());
  hasher.addValue(accumulator_.stepsTaken());
  return hasher.value();
}

}  // namespace mane::physics
