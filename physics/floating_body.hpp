#pragma once
// A rigid body floating on the ocean: it heaves, pitches and rolls under gravity, buoyancy,
// the water's drag and the wind on its sails, and neither drifts nor turns about the vertical,
// as the ship of NVIDIA's "Clear Sailing" demo (2004) does. The waves do not feel the body.
//
// The hull is a set of upright boxes (cells) in the body frame. Cells that share their (x, z)
// form a column, and the sea's surface is found once per column, where its axis crosses the
// level of the centre of mass. Each cell's submerged share is its depth under that surface
// over its height, clamped to [0, 1]; the
// water pushes it up by ρ g V·share at the submerged part's centre (Archimedes) and drags it
// by ρ V·share·c·(v_water − v) (linear drag, c per second). Summed over the cells these give
// the heave force and the torques about the pitch and roll axes. An upright box hull of cells
// stacked through its height floats at exactly its Archimedes draft in calm water.
//
// Pitch and roll are angles about the body's lateral and long axes (the rotation is
// heading · pitch · roll); each is driven by the torque about its own axis over the body's
// moment of inertia about it, so the coupling between the two turns (small for a ship, whose
// angles stay within tens of degrees) is left out, as is the water the hull drags along
// (added mass). Semi-implicit Euler, fixed steps, + − × ÷ and sqrt: deterministic.

#include <span>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/ocean_waves.hpp"
#include "physics/task_runner.hpp"

namespace mane::physics {

/// An upright box of the hull's watertight volume, in the body frame (x towards the bow, y up,
/// z to starboard; origin at the centre of mass).
struct HullCell {
  glm::vec3 centre{0.0f};
  glm::vec3 size{1.0f};  ///< metres, each > 0
};

struct FloatingBodySettings {
  float mass = 1000.0f;          ///< kg, > 0; spread evenly over the hull's cells for its inertia
  glm::vec3 position{0.0f};      ///< the centre of mass at rest: (x, z) it keeps, y it starts at
  float heading = 0.0f;          ///< radians about +y from +x, kept
  float waterDensity = 1025.0f;  ///< kg/m³, > 0 (sea water)
  float dragPerSecond = 0.5f;    ///< c, 1/s, ≥ 0
  std::vector<HullCell> hull;    ///< at least one
  glm::vec3 sailCentre{0.0f};    ///< body frame: where the wind's force on the sails acts
  float sailArea = 0.0f;         ///< m² facing the wind, ≥ 0 (drag coefficient 1, a flat plate)
};

/// What moves: the centre of mass's height and the two angles, with their rates.
struct FloatingBodyState {
  float height = 0.0f;         ///< m
  float heaveVelocity = 0.0f;  ///< m/s
  float pitch = 0.0f;          ///< radians, bow up
  float pitchRate = 0.0f;      ///< rad/s
  float roll = 0.0f;           ///< radians, starboard down
  float rollRate = 0.0f;       ///< rad/s
};

/// Where the sea's surface meets the hull's side in the last step, as spray would leave it.
struct WaterlineContact {
  glm::vec3 position{0.0f};  ///< on the surface, at the hull's side (world)
  glm::vec2 rest{0.0f};      ///< (x, z) where the water there rests, to first order
  glm::vec3 outward{0.0f};   ///< horizontal unit normal of the hull's side there (world)
  /// m/s: how fast the hull cuts into the water there, max(0, u·outward) + max(0, −u_y) with
  /// u the hull's velocity less the water's.
  float cutSpeed = 0.0f;
};

/// The density of air, kg/m³ (ISA at sea level).
inline constexpr float kAirDensity = 1.225f;

class FloatingBody {
public:
  /// Fails on settings out of the documented ranges, naming the field (and the cell).
  [[nodiscard]] static Result<FloatingBody> create(FloatingBodySettings settings);

  /// Advances by `dt` seconds on `ocean` as it is at `time`, with air moving at `wind` (m/s).
  /// The sea's surface over the columns is found on `tasks` (by default on this thread); the
  /// state does not depend on them. Errors: a failing runner, named (the step is still whole).
  [[nodiscard]] Result<void> step(const OceanWaves& ocean, double time, float dt, const glm::vec3& wind,
                                  const TaskRunner& tasks = {});

  /// A load besides the sea's and the wind's on `sailArea`, as cloth hung on the body hands it
  /// on: a force (N, world) and a torque about the centre of mass (N m, world), acting in every
  /// step until replaced. Only its vertical force and its torques about the pitch and roll axes
  /// move the body. Fails, changing nothing, on a value that is not finite.
  [[nodiscard]] Result<void> setLoad(const glm::vec3& force, const glm::vec3& torque);

  /// Body to world.
  [[nodiscard]] glm::mat4 transform() const;
  [[nodiscard]] const FloatingBodyState& state() const { return state_; }
  void setState(const FloatingBodyState& state) { state_ = state; }
  [[nodiscard]] const FloatingBodySettings& settings() const { return settings_; }
  /// The hull's side columns (those missing a neighbour in the cells' grid) whose height spans
  /// the sea's surface at the last step, in the order of the columns.
  [[nodiscard]] const std::vector<WaterlineContact>& waterline() const { return waterline_; }

  /// Moments of inertia about the lateral (pitch) and long (roll) axes through the centre of
  /// mass, kg m², of the mass spread evenly over the cells.
  [[nodiscard]] float pitchInertia() const { return pitchInertia_; }
  [[nodiscard]] float rollInertia() const { return rollInertia_; }

private:
  /// Cells that share (x, z) in the body frame: the range [first, end) of `settings_.hull`,
  /// which `create` sorts by column.
  struct Column {
    glm::vec3 axis{0.0f};  ///< (x, 0, z)
    std::size_t first = 0;
    std::size_t end = 0;
    glm::vec3 outward{0.0f};  ///< towards its missing neighbours, unit; zero inside the hull
    float bottom = 0.0f;      ///< of its lowest cell
    float top = 0.0f;         ///< of its highest cell
  };

  FloatingBody(FloatingBodySettings settings, std::vector<Column> columns, float pitchInertia, float rollInertia);
  void recordWaterline(const Column& column, const glm::mat3& turn, const glm::vec3& centre,
                       const glm::vec3& angularVelocity, const OceanSample& water);

  FloatingBodySettings settings_;
  std::vector<Column> columns_;
  FloatingBodyState state_;
  std::vector<WaterlineContact> waterline_;
  std::vector<OceanSample> columnWater_;  // the sea's surface over each column, this step
  glm::vec3 loadForce_{0.0f};             // setLoad's
  glm::vec3 loadTorque_{0.0f};
  float pitchInertia_;
  float rollInertia_;
};

}  // namespace mane::physics
