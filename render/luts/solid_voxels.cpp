#include "render/luts/solid_voxels.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>

#include <glm/common.hpp>

namespace mane::render {

namespace {

// Fixed-point lattice for the projected vertices: 2⁻²⁰ of a cell. With N ≤ 128 a coordinate is
// below 2²⁷, a product of two differences below 2⁵⁴: the orientation tests cannot overflow.
constexpr std::int64_t kOne = std::int64_t{1} << 20;
constexpr std::int64_t kHalf = kOne / 2;

struct Point2 {
  std::int64_t u = 0, v = 0;  // grid y and z, lattice units
};

// Twice the signed area of (a, b, c): > 0 when counter-clockwise in the (u, v) plane. Exact.
std::int64_t orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

// Whether a query with edge function `w` lies on the inner side of the counter-clockwise edge
// a→b. On the edge (w = 0) the top-left rule decides: the answer for the query shifted by
// (ε, −ε²), so an edge shared by two triangles is claimed by exactly one of them and a shared
// vertex by exactly one triangle of a fan that does not fold over it.
bool coversEdge(std::int64_t w, const Point2& a, const Point2& b) {
  if (w != 0) return w > 0;
  const std::int64_t du = b.u - a.u, dv = b.v - a.v;
  return dv < 0 || (dv == 0 && du < 0);
}

struct Crossing {
  std::uint32_t column = 0;  // j + N·k
  double x = 0.0;            // grid units along the ray
  std::int32_t sign = 0;     // +1 entering the material, −1 leaving
  auto key() const { return std::tie(column, x, sign); }
};

std::string describe(const glm::vec3& p) {
  // A stream, not string concatenation: GCC 12 warns falsely (-Wstringop-overflow) on the latter here.
  std::ostringstream text;
  text << '(' << p.x << ", " << p.y << ", " << p.z << ')';
  return text.str();
}

// A position's bits, with −0 folded into +0 so equal positions compare equal.
std::array<std::uint32_t, 3> positionKey(const glm::vec3& p) {
  return {std::bit_cast<std::uint32_t>(p.x + 0.0f), std::bit_cast<std::uint32_t>(p.y + 0.0f),
          std::bit_cast<std::uint32_t>(p.z + 0.0f)};
}

// Every directed edge a→b must be matched by as many b→a (closed and consistently wound).
Result<void> checkClosed(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices) {
  using EdgeKey = std::array<std::uint32_t, 6>;
  struct Edge {
    EdgeKey key;
    std::size_t corner;  // 3·triangle + edge number: the edge runs from this corner to the next
  };
  const auto next = [](std::size_t corner) { return corner - corner % 3 + (corner + 1) % 3; };
  std::vector<Edge> forward;
  std::vector<EdgeKey> reverse;
  forward.reserve(indices.size());
  reverse.reserve(indices.size());
  for (std::size_t corner = 0; corner < indices.size(); ++corner) {
    const auto a = positionKey(positions[indices[corner]]);
    const auto b = positionKey(positions[indices[next(corner)]]);
    forward.push_back({{a[0], a[1], a[2], b[0], b[1], b[2]}, corner});
    reverse.push_back({b[0], b[1], b[2], a[0], a[1], a[2]});
  }
  std::sort(forward.begin(), forward.end(),
            [](const Edge& l, const Edge& r) { return std::tie(l.key, l.corner) < std::tie(r.key, r.corner); });
  std::sort(reverse.begin(), reverse.end());
  // Equal totals: if the multisets differ, some forward key outnumbers its reverse.
  std::size_t r = 0;
  for (std::size_t f = 0; f < forward.size();) {
    std::size_t fEnd = f;
    while (fEnd < forward.size() && forward[fEnd].key == forward[f].key) ++fEnd;
    while (r < reverse.size() && reverse[r] < forward[f].key) ++r;
    std::size_t rEnd = r;
    while (rEnd < reverse.size() && reverse[rEnd] == forward[f].key) ++rEnd;
    if (rEnd - r < fEnd - f) {
      const std::size_t corner = forward[f].corner;
      return fail("voxelizeSolid: the mesh is not closed: edge " + describe(positions[indices[corner]]) + " -> " +
                  describe(positions[indices[next(corner)]]) + " of triangle " + std::to_string(corner / 3) +
                  " is used " + std::to_string(fEnd - f) + " time(s) but its opposite only " +
                  std::to_string(rEnd - r) +
                  " (every edge must be shared by two triangles wound opposite ways, counter-clockwise seen from "
                  "outside).");
    }
    f = fEnd;
    r = rEnd;
  }
  return {};
}

Result<void> checkInput(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices, int resolution) {
  if (resolution < SolidVoxels::kMinResolution || resolution > SolidVoxels::kMaxResolution) {
    return fail("voxelizeSolid: resolution " + std::to_string(resolution) + " is outside [" +
                std::to_string(SolidVoxels::kMinResolution) + ", " + std::to_string(SolidVoxels::kMaxResolution) +
                "] cells per axis.");
  }
  if (indices.empty()) return fail("voxelizeSolid: the mesh has no triangles.");
  if (indices.size() % 3 != 0) {
    return fail("voxelizeSolid: " + std::to_string(indices.size()) +
                " indices is not a multiple of 3 (three per triangle).");
  }
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= positions.size()) {
      return fail("voxelizeSolid: index " + std::to_string(i) + " (triangle " + std::to_string(i / 3) + ") is " +
                  std::to_string(indices[i]) + ", but there are " + std::to_string(positions.size()) + " positions.");
    }
  }
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const glm::vec3& p = positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return fail("voxelizeSolid: position " + std::to_string(v) + " is not finite: " + describe(p) + ".");
    }
  }
  return checkClosed(positions, indices);
}

}  // namespace

