#pragma once
// A scene's cloth entry brought to life: the physics::Cloth built from its mesh, and the
// surface the renderer draws, refreshed from the particles every frame.

#include <filesystem>
#include <span>
#include <string>

#include <glm/mat4x4.hpp>

#include "common/error.hpp"
#include "physics/cloth.hpp"
#include "scenes/assets.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {

/// The cloth entry's rest mesh in its own local space (before `Cloth::transform`): the 16 × 16
/// "procedural:grid" (1 m square in the XY plane, top edge at y = 0, hanging to y = −1), the
/// "procedural:cape" cut as `cloth.cape` says, the "procedural:fin" `cloth.fin` describes
/// (scenes/fin_cloth.hpp), or a mesh file resolved like the scene's meshes.
Result<Mesh> loadClothMesh(const Cloth& cloth, const AssetResolver& resolver,
                           const std::filesystem::path& sceneDirectory);

class SceneCloth {
public:
  /// `body` is the rigid placement (no scale) of the attached mesh at time 0: cloth-local
  /// points go through `cloth.transform` into body space, then `body` into the world.
  /// `colliders` are in body space (see `SceneColliders`); empty: none.
  static Result<SceneCloth> create(const Cloth& cloth, Mesh rest, const SimulationSettings& simulation,
                                   const glm::mat4& body, physics::ColliderSet colliders = {});

  /// Pins that follow a deforming body: where each pinned vertex (`cloth().pinnedVertices()`
  /// order) is at the end of the next advance, world space (physics::Cloth::setPinTargets).
  Result<void> setPinTargets(std::span<const glm::vec3> positions);
  /// The air's velocity on the cloth from now on, world m/s.
  Result<void> setWind(const glm::vec3& velocity) { return cloth_.setWind(velocity); }
  /// Replaces what the cloth collides with (body frame), e.g. shapes carried by moving joints.
  Result<void> setColliders(physics::ColliderSet colliders);

  /// Moves the body (and, unless pin targets were set, the pins) to `body` over the frame and
  /// simulates `frameDt` seconds.
  Result<void> advance(const glm::mat4& body, double frameDt, unsigned threads);

  /// World-space surface: positions from the particles, smooth normals, the rest mesh's uvs.
  const Mesh& surface() const { return surface_; }
  const physics::Cloth& cloth() const { return cloth_; }
  /// What the cloth collides with, in the body frame (metres).
  const physics::ColliderSet& colliders() const { return colliders_; }

private:
  SceneCloth(physics::Cloth cloth, Mesh surface) : cloth_(std::move(cloth)), surface_(std::move(surface)) {}
  void refreshSurface();

  physics::Cloth cloth_;
  std::string name_;
  Mesh surface_;
  physics::ColliderSet colliders_;
};

}  // namespace mane::scenes
