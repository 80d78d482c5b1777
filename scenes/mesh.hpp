#pragma once
// A triangle mesh as the loaders hand it over: plain arrays, no GPU or physics types.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace mane::scenes {

/// Axis-aligned box, in the mesh's units (metres for scene content). An empty mesh gives
/// `min > max` (see `isEmpty`).
struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};

  /// True when no point was added.
  [[nodiscard]] bool isEmpty() const { return min.x > max.x; }
  [[nodiscard]] glm::vec3 centre() const { return (min + max) * 0.5f; }
  [[nodiscard]] glm::vec3 size() const { return max - min; }
};

/// An indexed triangle list. Invariants (checked by `validate`): `indices.size()` is a
/// multiple of 3 and every index is < `positions.size()`; `normals` and `uvs` are either
/// empty or hold one entry per position. Positions in metres for scene content (files keep
/// their own units; the scene transform scales them).
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  ///< unit length
  std::vector<glm::vec2> uvs;      ///< texture coordinates, glTF convention (v down)
  std::vector<std::uint32_t> indices;

  [[nodiscard]] std::size_t vertexCount() const { return positions.size(); }
  [[nodiscard]] std::size_t triangleCount() const { return indices.size() / 3; }

  /// Bounds of all positions (including ones no triangle uses).
  [[nodiscard]] Bounds bounds() const;
};

/// Area-weighted smooth normals: each vertex gets the normalised sum of the (unnormalised)
/// cross products of the triangles that use it, so large triangles count more. Vertices that
/// no triangle uses, or whose triangles are all degenerate, get +Y. Replaces `mesh.normals`.
void computeSmoothNormals(Mesh& mesh);

/// Texture coordinates for a mesh that has none: each vertex is projected on the coordinate
/// plane across its normal's largest axis, uv = the other two coordinates × `uvPerUnit`. Seams
/// where neighbouring vertices choose different planes stretch the texture over one triangle;
/// fine for noise-like textures (fur photos), not for images. Needs `mesh.normals`; replaces
/// `mesh.uvs`.
void boxProjectUvs(Mesh& mesh, float uvPerUnit);

/// Empty string when the invariants above hold, else a description of the first violation.
[[nodiscard]] std::string validate(const Mesh& mesh);

}  // namespace mane::scenes
