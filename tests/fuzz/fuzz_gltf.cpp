// libFuzzer harness: bytes → a scratch file → loadGltf and loadCharacter (binary .glb when the
// bytes start with "glTF", JSON otherwise; the loaders pick by content, not by name). Each must
// return its result or an error, never crash, hang or leak. A mesh loadGltf returns must pass
// validate(); a character loadCharacter returns must pose (rest pose and every clip at its start,
// middle and end) and deform every mesh both ways without crashing, and its rest pose and clips
// must apply without error (the loader promised a consistent whole).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "scenes/gltf_character.hpp"
#include "scenes/gltf_loader.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

namespace {

void exercise(const mane::scenes::Character& character) {
  mane::physics::Pose pose = character.skeleton.restPose();
  for (const auto& clip : character.clips) {
    for (float fraction : {0.0f, 0.5f, 1.0f}) {
      if (!clip.apply(fraction * clip.duration(), pose)) std::abort();
    }
  }
  auto world = character.skeleton.worldMatrices(pose);
  if (!world) std::abort();
  mane::physics::DeformedSurface out;
  for (std::size_t m = 0; m < character.meshes.size(); ++m) {
    auto joints = character.jointMatrices(m, *world);
    if (!joints) std::abort();
    mane::physics::SkinnedMesh surface = character.meshes[m].surface;
    const auto& weights = pose.morphWeights[static_cast<std::size_t>(character.meshes[m].node)];
    // Hostile transforms may overflow to infinity or mirror (DQS refuses those): errors are fine.
    for (auto method : {mane::physics::SkinningMethod::LinearBlend, mane::physics::SkinningMethod::DualQuaternion}) {
      surface.setMethod(method);
      (void)surface.deform(*joints, weights, out);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Both names: .glb for binary containers, .gltf for JSON (buffers resolve beside it).
  static const mane::fuzz::InputFile glb("input.glb");
  static const mane::fuzz::InputFile gltf("input.gltf");
  const bool binary = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  const auto& path = (binary ? glb : gltf).write(data, size);
  auto mesh = mane::scenes::loadGltf(path);
  if (mesh && !mane::scenes::validate(*mesh).empty()) std::abort();
  auto character = mane::scenes::loadCharacter(path);
  if (character) exercise(*character);
  return 0;
}
