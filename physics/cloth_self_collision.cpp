#include "physics/cloth_self_collision.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace mane::physics {
namespace {

// A triangle (or a query) that sweeps over more cells than this along an axis in one step, four
// times the average, is skipped: it would flood the table, and only a cloth that is whipped or
// has blown apart has one.
constexpr int kMaxCellsPerAxis = 4;

using Cell = std::array<std::int32_t, 3>;

// Teschner et al. 2003's hash of a cell, with their three primes.
std::uint32_t bucketOf(const Cell& cell, std::size_t buckets) {
  const std::uint32_t h = (static_cast<std::uint32_t>(cell[0]) * 73856093u) ^
                          (static_cast<std::uint32_t>(cell[1]) * 19349663u) ^
                          (static_cast<std::uint32_t>(cell[2]) * 83492791u);
  return h % static_cast<std::uint32_t>(buckets);
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

// The cells a box [low, high] overlaps, from `from` to `to` on each axis; none for a box that is
// not finite, lies beyond a million cells from the origin or spans more than kMaxCellsPerAxis.
ClothSelfCollision::CellRange ClothSelfCollision::cellsOf(const glm::vec3& low, const glm::vec3& high,
                                                          float inverseCell) {
  CellRange range;
  constexpr float kFarthest = 1e6f;
  for (int axis = 0; axis < 3; ++axis) {
    const float first = std::floor(low[axis] * inverseCell), last = std::floor(high[axis] * inverseCell);
    if (!(first >= -kFarthest && last <= kFarthest && last - first < float(kMaxCellsPerAxis))) return range;
    range.from[axis] = static_cast<std::int32_t>(first);
    range.to[axis] = static_cast<std::int32_t>(last);
  }
  range.empty = false;
  return range;
}

ClothSelfCollision::ClothSelfCollision(std::span<const std::uint32_t> triangles, std::size_t vertexCount,
                                       float thickness)
    : triangles_(triangles.begin(), triangles.end()), thickness_(thickness) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edgeIndex;
  for (std::size_t t = 0; t + 2 < triangles_.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles_[t + k], b = triangles_[t + (k + 1) % 3];
      const auto [found, added] =
          edgeIndex.try_emplace({std::min(a, b), std::max(a, b)}, static_cast<std::uint32_t>(edges_.size()));
      if (added) edges_.push_back(found->first);
      triangleEdges_.push_back(found->second);
    }
  std::vector<std::vector<std::uint32_t>> rings(vertexCount);
  for (std::uint32_t v = 0; v < vertexCount; ++v) rings[v].push_back(v);
  for (std::size_t t = 0; t + 2 < triangles_.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles_[t + k], b = triangles_[t + (k + 1) % 3];
      rings[a].push_back(b);
      rings[b].push_back(a);
    }
  neighbourStarts_.push_back(0);
  for (auto& ring : rings) {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    neighbours_.insert(neighbours_.end(), ring.begin(), ring.end());
    neighbourStarts_.push_back(static_cast<std::uint32_t>(neighbours_.size()));
  }
}

bool ClothSelfCollision::neighbours(std::uint32_t vertex, std::uint32_t other) const {
  return std::binary_search(neighbours_.begin() + neighbourStarts_[vertex],
                            neighbours_.begin() + neighbourStarts_[vertex + 1], other);
}

bool ClothSelfCollision::touches(std::uint32_t vertex, std::uint32_t triangle) const {
  for (int k = 0; k < 3; ++k)
    if (neighbours(vertex, triangles_[3 * triangle + k])) return true;
  return false;
}

// Cells as wide as the triangles' average swept box, so that each covers a few: every triangle is
// entered in each cell that its swept box, grown by the thickness, overlaps, and a query looks in
// the cells that its own box overlaps.
void ClothSelfCollision::hashTriangles(const Particles& particles) {
  const auto& positions = particles.positions;
  const std::size_t triangleCount = triangles_.size() / 3;
  std::vector<std::pair<glm::vec3, glm::vec3>>& boxes = boxes_;
  boxes.resize(triangleCount);
  double extentSum = 0.0;
  std::size_t finiteCount = 0;
  for (std::size_t t = 0; t < triangleCount; ++t) {
    // The box the triangle swept during the step, from its previous corners to its current ones.
    glm::vec3 low = positions[triangles_[3 * t]], high = low;
    for (int k = 0; k < 3; ++k)
      for (const auto* corners : {&positions, &particles.previousPositions}) {
        low = glm::min(low, (*corners)[triangles_[3 * t + k]]);
        high = glm::max(high, (*corners)[triangles_[3 * t + k]]);
      }
    boxes[t] = {low - thickness_, high + thickness_};
    if (!finite(boxes[t].first) || !finite(boxes[t].second)) continue;
    const glm::vec3 size = boxes[t].second - boxes[t].first;
    extentSum += std::max(size.x, std::max(size.y, size.z));
    ++finiteCount;
  }
  seen_.resize(triangleCount, 0u);
  cellSize_ = finiteCount > 0 ? static_cast<float>(extentSum / double(finiteCount)) : 1.0f;
  const float inverseCell = 1.0f / cellSize_;

  std::vector<CellRange>& ranges = ranges_;
  ranges.resize(triangleCount);
  // Twice as many buckets as entries keeps the chains of unrelated cells short.
  std::size_t entries = 0;
  for (std::uint32_t t = 0; t < triangleCount; ++t) {
    const CellRange& r = ranges[t] = cellsOf(boxes[t].first, boxes[t].second, inverseCell);
    if (!r.empty)
      entries += std::size_t(r.to[0] - r.from[0] + 1) * std::size_t(r.to[1] - r.from[1] + 1) *
                 std::size_t(r.to[2] - r.from[2] + 1);
  }
  const std::size_t buckets = 2 * entries + 1;
  bucketStarts_.assign(buckets + 1, 0);
  // Two passes, counting then filling, so each bucket lists its triangles in index order.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::uint32_t t = 0; t < triangleCount; ++t) {
      const CellRange& r = ranges[t];
      if (r.empty) continue;
      for (std::int32_t x = r.from[0]; x <= r.to[0]; ++x)
        for (std::int32_t y = r.from[1]; y <= r.to[1]; ++y)
          for (std::int32_t z = r.from[2]; z <= r.to[2]; ++z) {
            const std::uint32_t bucket = bucketOf({x, y, z}, buckets);
            if (pass == 0)
              ++bucketStarts_[bucket + 1];
            else
              bucketEntries_[bucketStarts_[bucket]++] = t;
          }
    }
    if (pass == 0) {
      for (std::size_t b = 0; b < buckets; ++b) bucketStarts_[b + 1] += bucketStarts_[b];
      bucketEntries_.resize(bucketStarts_[buckets]);
    } else {
      // Filling advanced each start to the next bucket's: shift them back.
      for (std::size_t b = buckets; b > 0; --b) bucketStarts_[b] = bucketStarts_[b - 1];
      bucketStarts_[0] = 0;
    }
  }
}

