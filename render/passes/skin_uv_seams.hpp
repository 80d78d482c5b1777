#pragma once
// UV seams, and the skirts that carry texture-space diffusion across them
// (render/passes/skin_diffusion_pass.hpp).
//
// A seam is an edge of the surface that the uv layout cuts: its two triangles meet in space but
// map it to two places in uv. Texture-space diffusion blurs the irradiance map, so without help
// a texel on one side of a seam never sees the light of the surface just across it, and the two
// sides of the seam end up lit differently. The cure here is geometric: the surface across
// each seam is drawn a second time into the map, unfolded past the island's border, so the
// empty texels around an island hold the irradiance of the skin that really lies there.
//
// The unfolding: for a seam edge, the similarity of the plane (a rotation and a scale, with or
// without a mirror) that takes the edge's uvs on the far side to its uvs on the near side; the
// far side's chart (its triangles connected without crossing a seam) is carried by it past the
// edge, as far as the reach over the surface. A chart's own uvs are continuous, so near the edge
// the skirt continues the near island's parametrisation up to the charts' difference in stretch.
// Triangles squashed in uv (below a hundredth of the mesh's median uv density: charts collapsed
// to a point or a line, as files do for surfaces no texture covers) are neither drawn nor
// crossed. Across a seam to such a chart there is no skin to show, and the gutter would take
// whatever a nearby seam's skirt brings: the near side's own skin, mirrored across the edge,
// stands in for it.
//
// Where skirts overlap each other or another island, a depth value decides: the mesh's own
// triangles are at depth 0 and always win, and a skirt's depth grows with its distance from its
// seam edge, so each empty texel takes the nearest seam's skirt.
//
// Vertices are welded by exact position (mesh_welding.hpp): files split vertices at seams but
// keep their positions bit for bit. Edges shared by more than two triangles and mesh borders have no
// other side and get no skirt.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace mane::render {

/// An edge where two triangles meet in space but not in uv.
struct UvSeamEdge {
  std::array<std::uint32_t, 2> triangles;  ///< the two triangles (index / 3)
  /// The edge's two end points as each triangle indexes them: ends[side][k] is end k's vertex in
  /// triangles[side]; ends[0][k] and ends[1][k] have the same position and different uvs.
  std::array<std::array<std::uint32_t, 2>, 2> ends;
};

/// The mesh's seam edges, ordered by their two triangles.
[[nodiscard]] std::vector<UvSeamEdge> findUvSeams(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                                                  std::span<const std::uint32_t> indices);

/// One vertex of the texture-space draw: a mesh vertex (its position, normal and source uv, read
/// from the mesh) placed at `uv` in the map, at `depth`.
struct SkinDrawVertex {
  std::uint32_t source = 0;  ///< the mesh vertex
  float depth = 0.0f;        ///< 0 for the mesh's own triangles; in (0, 1] for skirts
  glm::vec2 uv{0.0f};        ///< where it lands in the map
};
static_assert(sizeof(SkinDrawVertex) == 16);

/// A triangle list: the mesh's own triangles at their uvs and depth 0, then the skirts of both
/// sides of every seam edge, nearest first (so a depth test discards most of the overlap early).
/// `reach`: how far past a seam a skirt goes over the surface, as a length in uv units where the
/// mesh has its median uv density (1 = the map's side); an island packed more densely in uv gets
/// a skirt as much wider in uv, so that its blurs, whose width is set in millimetres, reach as far.
[[nodiscard]] std::vector<SkinDrawVertex> textureSpaceDrawList(std::span<const glm::vec3> positions,
                                                               std::span<const glm::vec2> uvs,
                                                               std::span<const std::uint32_t> indices, float reach);

}  // namespace mane::render
