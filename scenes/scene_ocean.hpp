#pragma once
// A scene's sea and the ship that floats on it: the waves (physics/ocean_waves.hpp), the ship's
// body (physics/floating_body.hpp), the spray it throws up and its cannon's smoke
// (physics/effect_particles.hpp) and the debris afloat (physics/floating_debris.hpp), all stepped
// at the scene's fixed step, and what the renderer is given of them.

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/mat4x4.hpp>

#include "common/error.hpp"
#include "physics/effect_particles.hpp"
#include "physics/floating_body.hpp"
#include "physics/floating_debris.hpp"
#include "physics/split_mix64.hpp"
#include "physics/hash.hpp"
#include "physics/ocean_waves.hpp"
#include "physics/solver.hpp"
#include "render/frame.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {

/// The hull of a closed mesh as upright cells: the cells of a grid of `cells` (along x, y, z)
/// over its bounds whose centres lie inside it (an odd number of its triangles above them),
/// in model units times `scale`. Errors: no triangles, or no cell inside.
[[nodiscard]] Result<std::vector<physics::HullCell>> hullCells(const Mesh& mesh, float scale, glm::ivec3 cells);

class SceneOcean {
public:
  /// The sea of `scene` (which has one), with its ship when it has one, floating `shipMesh`
  /// (the ship's mesh as loaded, of scene mesh `shipIndex`).
  [[nodiscard]] static Result<SceneOcean> create(const Scene& scene, const Mesh* shipMesh, std::size_t shipIndex);

  /// Steps the ship, its spray and smoke and the debris over the frame that ends at `time`,
  /// lasting `frameDt` seconds, the ship's water found on `threads` workers (the state does not
  /// depend on them). Errors: the worker pool's, named (the frame is still stepped whole).
  [[nodiscard]] Result<void> advance(double time, double frameDt, unsigned threads);
  /// A sea grown by a wind of `speed` m/s from now on, blowing the same way; the waves change at
  /// once. Errors: a speed the waves refuse.
  [[nodiscard]] Result<void> setWindSpeed(float speed);
  [[nodiscard]] float windSpeed() const { return settings_.waves.windSpeed; }
  /// Drops the spray thrown while the world settled (the ship finding its draft, the clock held
  /// at 0): the first frame shows the sea as it is, not the ship's fall into it.
  void forgetSettlingSpray() {
    if (spray_) spray_->removeIf([](const physics::EffectParticle&) { return true; });
  }
  /// What the sails hand to the ship from now on (physics::FloatingBody::setLoad); nothing
  /// without a ship. Errors: a value that is not finite.
  [[nodiscard]] Result<void> setShipLoad(const glm::vec3& force, const glm::vec3& torque) {
    return ship_ ? ship_->setLoad(force, torque) : Result<void>{};
  }
  /// Fires the ship's cannon at the next step (nothing without one).
  void fireCannon() { cannonFired_ = true; }

  [[nodiscard]] const physics::OceanWaves& waves() const { return waves_; }
  /// The air's velocity over the sea, m/s: on the sails, the spray and the smoke.
  [[nodiscard]] glm::vec3 wind() const { return wind_; }
  [[nodiscard]] render::OceanData oceanData() const;
  /// The waves' phases at `time`, and the foam's step.
  [[nodiscard]] render::OceanFrame frame(double time, float seconds) const;

  /// The scene mesh that floats, if any.
  [[nodiscard]] std::optional<std::size_t> shipMesh() const { return ship_ ? std::optional(shipIndex_) : std::nullopt; }
  /// The ship's mesh's model matrix now, and its body frame (the same without the scale).
  [[nodiscard]] glm::mat4 shipModel() const;
  /// The ellipsoid inscribed in the hull's bounds where the ship is now, which the debris keeps
  /// out of and the water reflects; none without a ship.
  [[nodiscard]] std::optional<physics::DebrisObstacle> hullObstacle() const;
  [[nodiscard]] glm::mat4 shipBody() const;
  [[nodiscard]] const physics::FloatingBody* ship() const { return ship_ ? &*ship_ : nullptr; }
  [[nodiscard]] const physics::EffectParticles* spray() const { return spray_ ? &*spray_ : nullptr; }
  [[nodiscard]] const physics::EffectParticles* smoke() const { return smoke_ ? &*smoke_ : nullptr; }
  [[nodiscard]] const physics::FloatingDebris* debris() const { return debris_ ? &*debris_ : nullptr; }
  /// The spray, the smoke, the rigging and the debris, as the renderer draws them.
  [[nodiscard]] render::EffectsFrame effects() const;

  void hash(physics::StateHasher& hasher) const;

private:
  SceneOcean(const Scene& scene, physics::OceanWaves waves);
  [[nodiscard]] Result<void> addShip(const Scene& scene, const Mesh* shipMesh, std::size_t shipIndex);
  [[nodiscard]] Result<void> step(double time, float dt, const physics::TaskRunner& tasks);
  void throwSpray(float dt);
  void shoot();

  Ocean settings_;
  physics::OceanWaves waves_;
  float crestHeight_ = 0.0f;  ///< no water rises higher: Σ A
  glm::vec3 wind_{0.0f};  ///< m/s, at the sails
  std::optional<physics::FloatingBody> ship_;
  std::size_t shipIndex_ = 0;
  glm::vec3 centreOfMass_{0.0f};  ///< in the mesh's model space × scale
  float shipScale_ = 1.0f;
  glm::mat4 hullEllipsoid_{1.0f};  ///< in the hull's model space, from the unit sphere
  glm::vec3 hullAlbedo_{0.0f};
  glm::vec2 foamCentre_{0.0f};
  std::optional<physics::FixedStepAccumulator> steps_;
  std::optional<Ship> shipScene_;
  std::optional<physics::EffectParticles> spray_;
  std::optional<physics::EffectParticles> smoke_;
  std::optional<physics::FloatingDebris> debris_;
  physics::SplitMix64 random_{0x5EA5};  ///< where spray and smoke start, and how fast
  double nextShot_ = -1.0;              ///< when the cannon fires by itself next; < 0: never
  bool cannonFired_ = false;
};

}  // namespace mane::scenes