void ClothSelfCollision::gatherTriangles(const glm::vec3& low, const glm::vec3& high) {
  candidates_.clear();
  if (++query_ == 0) {  // wrapped: forget every stamp
    std::fill(seen_.begin(), seen_.end(), 0u);
    query_ = 1;
  }
  const std::size_t buckets = bucketStarts_.size() - 1;
  const float inverseCell = 1.0f / cellSize_;
  const CellRange r = cellsOf(low, high, inverseCell);
  if (r.empty) return;
  for (std::int32_t x = r.from[0]; x <= r.to[0]; ++x)
    for (std::int32_t y = r.from[1]; y <= r.to[1]; ++y)
      for (std::int32_t z = r.from[2]; z <= r.to[2]; ++z) {
        const std::uint32_t bucket = bucketOf({x, y, z}, buckets);
        for (std::uint32_t e = bucketStarts_[bucket]; e < bucketStarts_[bucket + 1]; ++e) {
          const std::uint32_t t = bucketEntries_[e];
          const auto& [boxLow, boxHigh] = boxes_[t];
          if (seen_[t] != query_ && glm::all(glm::lessThanEqual(low, boxHigh)) &&
              glm::all(glm::greaterThanEqual(high, boxLow))) {
            seen_[t] = query_;
            candidates_.push_back(t);
          }
        }
      }
  // In index order, so the corrections are applied in the same order whatever the hash.
  std::sort(candidates_.begin(), candidates_.end());
}

void ClothSelfCollision::resolve(Particles& particles) {
  hashTriangles(particles);
  resolveVertices(particles);
  resolveEdges(particles);
}

void ClothSelfCollision::resolveVertices(Particles& particles) {
  auto& positions = particles.positions;
  const auto& previous = particles.previousPositions;
  const auto& weights = particles.inverseMasses;
  // How far past a triangle a vertex may be found and still be taken to have gone through it in
  // this step, rather than to have come round its edge: about one cell, a triangle's size.
  const float reach = cellSize_;
  layered_.assign(positions.size(), 0);
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    if (weights[v] == 0.0f || !finite(positions[v])) continue;
    // Only a triangle whose swept box the vertex's path meets can touch it.
    gatherTriangles(glm::min(positions[v], previous[v]), glm::max(positions[v], previous[v]));
    for (const std::uint32_t t : candidates_) {
      if (touches(v, t)) continue;
      const std::uint32_t i0 = triangles_[3 * t], i1 = triangles_[3 * t + 1], i2 = triangles_[3 * t + 2];
      const glm::vec3 p0 = positions[i0], e1 = positions[i1] - p0, e2 = positions[i2] - p0;
      const glm::vec3 across = glm::cross(e1, e2);
      const float area2 = glm::length(across);
      if (!(area2 > 0.0f)) continue;
      const glm::vec3 normal = across / area2;
      const glm::vec3 q = positions[v] - p0;
      const float distance = glm::dot(q, normal);
      if (std::abs(distance) >= reach) continue;
      // Barycentric coordinates of the point's projection onto the plane; outside the triangle
      // (with a margin that closes the cracks between neighbours) there is no contact.
      const glm::vec3 onPlane = q - distance * normal;
      const float b1 = glm::dot(glm::cross(onPlane, e2), normal) / area2;
      const float b2 = glm::dot(glm::cross(e1, onPlane), normal) / area2;
      const float b0 = 1.0f - b1 - b2;
      constexpr float kMargin = 0.02f;
      if (b0 < -kMargin || b1 < -kMargin || b2 < -kMargin) continue;
      layered_[v] = 1;
      // The side it started the step on, from the previous positions (the current one where the
      // triangle had no area then).
      const glm::vec3 before = glm::cross(previous[i1] - previous[i0], previous[i2] - previous[i0]);
      const float side0 = glm::dot(previous[v] - previous[i0], before);
      const float side = side0 != 0.0f ? (side0 > 0.0f ? 1.0f : -1.0f) : (distance >= 0.0f ? 1.0f : -1.0f);
      const float gap = side * distance;
      if (gap >= thickness_) continue;
      const float w = weights[v] + weights[i0] * b0 * b0 + weights[i1] * b1 * b1 + weights[i2] * b2 * b2;
      if (!(w > 0.0f)) continue;
      const glm::vec3 push = ((thickness_ - gap) / w) * side * normal;
      positions[v] += weights[v] * push;
      positions[i0] -= weights[i0] * b0 * push;
      positions[i1] -= weights[i1] * b1 * push;
      positions[i2] -= weights[i2] * b2 * push;
    }
  }
}

