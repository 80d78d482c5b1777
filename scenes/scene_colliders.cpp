#include "scenes/scene_colliders.hpp"

#include <algorithm>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace mane::scenes {

std::vector<glm::vec3> positionsInBodyFrame(const Scene& scene, const Mesh& geometry, std::size_t mesh,
                                            std::size_t body) {
  std::vector<glm::vec3> out(geometry.positions.size());
  if (mesh == body) {
    // The body frame is the mesh's placement without its scale (bodyMatrix), so the mesh's model
    // space maps into it by the scale alone: exact, whatever the motion.
    const float scale = scene.meshes[body].transform.scale;
    for (std::size_t v = 0; v < out.size(); ++v) out[v] = geometry.positions[v] * scale;
    return out;
  }
  // Another mesh: where it stands relative to the body at time 0, then carried with the body.
  const glm::mat4 toBody =
      glm::inverse(bodyMatrix(scene, scene.meshes[body], 0.0f)) * animatedMatrix(scene, scene.meshes[mesh], 0.0f);
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = glm::vec3(toBody * glm::vec4(geometry.positions[v], 1.0f));
  return out;
}

Result<std::shared_ptr<const physics::SignedDistanceField>> SceneColliders::field(std::size_t body,
                                                                                  const SdfColliderSource& source) {
  const auto meshIt = std::find_if(scene_.meshes.begin(), scene_.meshes.end(),
                                   [&](const MeshInstance& m) { return m.name == source.mesh; });
  if (meshIt == scene_.meshes.end()) return fail("sdf: no mesh named \"" + source.mesh + "\" in meshes");
  const auto mesh = static_cast<std::size_t>(meshIt - scene_.meshes.begin());
  const FieldKey key{body, mesh, source.resolution};
  if (const auto found = fields_.find(key); found != fields_.end()) return found->second;
  const Mesh& geometry = meshes_[mesh].mesh;
  const std::vector<glm::vec3> positions = positionsInBodyFrame(scene_, geometry, mesh, body);
  physics::SdfSettings settings;
  settings.resolution = source.resolution;
  auto built = physics::SignedDistanceField::build(positions, geometry.indices, settings);
  if (!built) return fail("sdf of mesh " + source.mesh + ": " + built.error().message);
  auto shared = std::make_shared<const physics::SignedDistanceField>(std::move(*built));
  fields_.emplace(key, shared);
  return shared;
}

Result<physics::ColliderSet> SceneColliders::build(const Colliders& colliders, std::size_t body) {
  physics::ColliderSet set;
  set.spheres = colliders.spheres;
  set.capsules = colliders.capsules;
  set.friction = colliders.friction;
  set.thickness = colliders.thickness;
  if (colliders.sdf) {
    auto sdf = field(body, *colliders.sdf);
    if (!sdf) return std::unexpected(sdf.error());
    set.sdf = std::move(*sdf);
  }
  if (auto valid = physics::validateColliders(set); !valid) return std::unexpected(valid.error());
  return set;
}

}  // namespace mane::scenes
