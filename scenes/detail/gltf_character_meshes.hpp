#pragma once
// Reading a glTF character's skins and mesh instances (joint influences, morph targets) for
// loadCharacter. Private to scenes/.

#include <vector>

#include "common/error.hpp"
#include "scenes/detail/gltf_access.hpp"
#include "scenes/gltf_character.hpp"

namespace mane::scenes::detail {

/// Every skin of the file: joints checked to be nodes, inverse bind matrices read (identity per
/// joint when the skin has none, glTF 2.0 §5.28).
[[nodiscard]] Result<std::vector<CharacterSkin>> readSkins(const GltfContext& ctx);

/// The morph weights node `nodeIndex` rests with (node.weights, else mesh.weights, else zeros;
/// glTF 2.0 §3.7.2.1); empty when it holds no mesh with morph targets.
[[nodiscard]] Result<std::vector<float>> restMorphWeights(const GltfContext& ctx, int nodeIndex);

/// The mesh that node `nodeIndex` holds, its primitives merged, bound to `skins[node.skin]` or,
/// without a skin, rigidly to the node.
[[nodiscard]] Result<CharacterMesh> readCharacterMesh(const GltfContext& ctx, int nodeIndex,
                                                      const std::vector<CharacterSkin>& skins);

}  // namespace mane::scenes::detail
