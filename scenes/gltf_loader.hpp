#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, and binary .glb) → one merged Mesh.

#include <filesystem>

#include "common/error.hpp"
#include "scenes/mesh.hpp"

namespace mane::scenes {

/// Loads every triangle primitive reachable from the file's default scene (scene 0 when
/// none is named; every root node when the file has no scenes) into one mesh, with each
/// node's world transform applied to positions and normals, in the file's units (glTF says
/// metres). Handles interleaved and tightly packed buffer views, accessors without a buffer
/// view (all zeros), sparse accessors, u8/u16/u32 indices and non-indexed primitives.
/// Primitives without normals get smooth normals; texture coordinates (TEXCOORD_0) are kept
/// when any primitive has them (zeros elsewhere). Morph targets and skins are ignored: the
/// result is the bind pose (`loadCharacter`, scenes/gltf_character.hpp, reads them). Images are
/// not decoded.
///
/// Errors name the file and the problem: unreadable or truncated file, bad JSON, a missing
/// or out-of-range accessor or buffer view, an index past the vertex count, a primitive mode
/// other than TRIANGLES, a scene with no triangles.
[[nodiscard]] Result<Mesh> loadGltf(const std::filesystem::path& file);

}  // namespace mane::scenes
