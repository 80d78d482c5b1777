#include "scenes/mesh_curvature.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <unordered_map>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace mane::scenes {
namespace {

// A triangle is skipped when twice its area is at most this times its longest edge squared
// (roughly: its smallest angle is below 1e-10 rad), where float positions leave its
// cotangents to rounding noise.
constexpr double kDegenerateRatio = 1e-10;

std::string describe(glm::vec3 p) {
  // snprintf rather than "(" + std::to_string(…): g++ 12 reports a false -Wrestrict on the
  // latter (GCC bug 105329).
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", static_cast<double>(p.x), static_cast<double>(p.y),
                static_cast<double>(p.z));
  return text;
}

/// Maps each vertex to the lowest-numbered vertex within `tolerance` of it (a grid of cells
/// `tolerance` wide; a match is searched in the 27 cells around). Deterministic: vertices are
/// visited in order and the first representative found in a fixed cell order wins.
std::vector<std::uint32_t> weld(const std::vector<glm::vec3>& positions, double tolerance) {
  const auto n = static_cast<std::uint32_t>(positions.size());
  std::vector<std::uint32_t> rep(n);
  struct CellHash {
    std::size_t operator()(const std::array<std::int64_t, 3>& k) const {
      const auto u = [](std::int64_t x) { return static_cast<std::uint64_t>(x); };
      return static_cast<std::size_t>(u(k[0]) * 73856093u ^ u(k[1]) * 19349663u ^ u(k[2]) * 83492791u);
    }
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>, CellHash> cells;
  cells.reserve(n);
  // Cells must fit 64-bit integers: far from the origin with a tiny tolerance, weld exactly.
  double extent = 0.0;
  for (const glm::vec3& p : positions) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      extent = std::max({extent, std::abs(static_cast<double>(p.x)), std::abs(static_cast<double>(p.y)),
                         std::abs(static_cast<double>(p.z))});
    }
  }
  const bool exact = !(tolerance > 0.0) || !(extent / tolerance < 1e15);
  const auto key = [&](glm::vec3 p) -> std::array<std::int64_t, 3> {
    if (exact) {  // + 0.0f turns −0 into +0 so that the two compare equal
      return {std::bit_cast<std::int32_t>(p.x + 0.0f), std::bit_cast<std::int32_t>(p.y + 0.0f),
              std::bit_cast<std::int32_t>(p.z + 0.0f)};
    }
    return {static_cast<std::int64_t>(std::floor(p.x / tolerance)),
            static_cast<std::int64_t>(std::floor(p.y / tolerance)),
            static_cast<std::int64_t>(std::floor(p.z / tolerance))};
  };
  const double toleranceSq = tolerance * tolerance;
  for (std::uint32_t v = 0; v < n; ++v) {
    const glm::vec3 p = positions[v];
    rep[v] = v;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    const auto k = key(p);
    const int reach = exact ? 0 : 1;
    bool found = false;
    for (int dx = -reach; dx <= reach && !found; ++dx) {
      for (int dy = -reach; dy <= reach && !found; ++dy) {
        for (int dz = -reach; dz <= reach && !found; ++dz) {
          const auto cell = cells.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (cell == cells.end()) continue;
          for (std::uint32_t other : cell->second) {
            const glm::dvec3 d = glm::dvec3(positions[other]) - glm::dvec3(p);
            if (exact ? positions[other] == p : glm::dot(d, d) <= toleranceSq) {
              rep[v] = other;
              found = true;
              break;
            }
          }
        }
      }
    }
    if (!found) cells[k].push_back(v);
  }
  return rep;
}

/// Neighbour lists (compressed rows) over welded vertices, from the given triangles.
struct OneRings {
  std::vector<std::uint32_t> offsets;  // size n + 1
  std::vector<std::uint32_t> items;
};

OneRings neighbourRings(std::size_t n, const std::vector<std::uint32_t>& rep,
                        const std::vector<std::uint32_t>& indices) {
  std::vector<std::uint64_t> edges;  // both directions, (from << 32) | to
  edges.reserve(indices.size() * 2);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t a = rep[indices[t + c]];
      const std::uint64_t b = rep[indices[t + (c + 1) % 3]];
      if (a == b) continue;
      edges.push_back((a << 32) | b);
      edges.push_back((b << 32) | a);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  OneRings rings;
  rings.offsets.assign(n + 1, 0);
  rings.items.reserve(edges.size());
  for (std::uint64_t e : edges) {
    ++rings.offsets[(e >> 32) + 1];
    rings.items.push_back(static_cast<std::uint32_t>(e & 0xffffffffu));
  }
  for (std::size_t v = 0; v < n; ++v) rings.offsets[v + 1] += rings.offsets[v];
  return rings;
}

