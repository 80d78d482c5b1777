#include "scenes/limit_scalp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "physics/split_mix64.hpp"

namespace mane::scenes {
namespace {

// Cells of the starting grid over the whole surface: enough that a cell's area bound is tight
// (few rejections), few enough that the grid's limit evaluations cost little next to the
// tessellation.
constexpr double kTargetCells = 65536.0;
constexpr int kMaxCellsPerSide = 8;
// The area bound of a cell is its largest corner Jacobian times this: the Jacobian varies
// smoothly, little across a cell of a fine grid.
constexpr double kJacobianMargin = 1.5;
// Tries per root before the region is declared too thin to hit.
constexpr int kMaxTriesPerRoot = 10000;

struct Cell {
  std::uint32_t face = 0;
  int i = 0, j = 0;
  double jacobianBound = 0.0;  ///< ≥ |∂u × ∂v| in the cell (model units² per unit parameter²)
};

bool inRegion(const ScalpRegion& region, float lowest, const glm::vec3& position, const glm::vec3& normal) {
  return normal.y >= region.minUp && normal.z <= region.maxForward && position.y >= lowest;
}

// A uniform double in [0, 1) from the top 53 bits.
double uniform(physics::SplitMix64& rng) {
  return static_cast<double>(rng.next() >> 11) * 0x1.0p-53;
}

}  // namespace

Result<std::vector<LimitRoot>> sampleScalpOnLimitSurface(const subdiv::LimitSurface& surface, const ScalpRegion& region,
                                                         std::size_t count, std::uint64_t seed) {
  const std::uint32_t faces = surface.ptexFaceCount();
  if (faces == 0) return fail("scalp on the limit surface: the surface has no faces");
  const int side = std::clamp(static_cast<int>(std::lround(std::sqrt(kTargetCells / faces))), 1, kMaxCellsPerSide);
  const int nodes = side + 1;
  const double step = 1.0 / side;

  // The grid's nodes: position, normal and Jacobian |∂u × ∂v|.
  struct Node {
    glm::vec3 position;
    glm::vec3 normal;
    double jacobian;
  };
  std::vector<Node> grid(std::size_t(faces) * nodes * nodes);
  float top = std::numeric_limits<float>::lowest(), bottom = std::numeric_limits<float>::max();
  for (std::uint32_t f = 0; f < faces; ++f)
    for (int j = 0; j < nodes; ++j)
      for (int i = 0; i < nodes; ++i) {
        const subdiv::LimitSample s = surface.evaluate(f, i * step, j * step);
        grid[(std::size_t(f) * nodes + j) * nodes + i] = {s.position, s.normal,
                                                          glm::length(glm::cross(glm::dvec3(s.du), glm::dvec3(s.dv)))};
        top = std::max(top, s.position.y);
        bottom = std::min(bottom, s.position.y);
      }
  const float lowest = top - region.topFraction * (top - bottom);

  // Candidate cells (a corner in the region), weighted by their area bound.
  std::vector<Cell> cells;
  std::vector<double> cumulative;
  double total = 0.0;
  for (std::uint32_t f = 0; f < faces; ++f)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        bool candidate = false;
        double largest = 0.0;
        for (const auto [di, dj] : std::array<std::array<int, 2>, 4>{{{0, 0}, {1, 0}, {0, 1}, {1, 1}}}) {
          const Node& node = grid[(std::size_t(f) * nodes + j + dj) * nodes + i + di];
          candidate = candidate || inRegion(region, lowest, node.position, node.normal);
          largest = std::max(largest, node.jacobian);
        }
        if (!candidate || !(largest > 0.0)) continue;
        cells.push_back({f, i, j, largest * kJacobianMargin});
        total += cells.back().jacobianBound * step * step;
        cumulative.push_back(total);
      }
  if (cells.empty())
    return fail("scalp on the limit surface: no point of the surface is in the scalp region (top " +
                std::to_string(region.topFraction) + " of its height, normal y >= " + std::to_string(region.minUp) +
                ", z <= " + std::to_string(region.maxForward) + ")");

  physics::SplitMix64 rng(seed);
  std::vector<LimitRoot> roots;
  roots.reserve(count);
  while (roots.size() < count) {
    bool placed = false;
    for (int attempt = 0; attempt < kMaxTriesPerRoot && !placed; ++attempt) {
      const double pick = uniform(rng) * total;
      const std::size_t k =
          std::min(std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()),
                   cells.size() - 1);
      const Cell& cell = cells[k];
      // One draw per statement: C++ leaves the order of a call's arguments open, and compilers
      // differ. v is drawn before u, the order the shipped scenes' grooms were made with.
      const double v = uniform(rng);
      const double u = uniform(rng);
      const glm::dvec2 uv((cell.i + u) * step, (cell.j + v) * step);
      const double keep = uniform(rng);
      const subdiv::LimitSample s = surface.evaluate(cell.face, uv.x, uv.y);
      const double jacobian = glm::length(glm::cross(glm::dvec3(s.du), glm::dvec3(s.dv)));
      if (keep * cell.jacobianBound >= jacobian || !inRegion(region, lowest, s.position, s.normal)) continue;
      // A denser hairline: kept in proportion to the density there.
      if (region.hairlineDensity > 1.0f && uniform(rng) * region.hairlineDensity >= region.densityAt(s.normal))
        continue;
      roots.push_back({cell.face, uv, s.position, s.normal});
      placed = true;
    }
    if (!placed)
      return fail("scalp on the limit surface: the scalp region is too thin: " + std::to_string(kMaxTriesPerRoot) +
                  " points in a row fell outside it (or were thinned out by the hairline's density)");
  }
  return roots;
}

}  // namespace mane::scenes
