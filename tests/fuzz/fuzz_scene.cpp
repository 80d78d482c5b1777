// libFuzzer harness: scene JSON text → parseScene. Must return a value or an error, never
// crash, hang or leak; a scene it accepts must hold only finite numbers, its glasses must be
// built or refused by name (scenes/glasses.hpp), its fins must make valid cloth, and its sea must
// grow from its settings, with a finite surface.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include <glm/geometric.hpp>

#include "physics/cloth.hpp"
#include "physics/floating_debris.hpp"
#include "physics/ocean_waves.hpp"
#include "render/lens.hpp"
#include "scenes/fin_cloth.hpp"
#include "scenes/glasses.hpp"
#include "scenes/scene.hpp"

namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite(const mane::scenes::Transform& t) {
  return finite(t.translation) && finite(t.rotationDegrees) && std::isfinite(t.scale);
}

// Shapes carried by joints are placed from these numbers every frame.
bool finite(const mane::scenes::Colliders& colliders) {
  for (const auto& sphere : colliders.jointSpheres)
    if (sphere.joint.empty() || !finite(sphere.sphere.centre) || !std::isfinite(sphere.sphere.radius)) return false;
  for (const auto& capsule : colliders.jointCapsules)
    if (capsule.joint.empty() || !finite(capsule.capsule.a) || !finite(capsule.capsule.b) ||
        !std::isfinite(capsule.capsule.radius))
      return false;
  return true;
}

// A character's clip timeline and morph tracks, and the weights the tracks give between keys.
bool finite(const mane::scenes::CharacterInstance& character) {
  if (!finite(character.transform)) return false;
  for (const auto& clip : character.clips)
    if (!std::isfinite(clip.startSeconds) || !(clip.speed > 0.0f) || !std::isfinite(clip.crossFadeSeconds)) return false;
  for (const auto& track : character.morphs) {
    if (track.keys.empty()) return false;
    for (std::size_t k = 0; k < track.keys.size(); ++k) {
      const float t = track.keys[k].timeSeconds;
      const float between = k + 1 < track.keys.size() ? t + 0.5f * (track.keys[k + 1].timeSeconds - t) : t + 1.0f;
      if (!std::isfinite(track.weightAt(t)) || !std::isfinite(track.weightAt(between))) return false;
    }
    if (!std::isfinite(track.weightAt(0.5f))) return false;
  }
  return true;
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
  for (const auto& character : scene->characters)
    if (!finite(character)) std::abort();
  for (const auto& groom : scene->grooms)
    if (!finite(groom.colliders)) std::abort();
  for (const auto& cloth : scene->cloths) {
    if (!finite(cloth.colliders)) std::abort();
    for (const auto& [lower, upper] : cloth.pinRegions)
      if (!finite(lower) || !finite(upper)) std::abort();
    if (cloth.source == "procedural:fin") {
      mane::scenes::FinShape shape = cloth.fin;
      shape.rays = std::min(shape.rays, 8);  // the counts cost time; the sizes are what can break it
      shape.rows = std::min(shape.rows, 16);
      const mane::scenes::FinCloth fin = mane::scenes::makeFin(shape);
      mane::physics::ClothSettings settings;
      settings.shapeHolds = fin.holds;
      if (!mane::physics::Cloth::create(fin.mesh.positions, fin.mesh.indices, fin.base, settings)) std::abort();
    }
  }
  if (scene->ship && !scene->ocean) std::abort();
  if (scene->ocean) {
    auto waves = mane::physics::OceanWaves::create(scene->ocean->waves);
    if (!waves) std::abort();  // the parser has checked the settings
    const auto water = waves->surfaceAt({3.0f, -7.0f}, 12.5);
    if (!finite(water.position) || !finite(water.normal) || !std::isfinite(water.jacobian)) std::abort();
    if (scene->ocean->debris) {
      mane::physics::FloatingDebrisSettings settings = *scene->ocean->debris;
      settings.pieces = std::min(settings.pieces, 8);  // each piece costs a surface query
      auto debris = mane::physics::FloatingDebris::create(settings, *waves, 12.5);
      if (!debris) std::abort();  // the parser has checked the settings
      debris->step(*waves, 12.5 + 1.0 / 60.0, 1.0f / 60.0f);
      for (const glm::vec3& corner : debris->corners())
        if (!finite(corner)) std::abort();
    }
  }
  if (scene->ship) {
    for (const auto& line : scene->ship->rigging)
      if (!finite(line.from) || !finite(line.to) || !(line.width > 0.0f)) std::abort();
    if (scene->ship->cannon && !(std::abs(glm::length(scene->ship->cannon->direction) - 1.0f) < 1e-3f)) std::abort();
  }
  for (const auto& glasses : scene->glasses) {
    if (!finite(glasses.transform) || !finite(glasses.tint)) std::abort();
    auto built = mane::scenes::buildGlasses(glasses);
    if (!built) {
      if (built.error().message.find(glasses.name) == std::string::npos) std::abort();
      continue;
    }
    for (const auto& lens : built->lenses)
      if (!mane::render::validateLens(lens)) std::abort();
    for (const glm::vec3& p : built->frame.positions)
      if (!finite(p)) std::abort();
  }
  return 0;
}
