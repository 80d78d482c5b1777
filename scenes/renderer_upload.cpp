#include "scenes/renderer_upload.hpp"

namespace mane::scenes {

Result<void> uploadFrameState(const World& world, render::Renderer& renderer) {
  for (const auto& mesh : world.dynamicMeshes())
    if (auto updated = renderer.updateMesh(mesh.mesh, mesh.positions, mesh.normals); !updated) return updated;
  for (const auto& hair : world.hairGuides())
    if (auto updated = renderer.updateHair(hair.groom, hair.positions); !updated) return updated;
  for (const auto& fur : world.furLeans())
    if (auto updated = renderer.updateFurLeans(fur.fur, fur.leans); !updated) return updated;
  return {};
}

Result<void> refineSubdivided(World& world, render::Renderer& renderer, const render::Camera& camera, glm::uvec2 size,
                              unsigned threads) {
  auto refined = world.refineForCamera(camera, size, threads);
  if (!refined) return std::unexpected(refined.error());
  for (const std::size_t mesh : *refined)
    if (auto replaced = renderer.replaceMesh(mesh, world.meshData(mesh)); !replaced) return replaced;
  return {};
}

}  // namespace mane::scenes
