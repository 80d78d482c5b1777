#include "render/frame_validation.hpp"

namespace mane::render {

Result<void> validateMesh(const MeshData& mesh, const std::string& name) {
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    return fail(name + ": " + std::to_string(mesh.normals.size()) + " normals for " +
                std::to_string(mesh.positions.size()) + " positions");
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
    return fail(name + ": " + std::to_string(mesh.uvs.size()) + " uvs for " + std::to_string(mesh.positions.size()) +
                " positions");
  if (!mesh.curvatures.empty() && mesh.curvatures.size() != mesh.positions.size())
    return fail(name + ": " + std::to_string(mesh.curvatures.size()) + " curvatures for " +
                std::to_string(mesh.positions.size()) + " positions");
  if (mesh.indices.size() % 3 != 0) return fail(name + ": the index count is not a multiple of 3");
  if (mesh.skinning != nullptr) {
    if (mesh.dynamic) return fail(name + ": a mesh is either dynamic (updateMesh) or skinned, not both");
    if (mesh.skinning->positions.size() != mesh.positions.size() || mesh.normals.size() != mesh.positions.size() ||
        mesh.skinning->normals.size() != mesh.positions.size())
      return fail(name + ": a skinned mesh needs its bind pose's " + std::to_string(mesh.skinning->positions.size()) +
                  " positions and as many normals, in MeshData and its skinning; got " + std::to_string(mesh.positions.size()) + " and " +
                  std::to_string(mesh.normals.size()));
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= mesh.positions.size())
      return fail(name + ": index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) + " but there are " +
                  std::to_string(mesh.positions.size()) + " positions");
  return {};
}

Result<void> validateScene(const StaticScene& scene, const vk::PhysicalDeviceLimits& limits) {
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    if (auto valid = validateMesh(scene.meshes[m], "mesh " + std::to_string(m)); !valid) return valid;
  auto checkTexture = [&](const std::optional<TextureData>& texture, const std::string& name) -> Result<void> {
    if (!texture) return {};
    if (texture->width == 0 || texture->height == 0 ||
        texture->rgba.size() != std::size_t(texture->width) * texture->height * 4)
      return fail(name + ": " + std::to_string(texture->rgba.size()) + " bytes for a " +
                  std::to_string(texture->width) + "x" + std::to_string(texture->height) + " RGBA texture");
    if (texture->width > limits.maxImageDimension2D || texture->height > limits.maxImageDimension2D)
      return fail(name + ": " + std::to_string(texture->width) + "x" + std::to_string(texture->height) +
                  " exceeds the device's limit of " + std::to_string(limits.maxImageDimension2D));
    return {};
  };
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const std::string name = "material " + std::to_string(m);
    if (auto ok = checkTexture(scene.materials[m].albedo, name + " albedo"); !ok) return ok;
    if (auto ok = checkTexture(scene.materials[m].normalMap, name + " normal map"); !ok) return ok;
    if (auto ok = checkTexture(scene.materials[m].specularMap, name + " specular map"); !ok) return ok;
  }
  return {};
}

}  // namespace mane::render
