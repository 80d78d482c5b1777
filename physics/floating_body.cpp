#include "physics/floating_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <glm/common.hpp>

#include "physics/detail/hair_math.hpp"
#include "physics/detail/parallel_tasks.hpp"
#include "physics/detail/portable_math.hpp"

namespace mane::physics {

namespace {

// A column's water takes a few evaluations of every wave: a handful of columns outweigh a task's
// start.
constexpr std::size_t kColumnsPerTask = 8;

float dot(const glm::vec3& a, const glm::vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// heading · pitch · roll: about +y, then the lateral z, then the long x.
glm::mat3 rotation(float heading, float pitch, float roll) {
  const detail::SineCosine h = detail::sineCosine(heading);
  const detail::SineCosine p = detail::sineCosine(pitch);
  const detail::SineCosine r = detail::sineCosine(roll);
  const auto f = [](double v) { return static_cast<float>(v); };
  const glm::mat3 yaw(f(h.cosine), 0.0f, f(-h.sine), 0.0f, 1.0f, 0.0f, f(h.sine), 0.0f, f(h.cosine));
  const glm::mat3 pitchTurn(f(p.cosine), f(p.sine), 0.0f, f(-p.sine), f(p.cosine), 0.0f, 0.0f, 0.0f, 1.0f);
  const glm::mat3 rollTurn(1.0f, 0.0f, 0.0f, 0.0f, f(r.cosine), f(r.sine), 0.0f, f(-r.sine), f(r.cosine));
  return yaw * pitchTurn * rollTurn;
}

}  // namespace

Result<FloatingBody> FloatingBody::create(FloatingBodySettings settings) {
  const auto bad = [](const std::string& field, const char* expected) {
    return fail("Floating body: " + field + " must be " + expected + ".");
  };
  if (!(std::isfinite(settings.mass) && settings.mass > 0.0f)) return bad("mass", "positive (kg)");
  if (!detail::isFinite(settings.position)) return bad("position", "finite");
  if (!std::isfinite(settings.heading)) return bad("heading", "finite");
  if (!(std::isfinite(settings.waterDensity) && settings.waterDensity > 0.0f)) return bad("waterDensity", "positive");
  if (!(std::isfinite(settings.dragPerSecond) && settings.dragPerSecond >= 0.0f)) return bad("dragPerSecond", "≥ 0");
  if (!detail::isFinite(settings.sailCentre)) return bad("sailCentre", "finite");
  if (!(std::isfinite(settings.sailArea) && settings.sailArea >= 0.0f)) return bad("sailArea", "≥ 0");
  if (settings.hull.empty()) return bad("hull", "at least one cell");
  double volume = 0.0;
  for (std::size_t i = 0; i < settings.hull.size(); ++i) {
    const HullCell& cell = settings.hull[i];
    if (!detail::isFinite(cell.centre)) return bad("hull cell " + std::to_string(i) + "'s centre", "finite");
    if (!(detail::isFinite(cell.size) && cell.size.x > 0.0f && cell.size.y > 0.0f && cell.size.z > 0.0f))
      return bad("hull cell " + std::to_string(i) + "'s size", "positive on every axis");
    volume += static_cast<double>(cell.size.x) * cell.size.y * cell.size.z;
  }
  // Each cell a uniform box of its share of the mass: its own moment plus the parallel axis.
  double pitch = 0.0;
  double roll = 0.0;
  for (const HullCell& cell : settings.hull) {
    const glm::dvec3 c(cell.centre);
    const glm::dvec3 s(cell.size);
    const double m = settings.mass * (s.x * s.y * s.z) / volume;
    pitch += m * (c.x * c.x + c.y * c.y + (s.x * s.x + s.y * s.y) / 12.0);
    roll += m * (c.y * c.y + c.z * c.z + (s.y * s.y + s.z * s.z) / 12.0);
  }
  std::stable_sort(settings.hull.begin(), settings.hull.end(), [](const HullCell& a, const HullCell& b) {
    return a.centre.x < b.centre.x || (a.centre.x == b.centre.x && a.centre.z < b.centre.z);
  });
  std::vector<Column> columns;
  for (std::size_t i = 0; i < settings.hull.size(); ++i) {
    const glm::vec3 c = settings.hull[i].centre;
    if (columns.empty() || columns.back().axis.x != c.x || columns.back().axis.z != c.z)
      columns.push_back({.axis = {c.x, 0.0f, c.z}, .first = i, .end = i});
    columns.back().end = i + 1;
  }
  // The cells' grid: a column is on the hull's side where a neighbour a cell away is missing
  // (within a quarter of a cell, far beyond the rounding of the cells' centres).
  const auto has = [&columns](float x, float z, const glm::vec3& size) {
    return std::ranges::any_of(columns, [&](const Column& c) {
      return std::abs(c.axis.x - x) < 0.25f * size.x && std::abs(c.axis.z - z) < 0.25f * size.z;
    });
  };
  for (Column& column : columns) {
    const glm::vec3 size = settings.hull[column.first].size;
    column.bottom = std::numeric_limits<float>::max();
    column.top = std::numeric_limits<float>::lowest();
    for (std::size_t i = column.first; i < column.end; ++i) {
      column.bottom = std::min(column.bottom, settings.hull[i].centre.y - 0.5f * settings.hull[i].size.y);
      column.top = std::max(column.top, settings.hull[i].centre.y + 0.5f * settings.hull[i].size.y);
    }
    glm::vec3 out(0.0f);
    const glm::vec3 a = column.axis;
    if (!has(a.x + size.x, a.z, size)) out.x += 1.0f;
    if (!has(a.x - size.x, a.z, size)) out.x -= 1.0f;
    if (!has(a.x, a.z + size.z, size)) out.z += 1.0f;
    if (!has(a.x, a.z - size.z, size)) out.z -= 1.0f;
    const float length = std::sqrt(dot(out, out));
    if (length > 0.0f) column.outward = out / length;
  }
  return FloatingBody(std::move(settings), std::move(columns), static_cast<float>(pitch), static_cast<float>(roll));
}

FloatingBody::FloatingBody(FloatingBodySettings settings, std::vector<Column> columns, float pitchInertia,
                           float rollInertia)
    : settings_(std::move(settings)),
      columns_(std::move(columns)),
      pitchInertia_(pitchInertia),
      rollInertia_(rollInertia) {
  state_.height = settings_.position.y;
}

Result<void> FloatingBody::setLoad(const glm::vec3& force, const glm::vec3& torque) {
  if (!detail::isFinite(force) || !detail::isFinite(torque))
    return fail("floating body: the load's force and torque must be finite.");
  loadForce_ = force;
  loadTorque_ = torque;
  return {};
}

Result<void> FloatingBody::step(const OceanWaves& ocean, double time, float dt, const glm::vec3& wind,
                                const TaskRunner& tasks) {
  const glm::mat3 turn = rotation(settings_.heading, state_.pitch, state_.roll);
  const glm::vec3 centre(settings_.position.x, state_.height, settings_.position.z);
  // ω = ṗ·(heading's z) + ṙ·(heading·pitch's x): exact for this order of turns.
  const glm::mat3 yaw = rotation(settings_.heading, 0.0f, 0.0f);
  const glm::vec3 pitchAxis = yaw[2];
  const glm::vec3 rollAxis = rotation(settings_.heading, state_.pitch, 0.0f)[0];
  const glm::vec3 angularVelocity = state_.pitchRate * pitchAxis + state_.rollRate * rollAxis;

  const float gravity = kOceanGravity;
  const float rho = settings_.waterDensity;
  // Finding the water over each column is most of a step, and each column's is its own; the
  // forces are then summed in the columns' order, so the sum does not depend on the tasks.
  columnWater_.resize(columns_.size());
  const std::uint32_t taskCount = detail::taskCountFor(tasks, columns_.size(), kColumnsPerTask);
  auto findWater = [&](std::uint32_t task) {
    const std::size_t end = detail::taskRangeBegin(columns_.size(), taskCount, task + 1);
    for (std::size_t c = detail::taskRangeBegin(columns_.size(), taskCount, task); c < end; ++c) {
      const glm::vec3 axis = centre + turn * columns_[c].axis;
      columnWater_[c] = ocean.surfaceAt({axis.x, axis.z}, time);
    }
  };
  const Result<void> found = detail::runTasks(tasks, taskCount, findWater);
  glm::vec3 force(0.0f, -settings_.mass * gravity, 0.0f);
  glm::vec3 torque(0.0f);
  waterline_.clear();
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const Column& column = columns_[c];
    const OceanSample& water = columnWater_[c];
    if (column.outward != glm::vec3(0.0f)) recordWaterline(column, turn, centre, angularVelocity, water);
    for (std::size_t i = column.first; i < column.end; ++i) {
      const HullCell& cell = settings_.hull[i];
      const glm::vec3 arm = turn * cell.centre;
      const glm::vec3 at = centre + arm;
      const float bottom = at.y - 0.5f * cell.size.y;
      const float share = std::clamp((water.position.y - bottom) / cell.size.y, 0.0f, 1.0f);
      if (share <= 0.0f) continue;
      const float submerged = cell.size.x * cell.size.y * cell.size.z * share;
      const glm::vec3 velocity = glm::vec3(0.0f, state_.heaveVelocity, 0.0f) + detail::cross(angularVelocity, arm);
      const glm::vec3 push = glm::vec3(0.0f, rho * gravity * submerged, 0.0f) +
                             (rho * submerged * settings_.dragPerSecond) * (water.velocity - velocity);
      // The buoyancy acts at the submerged part's centre: half its depth above the bottom.
      const glm::vec3 lever(arm.x, bottom + 0.5f * share * cell.size.y - centre.y, arm.z);
      force += push;
      torque += detail::cross(lever, push);
    }
  }
  if (settings_.sailArea > 0.0f) {
    const float speed = std::sqrt(dot(wind, wind));
    const glm::vec3 push = (0.5f * kAirDensity * settings_.sailArea * speed) * wind;
    force += push;
    torque += detail::cross(turn * settings_.sailCentre, push);
  }
  force += loadForce_;
  torque += loadTorque_;
  // The body keeps its (x, z) and heading: only the vertical force and the two torques act.
  state_.heaveVelocity += dt * force.y / settings_.mass;
  state_.pitchRate += dt * dot(torque, pitchAxis) / pitchInertia_;
  state_.rollRate += dt * dot(torque, rollAxis) / rollInertia_;
  state_.height += dt * state_.heaveVelocity;
  state_.pitch += dt * state_.pitchRate;
  state_.roll += dt * state_.rollRate;
  if (!found) return fail("floating body: " + found.error().message);
  return {};
}

void FloatingBody::recordWaterline(const Column& column, const glm::mat3& turn, const glm::vec3& centre,
                                   const glm::vec3& angularVelocity, const OceanSample& water) {
  const float height = water.position.y - centre.y;
  const glm::vec3 lowest = turn * glm::vec3(column.axis.x, column.bottom, column.axis.z);
  const glm::vec3 highest = turn * glm::vec3(column.axis.x, column.top, column.axis.z);
  if (height < lowest.y || height > highest.y) return;
  const glm::vec3 arm(column.axis.x, 0.0f, column.axis.z);
  // Out to the side of its cell: a corner column to its corner.
  const glm::vec3 side = turn * (arm + glm::sign(column.outward) * 0.5f * settings_.hull[column.first].size);
  const glm::vec3 at(centre.x + side.x, water.position.y, centre.z + side.z);
  glm::vec3 outward = turn * column.outward;
  outward.y = 0.0f;
  const float length = std::sqrt(dot(outward, outward));
  if (length <= 0.0f) return;
  outward /= length;
  const glm::vec3 hull = glm::vec3(0.0f, state_.heaveVelocity, 0.0f) + detail::cross(angularVelocity, at - centre);
  const glm::vec3 u = hull - water.velocity;
  // The water at the side rests about as far from the axis's as it lies from it (the waves'
  // horizontal map is near the identity over a cell).
  const glm::vec2 rest = water.rest + glm::vec2(at.x - water.position.x, at.z - water.position.z);
  waterline_.push_back({.position = at,
                        .rest = rest,
                        .outward = outward,
                        .cutSpeed = std::max(0.0f, dot(u, outward)) + std::max(0.0f, -u.y)});
}

glm::mat4 FloatingBody::transform() const {
  glm::mat4 m(rotation(settings_.heading, state_.pitch, state_.roll));
  m[3] = glm::vec4(settings_.position.x, state_.height, settings_.position.z, 1.0f);
  return m;
}

}  // namespace mane::physics
