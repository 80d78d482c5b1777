#pragma once
// A groom's or cloth's `Colliders` entry (scene.hpp) turned into the physics::ColliderSet the
// solver uses, in the frame of the body it follows. Signed distance fields are built from the
// scene's meshes at load, once per (body, mesh, resolution), and shared by every groom and
// cloth that asks for the same one.

#include <cstddef>
#include <map>
#include <memory>
#include <span>
#include <tuple>
#include <vector>

#include "common/error.hpp"
#include "physics/colliders.hpp"
#include "physics/sdf.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_meshes.hpp"

namespace mane::scenes {

class SceneColliders {
public:
  /// `meshes` are the loaded geometry of `scene.meshes`, index for index (fallback spheres
  /// included: a field is then built from the sphere). Both must outlive this object.
  SceneColliders(const Scene& scene, std::span<const LoadedMesh> meshes) : scene_(scene), meshes_(meshes) {}

  /// The set for `colliders` on the body `scene.meshes[body]`: spheres and capsules as given
  /// (already in the body frame), friction, thickness and, when asked for, the field of the named
  /// mesh in the body frame. Fails when the field cannot be built (an empty or degenerate mesh)
  /// or `physics::validateColliders` rejects the set; the message names the mesh.
  [[nodiscard]] Result<physics::ColliderSet> build(const Colliders& colliders, std::size_t body);

private:
  using FieldKey = std::tuple<std::size_t, std::size_t, int>;  // body, mesh, resolution
  Result<std::shared_ptr<const physics::SignedDistanceField>> field(std::size_t body, const SdfColliderSource& source);

  const Scene& scene_;
  std::span<const LoadedMesh> meshes_;
  std::map<FieldKey, std::shared_ptr<const physics::SignedDistanceField>> fields_;
};

/// The positions of `scene.meshes[mesh]` (geometry `geometry`) in the body frame of
/// `scene.meshes[body]` at time 0: metres, as the body's colliders see them. For the body's own
/// mesh, its model positions times its scale.
[[nodiscard]] std::vector<glm::vec3> positionsInBodyFrame(const Scene& scene, const Mesh& geometry, std::size_t mesh,
                                                          std::size_t body);

}  // namespace mane::scenes
