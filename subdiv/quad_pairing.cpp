#include "subdiv/quad_pairing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/geometric.hpp>

namespace mane::subdiv {
namespace {

std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) {
  return (std::uint64_t(from) << 32) | to;
}

/// Two triangles that could become the quad (x, q, y, p): the first is (x, y, p), the second
/// (y, x, q), both counter-clockwise, sharing x–y.
struct Candidate {
  float worstCornerCosine = 0.0f;
  std::uint32_t first = 0, second = 0;  ///< face indices
  std::uint32_t firstCorner = 0;        ///< x's place in the first triangle
  std::uint32_t secondCorner = 0;       ///< y's place in the second
};

}  // namespace

QuadPairing pairTrianglesIntoQuads(const Cage& cage, const QuadPairingSettings& settings) {
  const std::size_t faceCount = cage.faceSizes.size();
  std::vector<std::size_t> offsets(faceCount);
  for (std::size_t f = 0, offset = 0; f < faceCount; offset += cage.faceSizes[f++]) offsets[f] = offset;
  const auto vertex = [&](std::size_t face, std::uint32_t k) {
    return cage.faceVertices[offsets[face] + k % cage.faceSizes[face]];
  };
  const auto uvIndex = [&](std::size_t face, std::uint32_t k) {
    return cage.faceUvIndices[offsets[face] + k % cage.faceSizes[face]];
  };
  const auto uv = [&](std::size_t face, std::uint32_t k) { return cage.uvs[uvIndex(face, k)]; };

  // Directed edge → (face, corner it starts at): a valid cage uses each directed edge once.
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> directed;
  for (std::size_t f = 0; f < faceCount; ++f)
    for (std::uint32_t k = 0; k < cage.faceSizes[f]; ++k)
      directed.emplace(edgeKey(vertex(f, k), vertex(f, k + 1)), std::pair{std::uint32_t(f), k});
  std::unordered_set<std::uint64_t> creased;
  for (const Crease& crease : cage.creases)
    if (crease.sharpness > 0.0f) creased.insert({edgeKey(crease.a, crease.b), edgeKey(crease.b, crease.a)});

  std::vector<Candidate> candidates;
  for (std::size_t f = 0; f < faceCount; ++f) {
    if (cage.faceSizes[f] != 3) continue;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t x = vertex(f, k), y = vertex(f, k + 1), p = vertex(f, k + 2);
      const auto across = directed.find(edgeKey(y, x));
      if (across == directed.end()) continue;
      const auto [g, m] = across->second;
      if (g <= f || cage.faceSizes[g] != 3 || creased.contains(edgeKey(x, y))) continue;
      const std::uint32_t q = vertex(g, m + 2);
      if (q == p) continue;
      if (cage.hasUvs() && (uv(f, k) != uv(g, m + 1) || uv(f, k + 1) != uv(g, m))) continue;
      const glm::vec3 corners[4] = {cage.positions[x], cage.positions[q], cage.positions[y], cage.positions[p]};
      float worst = 0.0f;
      for (int c = 0; c < 4; ++c) {
        const glm::vec3 toPrevious = glm::normalize(corners[(c + 3) % 4] - corners[c]);
        const glm::vec3 toNext = glm::normalize(corners[(c + 1) % 4] - corners[c]);
        worst = std::max(worst, std::abs(glm::dot(toPrevious, toNext)));
      }
      const glm::vec3 firstNormal = glm::normalize(glm::cross(corners[2] - corners[0], corners[3] - corners[0]));
      const glm::vec3 secondNormal = glm::normalize(glm::cross(corners[1] - corners[0], corners[2] - corners[0]));
      // NaN (a degenerate corner) fails both comparisons and is not paired.
      if (!(worst <= settings.maxCornerCosine) || !(glm::dot(firstNormal, secondNormal) >= settings.minNormalCosine))
        continue;
      candidates.push_back({worst, std::uint32_t(f), g, k, m});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.worstCornerCosine < b.worstCornerCosine; });

  QuadPairing result;
  Cage& out = result.cage;
  out.positions = cage.positions;
  out.uvs = cage.uvs;
  out.corners = cage.corners;
  out.boundary = cage.boundary;
  std::vector<bool> paired(faceCount, false);
  for (const Candidate& c : candidates) {
    if (paired[c.first] || paired[c.second]) continue;
    paired[c.first] = paired[c.second] = true;
    // (x, q, y, p): x and y from the first triangle, q from the second.
    out.faceSizes.push_back(4);
    out.faceVertices.insert(out.faceVertices.end(),
                            {vertex(c.first, c.firstCorner), vertex(c.second, c.secondCorner + 2),
                             vertex(c.first, c.firstCorner + 1), vertex(c.first, c.firstCorner + 2)});
    if (cage.hasUvs())
      out.faceUvIndices.insert(out.faceUvIndices.end(),
                               {uvIndex(c.first, c.firstCorner), uvIndex(c.second, c.secondCorner + 2),
                                uvIndex(c.first, c.firstCorner + 1), uvIndex(c.first, c.firstCorner + 2)});
    ++result.quads;
  }
  for (std::size_t f = 0; f < faceCount; ++f) {
    if (paired[f]) continue;
    out.faceSizes.push_back(cage.faceSizes[f]);
    for (std::uint32_t k = 0; k < cage.faceSizes[f]; ++k) {
      out.faceVertices.push_back(vertex(f, k));
      if (cage.hasUvs()) out.faceUvIndices.push_back(uvIndex(f, k));
    }
    if (cage.faceSizes[f] == 3) ++result.triangles;
  }
  // A crease on a removed diagonal is impossible (creased edges are not paired across).
  out.creases = cage.creases;
  return result;
}

}  // namespace mane::subdiv
