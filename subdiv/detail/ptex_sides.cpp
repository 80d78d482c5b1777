#include "subdiv/detail/ptex_sides.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace mane::subdiv::detail {
namespace {

// Point names pack a kind, an id and a parameter into 64 bits.
enum class PointKind : std::uint64_t { kVertex = 1, kEdgePoint = 2, kSpokePoint = 3, kCentre = 4, kInterior = 5 };
constexpr unsigned kParameterBits = 2 * kGridBits + 2;  // interior (i, j) or a line parameter

std::uint64_t packName(PointKind kind, std::uint64_t id, std::uint64_t parameter) {
  return (std::uint64_t(kind) << 61) | (id << kParameterBits) | parameter;
}

}  // namespace

PtexSides::PtexSides(const Cage& cage) {
  // Cage edges in order of first use; each with the faces' corners that run along it.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edgeIds;
  struct EdgeUse {
    std::uint32_t uvAtLower = 0, uvAtHigher = 0;
    bool used = false;
  };
  std::vector<EdgeUse> firstUse;
  std::vector<std::uint32_t> faceOffsets;
  std::uint32_t offset = 0;
  for (std::uint32_t size : cage.faceSizes) {
    faceOffsets.push_back(offset);
    for (std::uint32_t k = 0; k < size; ++k) {
      const std::uint32_t a = cage.faceVertices[offset + k];
      const std::uint32_t b = cage.faceVertices[offset + (k + 1) % size];
      const auto key = std::minmax(a, b);
      auto [it, inserted] = edgeIds.try_emplace({key.first, key.second}, std::uint32_t(lines_.size()));
      if (inserted) {
        lines_.push_back({LineKind::kEdge, key.first, key.second, false});
        firstUse.emplace_back();
      }
      if (cage.hasUvs()) {
        // The edge is a UV seam when the faces on its two sides give an end different UVs.
        const std::uint32_t uvA = cage.faceUvIndices[offset + k];
        const std::uint32_t uvB = cage.faceUvIndices[offset + (k + 1) % size];
        const std::uint32_t uvLower = a < b ? uvA : uvB;
        const std::uint32_t uvHigher = a < b ? uvB : uvA;
        EdgeUse& use = firstUse[it->second];
        if (!use.used)
          use = {uvLower, uvHigher, true};
        else if (use.uvAtLower != uvLower || use.uvAtHigher != uvHigher)
          lines_[it->second].uvSeam = true;
      }
    }
    offset += size;
  }
  // A cage vertex is on a UV seam when its faces give it more than one UV.
  std::vector<std::uint32_t> vertexUv(cage.positions.size(), ~0u);
  std::vector<bool> vertexSeam(cage.positions.size(), false);
  for (std::size_t k = 0; cage.hasUvs() && k < cage.faceVertices.size(); ++k) {
    const std::uint32_t v = cage.faceVertices[k];
    if (vertexUv[v] == ~0u)
      vertexUv[v] = cage.faceUvIndices[k];
    else if (vertexUv[v] != cage.faceUvIndices[k])
      vertexSeam[v] = true;
  }
  const auto cornerTag = [&](std::uint32_t faceVertexIndex) {
    const std::uint32_t v = cage.faceVertices[faceVertexIndex];
    return vertexSeam[v] ? cage.faceUvIndices[faceVertexIndex] + 1 : 0u;
  };
  const auto edgeLine = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    return edgeIds.at({key.first, key.second});
  };
  // A side running from cage vertex `from` over `fraction` (1 or ½) of the edge to `to`,
  // with grid coordinate c going 0 → kGrid (or kGrid → 0 when `descending`).
  const auto sideOnEdge = [&](std::uint32_t from, std::uint32_t to, std::int64_t startParameterFromFrom,
                              std::int64_t scale, bool descending) {
    const std::uint32_t line = edgeLine(from, to);
    // Parameter measured from `from`: start + scale·c (ascending) or start + scale·(kGrid − c).
    std::int64_t offsetFromFrom = descending ? startParameterFromFrom + scale * kGrid : startParameterFromFrom;
    std::int64_t scaleFromFrom = descending ? -scale : scale;
    // The line's parameter runs from its lower vertex.
    if (from == lines_[line].start) return SideOnLine{line, offsetFromFrom, scaleFromFrom};
    return SideOnLine{line, kLineLength - offsetFromFrom, -scaleFromFrom};
  };

  for (std::uint32_t face = 0; face < cage.faceSizes.size(); ++face) {
    const std::uint32_t size = cage.faceSizes[face];
    const std::uint32_t base = faceOffsets[face];
    const auto vertex = [&](std::uint32_t k) { return cage.faceVertices[base + (k % size)]; };
    if (size == 4) {
      Face ptex;
      ptex.cageFace = face;
      // Side k runs from face vertex k to k+1; sides 2 and 3 have their grid coordinate
      // decreasing in that direction.
      for (std::uint32_t k = 0; k < 4; ++k) ptex.sides[k] = sideOnEdge(vertex(k), vertex(k + 1), 0, 2, k >= 2);
      for (std::uint32_t k = 0; k < 4; ++k) ptex.cornerUvTags[k] = cage.hasUvs() ? cornerTag(base + k) : 0u;
      faces_.push_back(ptex);
      continue;
    }
    // An n-gon: one spoke per edge k, from that edge's midpoint to the centre.
    const auto firstSpoke = std::uint32_t(lines_.size());
    for (std::uint32_t k = 0; k < size; ++k)
      lines_.push_back({LineKind::kSpoke, edgeLine(vertex(k), vertex(k + 1)), face, false});
    for (std::uint32_t j = 0; j < size; ++j) {
      Face ptex;
      ptex.cageFace = face;
      // Side 0: vertex j → midpoint of edge (j, j+1), the first half of that edge.
      ptex.sides[0] = sideOnEdge(vertex(j), vertex(j + 1), 0, 1, false);
      // Side 1: midpoint of edge j → centre, along spoke j, j ascending.
      ptex.sides[1] = SideOnLine{firstSpoke + j, 0, 2};
      // Side 2: midpoint of edge j−1 (i = 0) → centre (i = kGrid), along spoke j−1.
      ptex.sides[2] = SideOnLine{firstSpoke + (j + size - 1) % size, 0, 2};
      // Side 3: vertex j (j = 0) → midpoint of edge (j−1, j) (j = kGrid): the half of that
      // edge next to vertex j.
      ptex.sides[3] = sideOnEdge(vertex(j), vertex(j + size - 1), 0, 1, false);
      ptex.cornerUvTags[0] = cage.hasUvs() ? cornerTag(base + j) : 0u;
      faces_.push_back(ptex);
    }
  }
}

