// libFuzzer harness: scene JSON text → parseScene. Must return a value or an error, never
// crash, hang or leak; a scene it accepts must hold only finite numbers.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "scenes/scene.hpp"

namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto scene = mane::scenes::parseScene(text, "fuzz.json");
  if (!scene) {
    if (scene.error().message.find("fuzz.json") == std::string::npos) std::abort();
    return 0;
  }
  const mane::scenes::Camera& camera = scene->camera;
  if (!finite(camera.position) || !finite(camera.target) || !finite(camera.up)) std::abort();
  for (const auto& light : scene->lights) {
    if (!finite(light.direction) || !finite(light.colour) || !std::isfinite(light.intensity)) {
      std::abort();
    }
  }
  for (const auto& mesh : scene->meshes) {
    const auto& t = mesh.transform;
    if (!finite(t.translation) || !finite(t.rotationDegrees) || !std::isfinite(t.scale)) {
      std::abort();
    }
    (void)mane::scenes::animatedMatrix(*scene, mesh, 0.5f);
  }
  return 0;
}