glm::ivec3 SolidVoxels::coordinates(std::size_t cell) const noexcept {
  const auto n = static_cast<std::size_t>(resolution);
  return {static_cast<int>(cell % n), static_cast<int>(cell / n % n), static_cast<int>(cell / (n * n))};
}

glm::dvec3 SolidVoxels::centre(std::size_t cell) const noexcept {
  return origin + (glm::dvec3(coordinates(cell)) + 0.5) * voxelSize;
}

glm::ivec3 SolidVoxels::cellAt(const glm::dvec3& point) const noexcept {
  glm::ivec3 cell;
  for (int a = 0; a < 3; ++a) {
    const double g = std::floor((point[a] - origin[a]) / voxelSize[a]);
    cell[a] = static_cast<int>(std::clamp(g, 0.0, static_cast<double>(resolution - 1)));
  }
  return cell;
}

Result<SolidVoxels> voxelizeSolid(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                                  int resolution) {
  if (auto ok = checkInput(positions, indices, resolution); !ok) return std::unexpected(ok.error());

  // Only the vertices the triangles use define the box.
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const std::uint32_t i : indices) {
    lo = glm::min(lo, glm::dvec3(positions[i]));
    hi = glm::max(hi, glm::dvec3(positions[i]));
  }
  for (int a = 0; a < 3; ++a) {
    if (!(hi[a] > lo[a])) {
      return fail("voxelizeSolid: the mesh's bounding box is flat along axis " + std::to_string(a) +
                  " (a closed mesh must enclose a volume).");
    }
  }

  SolidVoxels voxels;
  voxels.resolution = resolution;
  voxels.origin = lo;
  voxels.voxelSize = (hi - lo) / static_cast<double>(resolution);
  const int n = resolution;
  const auto toGrid = [&](const glm::vec3& p) { return (glm::dvec3(p) - lo) / voxels.voxelSize; };
  const auto toLattice = [](double g) {
    return static_cast<std::int64_t>(std::llround(g * static_cast<double>(kOne)));
  };

  std::vector<Crossing> crossings;
  for (std::size_t t = 0; t < indices.size() / 3; ++t) {
    std::array<glm::dvec3, 3> g;
    std::array<Point2, 3> q;
    for (int c = 0; c < 3; ++c) {
      g[c] = toGrid(positions[indices[3 * t + c]]);
      q[c] = {toLattice(g[c].y), toLattice(g[c].z)};
    }
    const std::int64_t area = orient(q[0], q[1], q[2]);
    if (area == 0) continue;  // parallel to the rays: a ray in general position misses it
    // n.x = area: the outward normal faces −x where the ray enters the material.
    const std::int32_t sign = area < 0 ? +1 : -1;
    if (area < 0) {
      std::swap(q[1], q[2]);
      std::swap(g[1], g[2]);
    }
    const std::int64_t uMin = std::min({q[0].u, q[1].u, q[2].u}), uMax = std::max({q[0].u, q[1].u, q[2].u});
    const std::int64_t vMin = std::min({q[0].v, q[1].v, q[2].v}), vMax = std::max({q[0].v, q[1].v, q[2].v});
    // Columns whose centre (j·kOne + kHalf) may lie in [min, max]; the exact tests decide.
    const auto first = [&](std::int64_t lo2) {
      return static_cast<int>(std::max<std::int64_t>(0, (lo2 - kHalf) / kOne));
    };
    const auto last = [&](std::int64_t hi2) {
      return static_cast<int>(std::min<std::int64_t>(n - 1, (hi2 - kHalf) / kOne + 1));
    };
    for (int k = first(vMin); k <= last(vMax); ++k) {
      for (int j = first(uMin); j <= last(uMax); ++j) {
        const Point2 p{j * kOne + kHalf, k * kOne + kHalf};
        const std::int64_t w0 = orient(q[1], q[2], p), w1 = orient(q[2], q[0], p), w2 = orient(q[0], q[1], p);
        if (!coversEdge(w0, q[1], q[2]) || !coversEdge(w1, q[2], q[0]) || !coversEdge(w2, q[0], q[1])) continue;
        const double sum = static_cast<double>(w0) + static_cast<double>(w1) + static_cast<double>(w2);
        const double x =
            (static_cast<double>(w0) * g[0].x + static_cast<double>(w1) * g[1].x + static_cast<double>(w2) * g[2].x) /
            sum;
        crossings.push_back({static_cast<std::uint32_t>(j + n * k), x, sign});
      }
    }
  }
  std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) { return a.key() < b.key(); });

  voxels.solid.assign(static_cast<std::size_t>(n) * n * n, 0);
  for (std::size_t c = 0; c < crossings.size();) {
    const std::uint32_t column = crossings[c].column;
    const int j = static_cast<int>(column % n), k = static_cast<int>(column / n);
    std::int32_t winding = 0;
    for (int i = 0; i < n; ++i) {
      // Crossings before the centre count; one exactly at it is on the surface, either is right.
      while (c < crossings.size() && crossings[c].column == column && crossings[c].x < i + 0.5) {
        winding += crossings[c++].sign;
      }
      voxels.solid[voxels.index(i, j, k)] = winding != 0 ? 1 : 0;
    }
    while (c < crossings.size() && crossings[c].column == column) winding += crossings[c++].sign;
    if (winding != 0) {
      return fail("voxelizeSolid: the ray along x through cell column (y " + std::to_string(j) + ", z " +
                  std::to_string(k) + ") ends with winding number " + std::to_string(winding) +
                  ": the mesh is not closed.");
    }
  }
  return voxels;
}

}  // namespace mane::render
