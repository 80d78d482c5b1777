#include "scenes/scene_environment.hpp"

#include <glm/trigonometric.hpp>

#include <cmath>
#include <string>

#include "render/environment/sky_model.hpp"
#include "render/environment/sun_extraction.hpp"
#include "scenes/environment_image.hpp"

namespace mane::scenes {
namespace {

constexpr int kPanoramaCubeSize = 256;  // a 1k panorama's texels are as wide as this cube's
constexpr int kSkyCubeSize = 64;        // the sky is smooth; its sun is the light's disc

render::CubeMap skyOf(const Scene& scene, const Environment& environment) {
  render::SkySettings sky{.turbidity = environment.turbidity,
                          .zenithLuminance = environment.intensity,
                          .groundAlbedo = environment.groundAlbedo};
  if (!scene.lights.empty()) {
    sky.towardSun = -scene.lights[0].direction;
    sky.sunLight = scene.lights[0].colour * scene.lights[0].intensity;
  }
  return render::skyCubeMap(sky, environment.cubeSize > 0 ? environment.cubeSize : kSkyCubeSize);
}

}  // namespace

Result<std::optional<SceneEnvironment>> loadSceneEnvironment(const Scene& scene, const AssetResolver& resolver,
                                                             std::vector<std::string>& notes) {
  if (!scene.environment) return std::nullopt;
  const Environment& environment = *scene.environment;
  if (!environment.file.empty()) {
    auto lookup = resolver.lookupForScene(environment.file, scene.file.parent_path());
    if (!lookup) return std::unexpected(lookup.error());
    if (lookup->path) {
      auto panorama = loadEnvironmentImage(*lookup->path);
      if (!panorama) return fail("environment: " + panorama.error().message);
      if (panorama->clampedTexels > 0)
        notes.push_back("environment: " + environment.file + ": " + std::to_string(panorama->clampedTexels) +
                        " texels brighter than " + std::to_string(kMaxPanoramaRadiance) + " clamped to it");
      if (panorama->zeroedTexels > 0)
        notes.push_back("environment: " + environment.file + ": " + std::to_string(panorama->zeroedTexels) +
                        " texels negative or not a number set to 0");
      const int size = environment.cubeSize > 0 ? environment.cubeSize : kPanoramaCubeSize;
      render::CubeMap cube = render::cubeFromEquirect(panorama->image, size, glm::radians(environment.rotationDegrees),
                                                      environment.intensity);
      if (!environment.sunLight) return SceneEnvironment{.data = {.radiance = std::move(cube)}};
      render::SunExtraction cut = render::extractSun(std::move(cube));
      if (cut.sun) {
        const glm::vec3 toward = cut.sun->direction;
        notes.push_back("environment: " + environment.file + ": its sun, " +
                        std::to_string(int(std::lround(glm::degrees(std::asin(toward.y))))) +
                        " degrees up, is the first light (irradiance " + std::to_string(cut.sun->intensity) +
                        " at its brightest channel)");
      } else {
        notes.push_back("environment: " + environment.file + ": no sun stands out of the sky to cut; no light added");
      }
      return SceneEnvironment{.data = {.radiance = std::move(cut.radiance)}, .sun = cut.sun};
    }
    notes.push_back("environment: " + environment.file + " missing (" + lookup->missingReason +
                    "): lit by the procedural sky instead");
  }
  return SceneEnvironment{.data = {.radiance = skyOf(scene, environment)}};
}

}  // namespace mane::scenes
