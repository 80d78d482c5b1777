#include "render/luts/solid_segments.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace mane::render {

namespace {

constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
// Jump only across cubes at least this many cells from their centre to their side: a jump costs
// a few divisions, about as much as two plain steps.
constexpr int kMinimumJump = 2;

// The state of one walk from the centre of cell `from` towards the centre of cell `to`, times
// as integers over `denominator` (see solid_segments.hpp).
struct Walk {
  std::int64_t denominator = 2;
  std::array<std::int64_t, 3> crossing{};   // the next crossing per axis (kNever: none)
  std::array<std::int64_t, 3> increment{};  // between crossings per axis
  std::array<std::ptrdiff_t, 3> step{};     // cell index change per crossing
  std::ptrdiff_t cell = 0;
  std::int64_t previous = 0;  // when the walk entered `cell`
  std::int64_t inside = 0;    // solid time so far

  Walk(const SolidVoxels& voxels, const glm::ivec3& from, const glm::ivec3& to) {
    const auto n = static_cast<std::ptrdiff_t>(voxels.resolution);
    const std::array<std::ptrdiff_t, 3> stride{1, n, n * n};
    for (int a = 0; a < 3; ++a) denominator *= std::max(1, std::abs(to[a] - from[a]));
    for (int a = 0; a < 3; ++a) {
      const int delta = to[a] - from[a];
      const std::int64_t half = delta == 0 ? 0 : denominator / (2 * std::abs(delta));
      crossing[a] = delta == 0 ? kNever : half;
      increment[a] = 2 * half;
      step[a] = delta < 0 ? -stride[a] : stride[a];
    }
    cell = static_cast<std::ptrdiff_t>(voxels.index(from.x, from.y, from.z));
  }

  // One plain step to the next cell; false once the segment's end is reached.
  bool advance(const std::uint8_t* solid) {
    const std::int64_t t = std::min({crossing[0], crossing[1], crossing[2]});
    // The last crossing of an axis is (2|Δ| − 1)·D/(2|Δ|) < D; the one after it is beyond D.
    if (t >= denominator) {
      if (solid[cell] != 0) inside += denominator - previous;
      return false;
    }
    if (solid[cell] != 0) inside += t - previous;
    previous = t;
    for (int a = 0; a < 3; ++a) {
      if (crossing[a] == t) {
        cell += step[a];
        crossing[a] += increment[a];
      }
    }
    return true;
  }

  // Every cell within `radius` of the current one is alike: move to the last cell before the
  // segment leaves that cube, adding the stretch at once. False once the segment's end is reached.
  bool jump(const std::uint8_t* solid, std::int64_t radius) {
    std::int64_t exit = kNever;  // the (radius + 1)-th next crossing: the cube's side
    for (int a = 0; a < 3; ++a) {
      if (crossing[a] != kNever) exit = std::min(exit, crossing[a] + radius * increment[a]);
    }
    const bool isSolid = solid[cell] != 0;
    if (exit >= denominator) {
      if (isSolid) inside += denominator - previous;
      return false;
    }
    std::int64_t last = previous;
    for (int a = 0; a < 3; ++a) {
      if (crossing[a] >= exit) continue;  // also kNever
      const std::int64_t taken = (exit - 1 - crossing[a]) / increment[a] + 1;
      last = std::max(last, crossing[a] + (taken - 1) * increment[a]);
      crossing[a] += taken * increment[a];
      cell += taken * step[a];
    }
    if (isSolid) inside += last - previous;
    previous = last;
    return true;
  }

  double fraction() const { return static_cast<double>(inside) / static_cast<double>(denominator); }
};

}  // namespace

double solidFractionBetweenCells(const SolidVoxels& voxels, const glm::ivec3& from, const glm::ivec3& to) noexcept {
  Walk walk(voxels, from, to);
  while (walk.advance(voxels.solid.data())) {
  }
  return walk.fraction();
}

double distanceBetweenCells(const SolidVoxels& voxels, const glm::ivec3& from, const glm::ivec3& to) noexcept {
  const glm::dvec3 d = glm::dvec3(to - from) * voxels.voxelSize;
  return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

SolidSegmentWalker::SolidSegmentWalker(const SolidVoxels& voxels) : voxels_(&voxels) {
  // Breadth-first over the 26 neighbours from the cells that touch the other kind (distance 1).
  // Along a shortest Chebyshev path to the nearest other cell every cell but the last is alike,
  // so the search distance is exactly the Chebyshev distance.
  const int n = voxels.resolution;
  reach_.assign(voxels.cellCount(), 0);
  std::vector<std::uint32_t> queue;
  const auto forNeighbours = [&](std::size_t cell, auto&& visit) {
    const glm::ivec3 c = voxels.coordinates(cell);
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec3 e = c + glm::ivec3(dx, dy, dz);
          if ((dx | dy | dz) == 0 || e.x < 0 || e.y < 0 || e.z < 0 || e.x >= n || e.y >= n || e.z >= n) continue;
          visit(voxels.index(e.x, e.y, e.z));
        }
      }
    }
  };
  for (std::size_t cell = 0; cell < voxels.cellCount(); ++cell) {
    bool touches = false;
    forNeighbours(cell, [&](std::size_t e) { touches = touches || voxels.solid[e] != voxels.solid[cell]; });
    if (touches) {
      reach_[cell] = 1;
      queue.push_back(static_cast<std::uint32_t>(cell));
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint8_t next = static_cast<std::uint8_t>(std::min(255, reach_[queue[head]] + 1));
    forNeighbours(queue[head], [&](std::size_t e) {
      if (reach_[e] != 0) return;
      reach_[e] = next;
      queue.push_back(static_cast<std::uint32_t>(e));
    });
  }
  for (std::uint8_t& r : reach_) r = r == 0 ? 255 : r;  // no other kind anywhere
}

double SolidSegmentWalker::solidFraction(const glm::ivec3& from, const glm::ivec3& to) const noexcept {
  const std::uint8_t* solid = voxels_->solid.data();
  Walk walk(*voxels_, from, to);
  for (;;) {
    const int radius = reach_[static_cast<std::size_t>(walk.cell)] - 1;
    if (!(radius >= kMinimumJump ? walk.jump(solid, radius) : walk.advance(solid))) break;
  }
  return walk.fraction();
}

}  // namespace mane::render
