#include "physics/sdf.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <glm/common.hpp>

namespace mane::physics {

namespace {

constexpr double kPi = 3.14159265358979323846;

double dot(const glm::dvec3& a, const glm::dvec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
glm::dvec3 cross(const glm::dvec3& a, const glm::dvec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// atan(t) for t in [0, 1] with + − × ÷ and sqrt only, so the build gives the same bits with
// every C library: two half-angle reductions atan(t) = 2·atan(t / (1 + √(1 + t²))) bring t below
// tan(π/16) ≈ 0.199, where the Taylor series to t²³ is exact to double precision.
double atanUnit(double t) {
  for (int r = 0; r < 2; ++r) t = t / (1.0 + std::sqrt(1.0 + t * t));
  const double t2 = t * t;
  double sum = 0.0;
  for (int k = 11; k >= 0; --k) sum = (k % 2 == 0 ? 1.0 : -1.0) / static_cast<double>(2 * k + 1) + t2 * sum;
  return 4.0 * t * sum;
}

// Angle between vectors u and v, radians in [0, π]: atan2(|u × v|, u·v) via half angles.
double angleBetween(const glm::dvec3& u, const glm::dvec3& v) {
  const double y = std::sqrt(dot(cross(u, v), cross(u, v)));
  const double x = dot(u, v);
  const double r = std::sqrt(x * x + y * y);
  if (!(r > 0.0)) return 0.0;
  if (x >= 0.0) return 2.0 * atanUnit(y / (r + x));
  return kPi - 2.0 * atanUnit(y / (r - x));
}

struct Node {
  double distance = std::numeric_limits<double>::infinity();  // unsigned, metres
  std::int32_t triangle = -1;                                 // nearest triangle found so far
  std::int8_t sign = 0;                                       // +1 outside, −1 inside, 0 unknown
  bool exact = false;                                         // inside the narrow band
};

}  // namespace

glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                  int& feature) noexcept {
  // Ericson 2005, §5.1.5 "ClosestPtPointTriangle": Voronoi regions tested vertex, edge, face.
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return feature = 0, a;
  const glm::dvec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return feature = 1, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return feature = 3, a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return feature = 2, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return feature = 5, a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return feature = 4, b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = 1.0 / (va + vb + vc);
  feature = 6;
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

Result<SignedDistanceField> SignedDistanceField::build(std::span<const glm::vec3> positions,
                                                       std::span<const std::uint32_t> indices,
                                                       const SdfSettings& settings) {
  if (settings.paddingCells < 1 || settings.bandCells < 1 || settings.resolution < 4 ||
      settings.resolution - 1 - 2 * settings.paddingCells < 1)
    return fail("Signed distance field: settings need resolution ≥ 4, paddingCells ≥ 1, bandCells ≥ 1 and " +
                std::string("resolution − 1 − 2·paddingCells ≥ 1; got resolution ") +
                std::to_string(settings.resolution) + ", paddingCells " + std::to_string(settings.paddingCells) +
                ", bandCells " + std::to_string(settings.bandCells) + ".");
  if (positions.empty() || indices.empty())
    return fail("Signed distance field: the mesh is empty (" + std::to_string(positions.size()) + " positions, " +
                std::to_string(indices.size()) + " indices).");
  if (indices.size() % 3 != 0)
    return fail("Signed distance field: the index count " + std::to_string(indices.size()) +
                " is not a multiple of 3 (triangles).");
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (!(std::isfinite(positions[v].x) && std::isfinite(positions[v].y) && std::isfinite(positions[v].z)))
      return fail("Signed distance field: vertex " + std::to_string(v) + " is not finite (NaN or infinite).");
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= positions.size())
      return fail("Signed distance field: triangle " + std::to_string(i / 3) + " uses vertex " +
                  std::to_string(indices[i]) + ", but the mesh has " + std::to_string(positions.size()) + " vertices.");

  // Weld vertices with identical coordinates (glTF splits them at UV seams), so that edges and
  // vertices shared across seams get one pseudo-normal. Sorting makes the result order-free.
  std::vector<std::uint32_t> order(positions.size());
  for (std::uint32_t v = 0; v < order.size(); ++v) order[v] = v;
  const auto key = [&](std::uint32_t v) { return std::tuple(positions[v].x, positions[v].y, positions[v].z); };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t l, std::uint32_t r) { return key(l) != key(r) ? key(l) < key(r) : l < r; });
  std::vector<std::uint32_t> weld(positions.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    weld[order[k]] = (k > 0 && key(order[k]) == key(order[k - 1])) ? weld[order[k - 1]] : order[k];

  // Non-degenerate triangles, welded, with unit face normals.
  struct Triangle {
    std::array<std::uint32_t, 3> v;
    glm::dvec3 normal;
  };
  std::vector<Triangle> triangles;
  triangles.reserve(indices.size() / 3);
  for (std::size_t t = 0; t < indices.size() / 3; ++t) {
    Triangle tri{{weld[indices[3 * t]], weld[indices[3 * t + 1]], weld[indices[3 * t + 2]]}, {}};
    const glm::dvec3 a(positions[tri.v[0]]), b(positions[tri.v[1]]), c(positions[tri.v[2]]);
    const glm::dvec3 n = cross(b - a, c - a);
    const double length = std::sqrt(dot(n, n));
    if (!(length > 0.0) || tri.v[0] == tri.v[1] || tri.v[1] == tri.v[2] || tri.v[2] == tri.v[0]) continue;
    tri.normal = n / length;
    triangles.push_back(tri);
  }
  if (triangles.empty()) return fail("Signed distance field: every triangle of the mesh is degenerate (zero area).");

  // Angle-weighted pseudo-normals (Bærentzen & Aanæs 2005, eq. 3): vertices sum the incident
  // face normals weighted by the face's angle at the vertex; edges sum their two faces' normals.
  std::vector<glm::dvec3> vertexNormal(positions.size(), glm::dvec3(0.0));
  for (const Triangle& tri : triangles)
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p(positions[tri.v[k]]), q(positions[tri.v[(k + 1) % 3]]), r(positions[tri.v[(k + 2) % 3]]);
      vertexNormal[tri.v[k]] += tri.normal * angleBetween(q - p, r - p);
    }
  struct EdgeUse {
    std::uint64_t key;
    std::uint32_t triangle;
  };
  std::vector<EdgeUse> edges;
  edges.reserve(3 * triangles.size());
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t lo = std::min(triangles[t].v[k], triangles[t].v[(k + 1) % 3]);
      const std::uint64_t hi = std::max(triangles[t].v[k], triangles[t].v[(k + 1) % 3]);
      edges.push_back({(lo << 32) | hi, t});
    }
  std::sort(edges.begin(), edges.end(), [](const EdgeUse& l, const EdgeUse& r) {
    return l.key != r.key ? l.key < r.key : l.triangle < r.triangle;
  });
  std::vector<glm::dvec3> edgeNormal(3 * triangles.size(), glm::dvec3(0.0));  // slots ab, bc, ca
  for (std::size_t begin = 0; begin < edges.size();) {
    std::size_t end = begin;
    glm::dvec3 sum(0.0);
    while (end < edges.size() && edges[end].key == edges[begin].key) sum += triangles[edges[end++].triangle].normal;
    for (std::size_t e = begin; e < end; ++e) {
      const Triangle& tri = triangles[edges[e].triangle];
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t lo = std::min(tri.v[k], tri.v[(k + 1) % 3]);
        const std::uint64_t hi = std::max(tri.v[k], tri.v[(k + 1) % 3]);
        if (((lo << 32) | hi) == edges[begin].key) edgeNormal[3 * edges[e].triangle + k] = sum;
      }
    }
    begin = end;
  }

  // Grid: cubic cells; `resolution` nodes across the longest padded axis.
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const Triangle& tri : triangles)
    for (std::uint32_t v : tri.v) {
      lo = glm::min(lo, glm::dvec3(positions[v]));
      hi = glm::max(hi, glm::dvec3(positions[v]));
    }
  const glm::dvec3 extent = hi - lo;
  const double longest = std::max({extent.x, extent.y, extent.z, 1e-6});
  const double h = longest / static_cast<double>(settings.resolution - 1 - 2 * settings.paddingCells);
  SignedDistanceField field;
  glm::dvec3 origin;
  for (int axis = 0; axis < 3; ++axis) {
    const int cells = static_cast<int>(std::ceil(extent[axis] / h - 1e-9)) + 2 * settings.paddingCells;
    field.dims_[axis] = std::min(cells, settings.resolution - 1) + 1;
    origin[axis] = 0.5 * (lo[axis] + hi[axis]) - 0.5 * h * static_cast<double>(field.dims_[axis] - 1);
  }
  field.origin_ = glm::vec3(origin);
  field.cellSize_ = static_cast<float>(h);
  field.inverseCellSize_ = static_cast<float>(1.0 / h);
  const glm::ivec3 dims = field.dims_;
  const auto nodeIndex = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(dims.x) * (j + static_cast<std::size_t>(dims.y) * k);
  };
  // Node positions from the float origin and cell size actually stored, so the values belong
  // exactly to the points `sample` interpolates between.
  const auto nodePosition = [&](int i, int j, int k) {
    return glm::dvec3(field.origin_) + glm::dvec3(i, j, k) * static_cast<double>(field.cellSize_);
  };
  std::vector<Node> nodes(static_cast<std::size_t>(dims.x) * dims.y * dims.z);

  const auto distanceTo = [&](const glm::dvec3& p, std::int32_t t, int& feature, glm::dvec3& closest) {
    const Triangle& tri = triangles[static_cast<std::size_t>(t)];
    closest = closestPointOnTriangle(p, glm::dvec3(positions[tri.v[0]]), glm::dvec3(positions[tri.v[1]]),
                                     glm::dvec3(positions[tri.v[2]]), feature);
    const glm::dvec3 d = p - closest;
    return std::sqrt(dot(d, d));
  };

  // 1. Narrow band: each triangle offers its exact distance to the nodes near it.
  const double band = static_cast<double>(settings.bandCells) * static_cast<double>(field.cellSize_);
  for (std::int32_t t = 0; t < static_cast<std::int32_t>(triangles.size()); ++t) {
    glm::dvec3 tlo(positions[triangles[t].v[0]]), thi = tlo;
    for (std::uint32_t v : triangles[t].v) {
      tlo = glm::min(tlo, glm::dvec3(positions[v]));
      thi = glm::max(thi, glm::dvec3(positions[v]));
    }
    glm::ivec3 from, to;
    for (int axis = 0; axis < 3; ++axis) {
      from[axis] = std::max(0, static_cast<int>(std::ceil((tlo[axis] - band - origin[axis]) / h)));
      to[axis] = std::min(dims[axis] - 1, static_cast<int>(std::floor((thi[axis] + band - origin[axis]) / h)));
    }
    for (int k = from.z; k <= to.z; ++k)
      for (int j = from.y; j <= to.y; ++j)
        for (int i = from.x; i <= to.x; ++i) {
          Node& node = nodes[nodeIndex(i, j, k)];
          int feature;
          glm::dvec3 closest;
          const double d = distanceTo(nodePosition(i, j, k), t, feature, closest);
          if (d < node.distance) node.distance = d, node.triangle = t;
        }
  }

  // 2. Signs in the band from the pseudo-normal of the closest feature.
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        Node& node = nodes[nodeIndex(i, j, k)];
        if (node.triangle < 0 || !(node.distance <= band)) continue;
        node.exact = true;
        int feature;
        glm::dvec3 closest;
        const glm::dvec3 p = nodePosition(i, j, k);
        distanceTo(p, node.triangle, feature, closest);
        const Triangle& tri = triangles[static_cast<std::size_t>(node.triangle)];
        const glm::dvec3 pseudo = feature < 3   ? vertexNormal[tri.v[feature]]
                                  : feature < 6 ? edgeNormal[3 * static_cast<std::size_t>(node.triangle) + feature - 3]
                                                : tri.normal;
        node.sign = dot(p - closest, pseudo) < 0.0 ? -1 : 1;
      }

  // 3. Fast sweeping: nearest triangles and signs spread from the band (Bridson 2015).
  for (int round = 0; round < 2; ++round)
    for (int direction = 0; direction < 8; ++direction) {
      const int di = direction & 1 ? -1 : 1, dj = direction & 2 ? -1 : 1, dk = direction & 4 ? -1 : 1;
      const int i0 = di > 0 ? 0 : dims.x - 1, j0 = dj > 0 ? 0 : dims.y - 1, k0 = dk > 0 ? 0 : dims.z - 1;
      for (int k = k0; k >= 0 && k < dims.z; k += dk)
        for (int j = j0; j >= 0 && j < dims.y; j += dj)
          for (int i = i0; i >= 0 && i < dims.x; i += di) {
            Node& node = nodes[nodeIndex(i, j, k)];
            if (node.exact) continue;
            const glm::dvec3 p = nodePosition(i, j, k);
            for (int n = 1; n < 8; ++n) {  // the 7 upwind neighbours
              const int ni = i - (n & 1 ? di : 0), nj = j - (n & 2 ? dj : 0), nk = k - (n & 4 ? dk : 0);
              if (ni < 0 || nj < 0 || nk < 0 || ni >= dims.x || nj >= dims.y || nk >= dims.z) continue;
              const Node& neighbour = nodes[nodeIndex(ni, nj, nk)];
              if (node.sign == 0 && neighbour.sign != 0) node.sign = neighbour.sign;
              if (neighbour.triangle < 0 || neighbour.triangle == node.triangle) continue;
              int feature;
              glm::dvec3 closest;
              const double d = distanceTo(p, neighbour.triangle, feature, closest);
              if (d < node.distance) node.distance = d, node.triangle = neighbour.triangle;
            }
          }
    }

  field.values_.resize(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n)
    field.values_[n] = static_cast<float>(nodes[n].sign < 0 ? -nodes[n].distance : nodes[n].distance);
  field.findContactBox();
  return field;
}

