#include "render/passes/skin_uv_seams.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <optional>
#include <tuple>

#include "render/passes/mesh_welding.hpp"

namespace mane::render {
namespace {

constexpr std::uint32_t kNone = ~0u;

// Triangle t's edge k runs from corner k to corner k + 1.
struct EdgeUse {
  std::uint32_t low, high;  // welded vertices (weldByPosition), low < high
  std::uint32_t triangle, edge;
};

// The mesh's topology over welded vertices: which triangle meets which across each edge, and
// whether that edge is a seam.
struct Topology {
  std::vector<UvSeamEdge> seams;
  // Per triangle and edge: the triangle across it within the same uv chart, or kNone (a seam, a
  // border or a non-manifold edge).
  std::vector<std::array<std::uint32_t, 3>> chartNeighbours;
};

Topology buildTopology(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                       std::span<const std::uint32_t> indices) {
  const std::vector<std::uint32_t> weld = weldByPosition(positions);
  const std::size_t triangles = indices.size() / 3;
  const auto corner = [&](std::uint32_t t, std::uint32_t k) { return indices[3 * t + k % 3]; };
  std::vector<EdgeUse> uses;
  uses.reserve(indices.size());
  for (std::uint32_t t = 0; t < triangles; ++t)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t a = weld[corner(t, k)], b = weld[corner(t, k + 1)];
      if (a != b) uses.push_back({std::min(a, b), std::max(a, b), t, k});
    }
  std::ranges::sort(uses, [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.low, x.high, x.triangle, x.edge) < std::tie(y.low, y.high, y.triangle, y.edge);
  });

  Topology topology;
  topology.chartNeighbours.assign(triangles, {kNone, kNone, kNone});
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].low == uses[i].low && uses[j].high == uses[i].high) ++j;
    if (j - i == 2) {
      const EdgeUse& x = uses[i];
      const EdgeUse& y = uses[i + 1];
      // Each side's vertices at the edge's two welded ends, in the same order.
      const auto ends = [&](const EdgeUse& use) {
        std::array<std::uint32_t, 2> v{corner(use.triangle, use.edge), corner(use.triangle, use.edge + 1)};
        if (weld[v[0]] != use.low) std::swap(v[0], v[1]);
        return v;
      };
      const std::array<std::uint32_t, 2> ex = ends(x), ey = ends(y);
      if (uvs[ex[0]] == uvs[ey[0]] && uvs[ex[1]] == uvs[ey[1]]) {
        topology.chartNeighbours[x.triangle][x.edge] = y.triangle;
        topology.chartNeighbours[y.triangle][y.edge] = x.triangle;
      } else {
        topology.seams.push_back({.triangles = {x.triangle, y.triangle}, .ends = {ex, ey}});
      }
    }
    i = j;
  }
  std::ranges::sort(topology.seams, [](const UvSeamEdge& a, const UvSeamEdge& b) {
    return std::tie(a.triangles[0], a.triangles[1]) < std::tie(b.triangles[0], b.triangles[1]);
  });
  return topology;
}

// A similarity of the plane, x → origin + z·(x − from) or, mirrored, origin + z·conj(x − from),
// in complex notation.
struct Unfolding {
  glm::dvec2 from, origin, z;
  bool mirrored = false;

  glm::dvec2 operator()(glm::dvec2 x) const {
    glm::dvec2 d = x - from;
    if (mirrored) d.y = -d.y;
    return origin + glm::dvec2(z.x * d.x - z.y * d.y, z.x * d.y + z.y * d.x);
  }
};

glm::dvec2 complexDivide(glm::dvec2 a, glm::dvec2 b) {
  const double norm = glm::dot(b, b);
  return glm::dvec2(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / norm;
}

double cross(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}

double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 d = b - a;
  const double t = std::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0, 1.0);
  return glm::length(p - (a + t * d));
}

