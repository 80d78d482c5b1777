// mane_scene_hashes: loads scene files and prints, for each, hashes of what the CPU computes from
// them, so that two builds (two compilers, two standard libraries, two machines) can be compared
// with a plain diff (tests/determinism/across_compilers.sh).
//
//   mane_scene_hashes [--steps N] [--threads T] SCENE...
//
// Per scene, one "SCENE WHAT HASH" line each for:
//   geometry   the static scene handed to the renderer at load: every mesh's positions, normals,
//              uvs, indices and curvatures (tessellated subdivision surfaces, procedural and
//              loaded meshes) and every groom's dense-strand layout and strand looks;
//   state@K    World::stateHash (grooms, cloths, moving furs, clock) after K fixed steps, for
//              K = 0 (as loaded), 1 and N: a difference at 0 points at loading, one that appears
//              later at the simulation;
//   placements@N  the camera and every mesh instance's model matrix after N steps (animation).
// Textures are not decoded: `mane sim` does not need them either.

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/hash.hpp"
#include "scenes/world.hpp"

namespace {

using mane::physics::StateHasher;

std::uint64_t geometryHash(const mane::render::StaticScene& statics) {
  StateHasher hasher;
  for (const mane::render::MeshData& mesh : statics.meshes) {
    hasher.add(mesh.positions);
    hasher.add(mesh.normals);
    hasher.add(mesh.uvs);
    hasher.add(mesh.indices);
    hasher.add(mesh.curvatures);
  }
  for (const mane::render::HairGroomData& groom : statics.grooms) {
    hasher.add(std::span<const mane::GuideFrameRef>(groom.layout.guideFrames));
    hasher.add(std::span<const mane::DenseStrand>(groom.layout.strands));
    hasher.add(std::span<const mane::render::HairStrandLook>(groom.strandLooks));
  }
  return hasher.value();
}

std::uint64_t placementsHash(const mane::render::FrameInput& frame) {
  StateHasher hasher;
  hasher.addValue(frame.camera.position);
  hasher.addValue(frame.camera.target);
  hasher.addValue(frame.camera.up);
  for (const mane::render::MeshInstance& instance : frame.instances) hasher.addValue(instance.model);
  return hasher.value();
}

bool parseCount(std::string_view text, unsigned& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

void print(const std::string& scene, const std::string& what, std::uint64_t hash) {
  std::printf("%s %s %s\n", scene.c_str(), what.c_str(), mane::physics::hashText(hash).c_str());
}

/// Prints the scene's lines; false (with a message on stderr) when it cannot be loaded or run.
bool hashScene(const std::filesystem::path& file, unsigned steps, unsigned threads) {
  const std::string name = file.stem().string();
  auto scene = mane::scenes::loadScene(file);
  auto resolver = mane::scenes::AssetResolver::createDefault();
  if (!scene || !resolver) {
    std::fprintf(stderr, "%s: %s\n", file.c_str(), (!scene ? scene.error() : resolver.error()).message.c_str());
    return false;
  }
  auto world = mane::scenes::World::create(std::move(*scene), *resolver, {.loadTextures = false});
  if (!world) {
    std::fprintf(stderr, "%s: %s\n", file.c_str(), world.error().message.c_str());
    return false;
  }
  print(name, "geometry", geometryHash(world->staticScene()));
  const double step = world->scene().simulation.stepSeconds;
  for (unsigned k = 0; k <= steps; ++k) {
    if (k > 0)
      if (auto advanced = world->advance(step, threads); !advanced) {
        std::fprintf(stderr, "%s: step %u: %s\n", file.c_str(), k, advanced.error().message.c_str());
        return false;
      }
    if (k == 0 || k == 1 || k == steps) print(name, "state@" + std::to_string(k), world->stateHash());
  }
  print(name, "placements@" + std::to_string(steps), placementsHash(world->frameInput()));
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  unsigned steps = 120, threads = 1;
  std::vector<std::filesystem::path> scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument = argv[i];
    if ((argument == "--steps" || argument == "--threads") && i + 1 < argc) {
      if (!parseCount(argv[++i], argument == "--steps" ? steps : threads) || threads == 0) {
        std::fprintf(stderr, "mane_scene_hashes: %s %s: expected a whole number (threads ≥ 1)\n", argv[i - 1],
                     argv[i]);
        return 2;
      }
    } else if (argument.starts_with("-")) {
      std::fprintf(stderr, "usage: mane_scene_hashes [--steps N] [--threads T] SCENE...\n");
      return 2;
    } else {
      scenes.emplace_back(argument);
    }
  }
  if (scenes.empty()) {
    std::fprintf(stderr, "usage: mane_scene_hashes [--steps N] [--threads T] SCENE...\n");
    return 2;
  }
  bool ok = true;
  for (const auto& scene : scenes) ok = hashScene(scene, steps, threads) && ok;
  return ok ? 0 : 1;
}
