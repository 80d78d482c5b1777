#pragma once
// Reading a glTF character's animations into clips for loadCharacter. Private to scenes/.

#include <vector>

#include "common/error.hpp"
#include "physics/animation_clip.hpp"
#include "physics/skeleton.hpp"
#include "scenes/detail/gltf_access.hpp"

namespace mane::scenes::detail {

/// Every animation of the file as a clip over `skeleton` (built from the same file): channels
/// for translation, rotation, scale and morph weights, in file order. Channels without a target
/// node or with a path glTF 2.0 does not define (extensions) are skipped.
[[nodiscard]] Result<std::vector<physics::AnimationClip>> readClips(const GltfContext& ctx,
                                                                    const physics::Skeleton& skeleton);

}  // namespace mane::scenes::detail
