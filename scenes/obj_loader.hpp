#pragma once
// Wavefront OBJ → Mesh, and the extension-based dispatcher over all mesh loaders.

#include <filesystem>

#include "common/error.hpp"
#include "scenes/mesh.hpp"

namespace mane::scenes {

/// Loads every face of an OBJ file (all groups and objects merged) as triangles: polygons
/// are split as fans around their first corner, which is exact for the convex quads of
/// subdivision cages. A file whose faces reference positions only keeps its numbering:
/// vertex i is the i-th `v` line, unreferenced ones included. Otherwise there is one output
/// vertex per distinct (position, uv, normal) index triple, in first-use order, so vertices
/// split at UV or normal seams and unreferenced positions are dropped. Missing normals are
/// computed (smooth, area-weighted). Materials (.mtl) and OpenSubdiv `t` crease tags are ignored.
/// Errors name the file and the problem (unreadable file, a face index outside the file's
/// vertex, uv or normal lists, a file without faces).
[[nodiscard]] Result<Mesh> loadObj(const std::filesystem::path& file);

/// Loads a mesh by extension (case-insensitive): `.gltf`/`.glb` → `loadGltf`, `.obj` →
/// `loadObj`; any other extension is an error naming the file.
[[nodiscard]] Result<Mesh> loadMesh(const std::filesystem::path& file);

}  // namespace mane::scenes