/// True when the triangles around `v` (each given by its two other corners) form one closed
/// fan; the caller has checked that every edge at `v` has exactly two triangles, so each
/// corner appears twice and the fan is a union of cycles: walk one and count its length.
bool isSingleFan(const std::vector<std::array<std::uint32_t, 2>>& link) {
  if (link.empty()) return false;
  std::size_t steps = 1;
  std::size_t current = 0;
  std::uint32_t next = link[0][1];
  while (next != link[0][0]) {
    std::size_t found = link.size();
    for (std::size_t i = 0; i < link.size(); ++i) {
      if (i == current) continue;
      if (link[i][0] == next) {
        found = i;
        next = link[i][1];
        break;
      }
      if (link[i][1] == next) {
        found = i;
        next = link[i][0];
        break;
      }
    }
    if (found == link.size() || ++steps > link.size()) return false;
    current = found;
  }
  return steps == link.size();
}

}  // namespace

Result<VertexCurvature> computeVertexCurvature(const Mesh& mesh, const CurvatureSettings& settings) {
  const std::size_t n = mesh.positions.size();
  const std::string where = "mesh '" + mesh.name + "': ";
  if (mesh.indices.size() % 3 != 0) {
    return fail(where + "index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != n) {
    return fail(where + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) + " positions");
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    const std::uint32_t v = mesh.indices[i];
    if (v >= n) {
      return fail(where + "triangle " + std::to_string(i / 3) + " uses vertex " + std::to_string(v) +
                  " but there are only " + std::to_string(n) + " positions");
    }
    const glm::vec3 p = mesh.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return fail(where + "vertex " + std::to_string(v) + " (used by triangle " + std::to_string(i / 3) +
                  ") has a non-finite position " + describe(p));
    }
  }

  // The diagonal of the used (hence finite) positions sets the weld tolerance.
  glm::dvec3 low(std::numeric_limits<double>::max());
  glm::dvec3 high(std::numeric_limits<double>::lowest());
  for (std::uint32_t v : mesh.indices) {
    low = glm::min(low, glm::dvec3(mesh.positions[v]));
    high = glm::max(high, glm::dvec3(mesh.positions[v]));
  }
  const double diagonal = mesh.indices.empty() ? 0.0 : glm::length(high - low);
  const std::vector<std::uint32_t> rep =
      weld(mesh.positions, std::max(0.0, static_cast<double>(settings.relativeWeldTolerance)) * diagonal);

  // Meyer's per-triangle terms, accumulated on welded vertices.
  std::vector<glm::dvec3> laplacian(n, glm::dvec3(0.0));  // Σ (cot α + cot β)(x_i − x_j)
  std::vector<double> area(n, 0.0);                       // A_mixed
  std::vector<double> angleSum(n, 0.0);
  std::vector<std::uint8_t> flags(n, kCurvatureUnused);
  std::vector<std::uint32_t> kept;  // welded corners of the triangles used
  kept.reserve(mesh.indices.size());
  std::size_t skipped = 0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::array<std::uint32_t, 3> v = {rep[mesh.indices[t]], rep[mesh.indices[t + 1]], rep[mesh.indices[t + 2]]};
    const std::array<glm::dvec3, 3> p = {glm::dvec3(mesh.positions[v[0]]), glm::dvec3(mesh.positions[v[1]]),
                                         glm::dvec3(mesh.positions[v[2]])};
    // Edge opposite corner c: from corner c+1 to corner c+2.
    const std::array<glm::dvec3, 3> e = {p[2] - p[1], p[0] - p[2], p[1] - p[0]};
    const double twiceArea = glm::length(glm::cross(e[2], -e[1]));
    const double longestSq = std::max({glm::dot(e[0], e[0]), glm::dot(e[1], e[1]), glm::dot(e[2], e[2])});
    for (std::uint32_t c : v) flags[c] &= static_cast<std::uint8_t>(~kCurvatureUnused);
    if (!(twiceArea > kDegenerateRatio * longestSq)) {
      ++skipped;
      for (std::uint32_t c : v) flags[c] |= kCurvatureDegenerate;
      continue;
    }
    kept.insert(kept.end(), v.begin(), v.end());
    std::array<double, 3> dots{};  // at corner c: (x_{c+1} − x_c)·(x_{c+2} − x_c)
    std::array<double, 3> cot{};
    for (int c = 0; c < 3; ++c) {
      dots[c] = -glm::dot(e[(c + 1) % 3], e[(c + 2) % 3]);
      cot[c] = dots[c] / twiceArea;
      angleSum[v[c]] += std::atan2(twiceArea, dots[c]);
    }
    for (int c = 0; c < 3; ++c) {
      const int a = (c + 1) % 3;
      const int b = (c + 2) % 3;
      // Edge (a, b) is opposite corner c, weight cot θ_c (Meyer eq. 8, one of its two triangles).
      laplacian[v[a]] += cot[c] * (p[a] - p[b]);
      laplacian[v[b]] += cot[c] * (p[b] - p[a]);
    }
    const bool obtuse = dots[0] < 0.0 || dots[1] < 0.0 || dots[2] < 0.0;
    for (int c = 0; c < 3; ++c) {
      if (!obtuse) {  // Voronoi region of corner c: 1/8 Σ |edge from c|² cot(opposite angle)
        const int a = (c + 1) % 3;
        const int b = (c + 2) % 3;
        area[v[c]] += (glm::dot(e[b], e[b]) * cot[b] + glm::dot(e[a], e[a]) * cot[a]) / 8.0;
      } else {
        area[v[c]] += twiceArea * (dots[c] < 0.0 ? 0.25 : 0.125);
      }
    }
  }

  // Topology on the kept triangles: boundary (edge with one triangle), non-manifold (3+).
  std::vector<std::uint64_t> edges;
  edges.reserve(kept.size());
  for (std::size_t t = 0; t < kept.size(); t += 3) {
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t a = kept[t + c];
      const std::uint64_t b = kept[t + (c + 1) % 3];
      edges.push_back((std::min(a, b) << 32) | std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    const std::uint8_t flag = j - i == 1 ? kCurvatureBoundary : j - i > 2 ? kCurvatureNonManifold : 0;
    flags[edges[i] >> 32] |= flag;
    flags[edges[i] & 0xffffffffu] |= flag;
    i = j;
  }
  // A vertex whose edges are all manifold can still join two fans (a "bowtie").
  std::vector<std::uint32_t> fanOffsets(n + 1, 0);
  for (std::uint32_t c : kept) ++fanOffsets[c + 1];
  for (std::size_t i = 0; i < n; ++i) fanOffsets[i + 1] += fanOffsets[i];
  std::vector<std::uint32_t> fanTriangles(kept.size());
  {
    std::vector<std::uint32_t> fill(fanOffsets.begin(), fanOffsets.end() - 1);
    for (std::size_t i = 0; i < kept.size(); ++i) fanTriangles[fill[kept[i]]++] = static_cast<std::uint32_t>(i / 3);
  }
  std::vector<std::array<std::uint32_t, 2>> link;
  for (std::size_t i = 0; i < n; ++i) {
    if (flags[i] != 0 || rep[i] != i) continue;
    link.clear();
    for (std::uint32_t k = fanOffsets[i]; k < fanOffsets[i + 1]; ++k) {
      const std::size_t t = 3 * static_cast<std::size_t>(fanTriangles[k]);
      const int c = kept[t] == i ? 0 : kept[t + 1] == i ? 1 : 2;
      link.push_back({kept[t + (c + 1) % 3], kept[t + (c + 2) % 3]});
    }
    if (!isSingleFan(link)) flags[i] |= kCurvatureNonManifold;
  }

  // Normals for the sign, summed over welded copies.
  std::vector<glm::dvec3> normal(n, glm::dvec3(0.0));
  if (!mesh.normals.empty()) {
    for (std::size_t i = 0; i < n; ++i) normal[rep[i]] += glm::dvec3(mesh.normals[i]);
  } else {
    for (std::size_t t = 0; t < kept.size(); t += 3) {
      const glm::dvec3 a(mesh.positions[kept[t]]);
      const glm::dvec3 face =
          glm::cross(glm::dvec3(mesh.positions[kept[t + 1]]) - a, glm::dvec3(mesh.positions[kept[t + 2]]) - a);
      for (int c = 0; c < 3; ++c) normal[kept[t + c]] += face;
    }
  }

  VertexCurvature out;
  out.meanCurvature.assign(n, 0.0f);
  out.gaussianCurvature.assign(n, 0.0f);
  out.maxCurvature.assign(n, 0.0f);
  out.minCurvature.assign(n, 0.0f);
  out.mixedArea.assign(n, 0.0f);
  out.flags.resize(n);
  out.weldedVertex = rep;
  out.skippedTriangles = skipped;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = rep[i];
    out.flags[i] = flags[r];
    out.mixedArea[i] = flags[r] == 0 ? static_cast<float>(area[r]) : 0.0f;
    if (flags[r] != 0 || !(area[r] > 0.0)) continue;
    if (r != i) {  // a welded copy: same values as its representative, computed earlier
      out.meanCurvature[i] = out.meanCurvature[r];
      out.gaussianCurvature[i] = out.gaussianCurvature[r];
      out.maxCurvature[i] = out.maxCurvature[r];
      out.minCurvature[i] = out.minCurvature[r];
      continue;
    }
    const double sign = glm::dot(laplacian[i], normal[i]) < 0.0 ? -1.0 : 1.0;
    const double h = sign * glm::length(laplacian[i]) / (4.0 * area[i]);
    const double k = (2.0 * std::numbers::pi - angleSum[i]) / area[i];
    const double spread = std::sqrt(std::max(h * h - k, 0.0));
    out.meanCurvature[i] = static_cast<float>(h);
    out.gaussianCurvature[i] = static_cast<float>(k);
    out.maxCurvature[i] = static_cast<float>(h + spread);
    out.minCurvature[i] = static_cast<float>(h - spread);
  }
  return out;
}