// Per triangle, uv units per unit of surface (the square root of the ratio of its areas); 0 for
// a triangle without area in space.
std::vector<double> uvDensities(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                                std::span<const std::uint32_t> indices) {
  std::vector<double> densities(indices.size() / 3, 0.0);
  for (std::size_t t = 0; t < densities.size(); ++t) {
    const std::uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
    const double world = glm::length(glm::cross(glm::dvec3(positions[b]) - glm::dvec3(positions[a]),
                                                glm::dvec3(positions[c]) - glm::dvec3(positions[a])));
    const double uv = std::abs(cross(glm::dvec2(uvs[b]) - glm::dvec2(uvs[a]), glm::dvec2(uvs[c]) - glm::dvec2(uvs[a])));
    if (world > 0.0) densities[t] = std::sqrt(uv / world);
  }
  return densities;
}

// The unfolding that takes the far triangle's edge onto the near one's, with the far triangle
// landing on the other side of the edge; none when either side is degenerate in uv.
std::optional<Unfolding> unfoldAcross(const UvSeamEdge& seam, int nearSide, std::span<const glm::vec2> uvs,
                                      std::span<const std::uint32_t> indices) {
  const int farSide = 1 - nearSide;
  const glm::dvec2 a0(uvs[seam.ends[nearSide][0]]), a1(uvs[seam.ends[nearSide][1]]);
  const glm::dvec2 b0(uvs[seam.ends[farSide][0]]), b1(uvs[seam.ends[farSide][1]]);
  const glm::dvec2 dA = a1 - a0, dB = b1 - b0;
  if (!(glm::dot(dA, dA) > 0.0) || !(glm::dot(dB, dB) > 0.0)) return std::nullopt;
  const auto third = [&](int side) {
    const std::uint32_t t = seam.triangles[side];
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t v = indices[3 * t + k];
      if (v != seam.ends[side][0] && v != seam.ends[side][1]) return glm::dvec2(uvs[v]);
    }
    return glm::dvec2(uvs[indices[3 * t]]);
  };
  const double nearSideOfEdge = cross(dA, third(nearSide) - a0);
  for (const bool mirrored : {false, true}) {
    const glm::dvec2 conjugated = mirrored ? glm::dvec2(dB.x, -dB.y) : dB;
    const Unfolding unfolding{.from = b0, .origin = a0, .z = complexDivide(dA, conjugated), .mirrored = mirrored};
    if (cross(dA, unfolding(third(farSide)) - a0) * nearSideOfEdge < 0.0) return unfolding;
  }
  return std::nullopt;
}

// The reflection across the line through a0 and a1: x → a0 + u²·conj(x − a0), u the line's unit
// direction (complex); none for a degenerate edge.
std::optional<Unfolding> mirrorAcross(glm::dvec2 a0, glm::dvec2 a1) {
  const double length = glm::length(a1 - a0);
  if (!(length > 0.0)) return std::nullopt;
  const glm::dvec2 u = (a1 - a0) / length;
  return Unfolding{.from = a0, .origin = a0, .z = glm::dvec2(u.x * u.x - u.y * u.y, 2.0 * u.x * u.y), .mirrored = true};
}

// Whether a triangle at these uvs may cover a texel of the map: not wholly past one of its edges.
bool insideMap(const std::array<SkinDrawVertex, 3>& corners) {
  for (int axis = 0; axis < 2; ++axis) {
    bool below = true, above = true;
    for (const SkinDrawVertex& corner : corners) {
      below = below && corner.uv[axis] < 0.0f;
      above = above && corner.uv[axis] > 1.0f;
    }
    if (below || above) return false;
  }
  return true;
}

}  // namespace

std::vector<UvSeamEdge> findUvSeams(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                                    std::span<const std::uint32_t> indices) {
  return buildTopology(positions, uvs, indices).seams;
}

