#pragma once
// Turning a scene's mesh entries into geometry, with the procedural fallback that lets a scene
// run without its third-party assets.

#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "scenes/assets.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"
#include "subdiv/cage.hpp"

namespace mane::scenes {

/// Radius, metres, of the sphere that stands in for a missing asset: about a head's size.
inline constexpr float kFallbackSphereRadius = 0.1f;

/// A mesh entry's geometry in its own (model) space; apply `MeshInstance::transform` or
/// `animatedMatrix` to place it.
struct LoadedMesh {
  Mesh mesh;
  bool procedural = false;  ///< built in, either by request or as a fallback
  /// For the user when the result is not what the scene asked for, e.g. "asset X missing:
  /// using a procedural sphere (...)"; empty otherwise. The caller prints it.
  std::string note;
  /// With the entry's `subdivision`: the cage its limit surface is built from (an OBJ's own
  /// polygons, creases and corners; otherwise the triangles welded by position), UVs in
  /// `Mesh`'s convention. `mesh` stays the file's triangles until the World tessellates it.
  std::optional<subdiv::Cage> cage;
  /// After tessellation, the skin shader's 1/r per vertex of `mesh` (SubdividedMesh).
  std::vector<float> limitInverseRadius;
};

/// Builds a "procedural:<kind>" entry, or resolves and loads the asset. An asset that is
/// missing everywhere (not shipped, offline) becomes a procedural sphere of
/// `kFallbackSphereRadius` with a note. Errors are kept for what must not pass silently: a
/// name the manifest does not list, a checksum mismatch, a file that does not parse.
/// `sceneDirectory` anchors sources that are file paths rather than manifest names (see
/// `AssetResolver::lookupForScene`). With a `subdivision`, also the cage (an OBJ that is no
/// valid cage is an error naming its line).
[[nodiscard]] Result<LoadedMesh> loadSceneMesh(const MeshInstance& instance, const AssetResolver& resolver,
                                               const std::filesystem::path& sceneDirectory = {});

}  // namespace mane::scenes
