#include "render/fur_surfaces.hpp"

#include <string>

namespace mane::render {

Result<FurSurfaces> FurSurfaces::create(const Device& device, const StaticScene& scene, const FurPassSettings& target,
                                        const HairShadowPass& shadows) {
  FurSurfaces result;
  for (std::size_t f = 0; f < scene.furs.size(); ++f) {
    const FurSurfaceData& entry = scene.furs[f];
    const std::string name = "fur " + std::to_string(f);
    if (entry.mesh >= scene.meshes.size() || entry.material >= scene.materials.size())
      return fail(name + ": mesh " + std::to_string(entry.mesh) + " or material " + std::to_string(entry.material) +
                  " is not in the scene");
    const MaterialData& material = scene.materials[entry.material];
    if (material.shading != SurfaceShading::kFur)
      return fail(name + ": material " + std::to_string(entry.material) + " is not a fur material");
    if (!material.albedo) return fail(name + ": its material has no photo (albedo texture) to grow the fur from");
    const FurParameters& fur = material.fur;
    FurPassSettings settings = target;
    settings.fins = fur.fins;
    auto pass = FurPass::create(device, settings, *material.albedo,
                                FurShellSettings{.layers = fur.layers, .thickness = fur.thickness}, &shadows);
    if (!pass) return fail(name + ": " + pass.error().message);
    if (auto set = (*pass)->setMesh(scene.meshes[entry.mesh]); !set)
      return fail(name + " (mesh " + std::to_string(entry.mesh) + "): " + set.error().message);
    result.furs_.push_back({.mesh = entry.mesh,
                            .material = entry.material,
                            .look = {.layAngle = fur.layAngle,
                                     .specularExponent = fur.specularExponent,
                                     .specularStrength = fur.specularStrength,
                                     .tint = material.baseColor,
                                     .comb = fur.comb,
                                     .layDirection = fur.layDirection,
                                     .layRepeatsPerMetre = fur.layRepeatsPerMetre,
                                     .doubleSided = material.doubleSided,
                                     .pixelsPerLayer = fur.pixelsPerLayer},
                            .pass = std::move(*pass)});
  }
  return result;
}

std::vector<HairShadowPass::Groom> FurSurfaces::shadowCasters() const {
  std::vector<HairShadowPass::Groom> casters;
  for (const Fur& fur : furs_)
    casters.push_back({.strands = fur.pass->shadowStrands(),
                       .width = fur.pass->shadowColumnWidth(),
                       .opacity = kFurColumnOpacity,
                       .extinction = 1.0f,
                       .resolution = fur.pass->shadowResolution()});
  return casters;
}

void FurSurfaces::refreshShadows() {
  for (Fur& fur : furs_) fur.pass->refreshShadows();
}

void FurSurfaces::setShadowUniforms(const HairShadowUniforms& uniforms) {
  for (Fur& fur : furs_) fur.pass->setShadowUniforms(uniforms);
}

bool FurSurfaces::draws(const MeshInstance& instance, const FrameInput& frame) const {
  if (!frame.furShells) return false;
  for (const Fur& fur : furs_)
    if (fur.mesh == instance.mesh && fur.material == instance.material) return true;
  return false;
}

Result<void> FurSurfaces::update(const FrameInput& frame, glm::vec3 ambient, const SphericalHarmonics9& environment,
                                 vk::Extent2D extent, float aspect) {
  const glm::mat4 viewProjection = frame.camera.projection(aspect) * frame.camera.view();
  const DirectionalLight light = frame.lights.empty() ? DirectionalLight{.intensity = 0.0f} : frame.lights[0];
  for (std::size_t f = 0; f < furs_.size(); ++f) {
    Fur& fur = furs_[f];
    fur.drawn = false;
    if (!frame.furShells) continue;
    for (const MeshInstance& instance : frame.instances) {
      if (instance.mesh != fur.mesh || instance.material != fur.material) continue;
      if (auto updated = fur.pass->update({.model = instance.model,
                                           .viewProjection = viewProjection,
                                           .eye = glm::vec4(frame.camera.position, 1.0f),
                                           .extent = extent,
                                           .light = light,
                                           .ambient = ambient,
                                           .environment = environment,
                                           .look = fur.look});
          !updated)
        return fail("fur " + std::to_string(f) + ": " + updated.error().message);
      fur.drawn = true;
      break;
    }
  }
  return {};
}

void FurSurfaces::draw(const vk::raii::CommandBuffer& commands) const {
  for (const Fur& fur : furs_)
    if (fur.drawn) fur.pass->draw(commands);
}

Result<void> FurSurfaces::setLeans(std::size_t fur, std::span<const glm::vec3> leans) {
  if (fur >= furs_.size())
    return fail("fur " + std::to_string(fur) + " is not in the scene (it has " + std::to_string(furs_.size()) + ")");
  if (auto set = furs_[fur].pass->setLeans(leans); !set)
    return fail("fur " + std::to_string(fur) + ": " + set.error().message);
  return {};
}

Result<void> FurSurfaces::setPose(std::size_t fur, std::span<const glm::vec4> positions,
                                  std::span<const glm::vec4> normals) {
  if (fur >= furs_.size())
    return fail("fur " + std::to_string(fur) + " is not in the scene (it has " + std::to_string(furs_.size()) + ")");
  if (auto set = furs_[fur].pass->setPose(positions, normals); !set)
    return fail("fur " + std::to_string(fur) + ": " + set.error().message);
  return {};
}

}  // namespace mane::render