TriangleMesh makeIcosphere(float radius, int subdivisions) {
  // Icosahedron: the cyclic permutations of (0, ±1, ±φ).
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> points = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                    {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                    {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  std::vector<std::uint32_t> indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                        4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                                        6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (glm::dvec3& p : points) p /= std::sqrt(dot(p, p));
  for (int level = 0; level < subdivisions; ++level) {
    std::unordered_map<std::uint64_t, std::uint32_t> midpoints;  // edge → its new vertex
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      const auto [where, added] = midpoints.try_emplace(key, static_cast<std::uint32_t>(points.size()));
      if (added) {
        const glm::dvec3 m = (points[a] + points[b]) * 0.5;
        points.push_back(m / std::sqrt(dot(m, m)));
      }
      return where->second;
    };
    std::vector<std::uint32_t> finer;
    finer.reserve(indices.size() * 4);
    for (std::size_t t = 0; t < indices.size(); t += 3) {
      const std::uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      for (std::uint32_t v : {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca}) finer.push_back(v);
    }
    indices = std::move(finer);
  }
  TriangleMesh mesh;
  mesh.positions.reserve(points.size());
  for (const glm::dvec3& p : points) mesh.positions.emplace_back(p * static_cast<double>(radius));
  mesh.indices = std::move(indices);
  return mesh;
}

void SignedDistanceField::findContactBox() {
  // A trilinear sample is a convex combination of its cell's 8 node values, so in a cell whose
  // nodes are all ≥ level it is ≥ level up to rounding (a few ulps, far below 1e-6 m here).
  // Half a cell: nodes within that of the surface sit at least one padding cell minus half a
  // cell inside the grid, so the contact cells stay off the boundary with the minimum padding.
  const float level = 0.5f * cellSize_;
  contactCells_.assign((values_.size() + 31) / 32, 0u);
  glm::ivec3 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
  for (int k = 0; k + 1 < dims_.z; ++k)
    for (int j = 0; j + 1 < dims_.y; ++j)
      for (int i = 0; i + 1 < dims_.x; ++i) {
        const float* v =
            values_.data() + static_cast<std::size_t>(i) +
            static_cast<std::size_t>(dims_.x) *
                (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims_.y) * static_cast<std::size_t>(k));
        const std::size_t sy = static_cast<std::size_t>(dims_.x), sz = sy * static_cast<std::size_t>(dims_.y);
        const float lowest = std::min({v[0], v[1], v[sy], v[sy + 1], v[sz], v[sz + 1], v[sz + sy], v[sz + sy + 1]});
        if (!(lowest >= level)) {
          lo = glm::min(lo, glm::ivec3(i, j, k)), hi = glm::max(hi, glm::ivec3(i, j, k));
          const auto cell = static_cast<std::size_t>(v - values_.data());
          contactCells_[cell / 32] |= 1u << (cell % 32);
        }
      }
  if (lo.x > hi.x) {  // nothing below the level anywhere: an empty box
    contactLevel_ = level;
    contactLower_ = glm::vec3(1.0f);
    contactUpper_ = glm::vec3(-1.0f);
    return;
  }
  // A point outside the grid samples its clamped image on the boundary: the cull holds only when
  // the contact cells stay off the boundary cells.
  if (lo.x < 1 || lo.y < 1 || lo.z < 1 || hi.x > dims_.x - 3 || hi.y > dims_.y - 3 || hi.z > dims_.z - 3) {
    contactLevel_ = -std::numeric_limits<float>::infinity();
    contactCells_.clear();
    return;
  }
  contactLevel_ = level;
  contactLower_ = origin_ + glm::vec3(lo - 1) * cellSize_;
  contactUpper_ = origin_ + glm::vec3(hi + 2) * cellSize_;
}

glm::vec3 SignedDistanceField::upperCorner() const noexcept {
  return origin_ + glm::vec3(dims_ - 1) * cellSize_;
}

bool SignedDistanceField::insideGrid(const glm::vec3& p) const noexcept {
  const glm::vec3 u = (p - origin_) * inverseCellSize_;
  return u.x >= 0.0f && u.y >= 0.0f && u.z >= 0.0f && u.x <= static_cast<float>(dims_.x - 1) &&
         u.y <= static_cast<float>(dims_.y - 1) && u.z <= static_cast<float>(dims_.z - 1);
}

}  // namespace mane::physics