std::vector<SkinDrawVertex> textureSpaceDrawList(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                                                 std::span<const std::uint32_t> indices, float reach) {
  std::vector<SkinDrawVertex> draw;
  draw.reserve(indices.size());
  for (const std::uint32_t v : indices) draw.push_back({.source = v, .depth = 0.0f, .uv = uvs[v]});
  if (!(reach > 0.0f)) return draw;

  const Topology topology = buildTopology(positions, uvs, indices);
  // Triangles squashed in uv (a chart collapsed to a line or a point, as files do for surfaces
  // no texture covers) hold no texels and have no shape to unfold: skirts neither draw nor
  // cross them, nor start from them. Squashed: below a hundredth of the mesh's median density.
  const std::vector<double> density = uvDensities(positions, uvs, indices);
  std::vector<double> sorted = density;
  std::ranges::nth_element(sorted, sorted.begin() + std::ptrdiff_t(sorted.size() / 2));
  const double medianDensity = sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
  const double squashed = 0.01 * medianDensity;
  // A skirt vertex's depth: a little above the mesh's own at the seam, 1 at the reach.
  constexpr double kNearest = 1.0 / 256.0;
  struct SkirtTriangle {
    float nearest;
    std::array<SkinDrawVertex, 3> corners;
  };
  std::vector<SkirtTriangle> skirts;
  std::vector<std::uint32_t> visitedBy(topology.chartNeighbours.size(), kNone);
  std::vector<std::uint32_t> queue;
  std::uint32_t walk = 0;
  for (const UvSeamEdge& seam : topology.seams)
    for (int nearSide = 0; nearSide < 2; ++nearSide, ++walk) {
      const double nearDensity = density[seam.triangles[nearSide]], farDensity = density[seam.triangles[1 - nearSide]];
      if (nearDensity <= squashed) continue;
      const glm::dvec2 a0(uvs[seam.ends[nearSide][0]]), a1(uvs[seam.ends[nearSide][1]]);
      std::optional<Unfolding> unfold =
          farDensity > squashed ? unfoldAcross(seam, nearSide, uvs, indices) : std::nullopt;
      std::uint32_t start = seam.triangles[1 - nearSide];
      double startDensity = farDensity;
      if (!unfold) {
        // No skin across to show (squashed in uv): the near side's own, mirrored across the edge,
        // so that the gutter holds its continuation rather than what some other seam's skirt
        // would bring.
        unfold = mirrorAcross(a0, a1);
        start = seam.triangles[nearSide];
        startDensity = nearDensity;
      }
      // The reach as a distance over the surface, in the near side's uv: the chart, as
      // unfolded, has |z|·startDensity uv units per unit of surface.
      const double nearReach = reach * glm::length(unfold->z) * startDensity / medianDensity;
      // The chart, breadth first from the seam's triangle, while it stays within reach of the edge.
      queue.assign(1, start);
      visitedBy[queue[0]] = walk;
      for (std::size_t q = 0; q < queue.size(); ++q) {
        const std::uint32_t t = queue[q];
        if (density[t] <= squashed) continue;
        SkirtTriangle skirt{.nearest = 1.0f, .corners = {}};
        for (std::uint32_t k = 0; k < 3; ++k) {
          const std::uint32_t v = indices[3 * t + k];
          const glm::dvec2 at = (*unfold)(glm::dvec2(uvs[v]));
          const double depth = kNearest + (1.0 - kNearest) * std::min(distanceToSegment(at, a0, a1) / nearReach, 1.0);
          skirt.corners[k] = {.source = v, .depth = float(depth), .uv = glm::vec2(at)};
          skirt.nearest = std::min(skirt.nearest, float(depth));
        }
        if (q > 0 && skirt.nearest >= 1.0f) continue;  // wholly out of reach: neither drawn nor followed
        if (insideMap(skirt.corners)) skirts.push_back(skirt);  // past the map's edge: followed only
        for (const std::uint32_t next : topology.chartNeighbours[t])
          if (next != kNone && visitedBy[next] != walk) {
            visitedBy[next] = walk;
            queue.push_back(next);
          }
      }
    }
  std::ranges::stable_sort(skirts, {}, &SkirtTriangle::nearest);
  draw.reserve(draw.size() + 3 * skirts.size());
  for (const SkirtTriangle& skirt : skirts) draw.insert(draw.end(), skirt.corners.begin(), skirt.corners.end());
  return draw;
}

}  // namespace mane::render