PointName PtexSides::nameOnLine(const Face& face, std::uint32_t line, std::int64_t parameter) const {
  const Line& l = lines_[line];
  if (l.kind == LineKind::kSpoke) {
    if (parameter == 0) return nameOnLine(face, l.start, kGrid);  // the edge's midpoint
    if (parameter == kLineLength) return {packName(PointKind::kCentre, l.end, 0), 0};
    return {packName(PointKind::kSpokePoint, line, std::uint64_t(parameter)), 0};
  }
  const std::uint32_t tag = l.uvSeam ? face.cageFace + 1 : 0u;
  if (parameter == 0) return {packName(PointKind::kVertex, l.start, 0), tag};
  if (parameter == kLineLength) return {packName(PointKind::kVertex, l.end, 0), tag};
  return {packName(PointKind::kEdgePoint, line, std::uint64_t(parameter)), tag};
}

PointName PtexSides::name(std::uint32_t ptexFace, std::int64_t i, std::int64_t j) const {
  const Face& face = faces_[ptexFace];
  if (i > 0 && i < kGrid && j > 0 && j < kGrid)
    return {packName(PointKind::kInterior, ptexFace, std::uint64_t((i << (kGridBits + 1)) | j)), 0};
  // Corners that are cage vertices take their UV tag from the face corner, not the edge.
  const bool atCorner = (i == 0 || i == kGrid) && (j == 0 || j == kGrid);
  const int corner = !atCorner ? -1 : j == 0 ? (i == 0 ? 0 : 1) : (i == 0 ? 3 : 2);
  const int side = j == 0 ? 0 : i == kGrid ? 1 : j == kGrid ? 2 : 3;
  const SideOnLine& s = face.sides[side];
  PointName result = nameOnLine(face, s.line, s.toLine(side % 2 == 0 ? i : j));
  if (corner >= 0 && (result.location >> 61) == std::uint64_t(PointKind::kVertex))
    result.uvTag = face.cornerUvTags[corner];
  return result;
}

}  // namespace mane::subdiv::detail