Result<std::vector<float>> skinInverseRadius(const Mesh& mesh, const VertexCurvature& curvature,
                                             const SkinCurvatureSettings& settings) {
  const std::size_t n = mesh.positions.size();
  if (curvature.vertexCount() != n || curvature.flags.size() != n || curvature.weldedVertex.size() != n) {
    return fail("mesh '" + mesh.name + "': curvature for " + std::to_string(curvature.vertexCount()) +
                " vertices given for " + std::to_string(n) + " positions");
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= n) {
      return fail("mesh '" + mesh.name + "': triangle " + std::to_string(i / 3) + " uses vertex " +
                  std::to_string(mesh.indices[i]) + " but there are only " + std::to_string(n) + " positions");
    }
  }
  const std::vector<std::uint32_t>& rep = curvature.weldedVertex;
  for (std::size_t i = 0; i < n; ++i) {
    if (rep[i] > i)
      return fail("mesh '" + mesh.name + "': curvature's welded vertex of " + std::to_string(i) + " is " +
                  std::to_string(rep[i]) + ", not a lower-numbered vertex");
  }
  const OneRings rings = neighbourRings(n, rep, mesh.indices);

  // Work on representatives only; copies take their value at the end.
  std::vector<float> value(n, 0.0f);
  std::vector<std::uint8_t> known(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (rep[i] != i || curvature.flags[i] != 0) continue;
    const float h = curvature.meanCurvature[i];
    value[i] = settings.measure == SkinCurvatureMeasure::meanAbsolute
                   ? std::abs(h)
                   : std::max(std::abs(curvature.maxCurvature[i]), std::abs(curvature.minCurvature[i]));
    known[i] = 1;
  }
  // Fill outward from known vertices, one ring per pass (Jacobi: a pass reads only values
  // known before it, so the result does not depend on vertex order).
  std::vector<std::uint32_t> filled;
  for (;;) {
    filled.clear();
    for (std::uint32_t i = 0; i < n; ++i) {
      if (known[i] || rep[i] != i) continue;
      double sum = 0.0;
      int count = 0;
      for (std::uint32_t k = rings.offsets[i]; k < rings.offsets[i + 1]; ++k) {
        const std::uint32_t j = rings.items[k];
        if (known[j] == 1) {
          sum += value[j];
          ++count;
        }
      }
      if (count > 0) {
        value[i] = static_cast<float>(sum / count);
        filled.push_back(i);
      }
    }
    if (filled.empty()) break;
    for (std::uint32_t i : filled) known[i] = 1;
  }
  std::vector<float> next(n);
  for (int pass = 0; pass < settings.smoothingPasses; ++pass) {
    for (std::size_t i = 0; i < n; ++i) {
      double sum = value[i];
      for (std::uint32_t k = rings.offsets[i]; k < rings.offsets[i + 1]; ++k) sum += value[rings.items[k]];
      next[i] = static_cast<float>(sum / (1.0 + (rings.offsets[i + 1] - rings.offsets[i])));
    }
    value.swap(next);
  }
  for (std::size_t i = 0; i < n; ++i) value[i] = value[rep[i]];
  return value;
}

float skinLutCoordinate(float inverseRadiusPerUnit, const SkinLutCurvatureRange& range) {
  const float perMm = inverseRadiusPerMillimetre(inverseRadiusPerUnit, range.millimetresPerUnit);
  return std::clamp((perMm - range.minInverseRadius) / (range.maxInverseRadius - range.minInverseRadius), 0.0f, 1.0f);
}

}  // namespace mane::scenes