// Two edges can cross with every corner far from the other's triangles (a long edge through a
// short triangle): each edge is kept `thickness` from the edges of the triangles near it, along
// the line between their closest points, on the side that line pointed to at the step's start.
// Only where cloth lies over cloth can that happen: edges with a corner that the vertex pass found
// over another layer (within a cell of a triangle that it is not part of, above its inside).
void ClothSelfCollision::resolveEdges(Particles& particles) {
  auto& positions = particles.positions;
  const auto& previous = particles.previousPositions;
  const auto& weights = particles.inverseMasses;
  const auto inFold = [&](std::uint32_t edge) { return layered_[edges_[edge].first] || layered_[edges_[edge].second]; };
  for (std::uint32_t e = 0; e < edges_.size(); ++e) {
    const auto [a, b] = edges_[e];
    if ((weights[a] == 0.0f && weights[b] == 0.0f) || !inFold(e)) continue;
    const glm::vec3 low = glm::min(glm::min(positions[a], previous[a]), glm::min(positions[b], previous[b]));
    const glm::vec3 high = glm::max(glm::max(positions[a], previous[a]), glm::max(positions[b], previous[b]));
    if (!finite(low) || !finite(high)) continue;
    gatherTriangles(low, high);
    for (const std::uint32_t t : candidates_)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t f = triangleEdges_[3 * t + k];
        // Each pair once (by the lower edge index where both are in a fold), and none that share
        // a corner or whose corners are neighbours: those lie within an edge of each other at rest.
        if (f == e || (f < e && inFold(f))) continue;
        const auto [c, d] = edges_[f];
        if (neighbours(a, c) || neighbours(a, d) || neighbours(b, c) || neighbours(b, d)) continue;
        // Closest points a + s(b − a) and c + u(d − c) (Ericson 2005, §5.1.9); only where both
        // lie inside their edges is this an edge–edge contact (else a corner's, or none).
        const glm::vec3 r = positions[a] - positions[c], ab = positions[b] - positions[a],
                        cd = positions[d] - positions[c];
        const float aa = glm::dot(ab, ab), cc = glm::dot(cd, cd), ac = glm::dot(ab, cd);
        const float ar = glm::dot(ab, r), cr = glm::dot(cd, r);
        const float denominator = aa * cc - ac * ac;
        if (!(denominator > 1e-12f * aa * cc)) continue;  // parallel
        const float s = (ac * cr - ar * cc) / denominator, u = (aa * cr - ac * ar) / denominator;
        constexpr float kInside = 0.01f;
        if (s < kInside || s > 1.0f - kInside || u < kInside || u > 1.0f - kInside) continue;
        const glm::vec3 between = (positions[a] + s * ab) - (positions[c] + u * cd);
        const glm::vec3 before =
            (previous[a] + s * (previous[b] - previous[a])) - (previous[c] + u * (previous[d] - previous[c]));
        const float length0 = glm::length(before);
        if (!(length0 > 0.0f)) continue;
        const glm::vec3 normal = before / length0;
        const float gap = glm::dot(between, normal);
        if (gap >= thickness_ || gap < -cellSize_) continue;
        const float w =
            weights[a] * (1 - s) * (1 - s) + weights[b] * s * s + weights[c] * (1 - u) * (1 - u) + weights[d] * u * u;
        if (!(w > 0.0f)) continue;
        const glm::vec3 push = ((thickness_ - gap) / w) * normal;
        positions[a] += weights[a] * (1 - s) * push;
        positions[b] += weights[b] * s * push;
        positions[c] -= weights[c] * (1 - u) * push;
        positions[d] -= weights[d] * u * push;
      }
  }
}

}  // namespace mane::physics
