#pragma once
// The cloth tests' square grid: n × n vertices of side `size` metres in the XY plane, row 0 at
// the top (y = 0) and the rest hanging below it, two counter-clockwise triangles per cell.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace mane::testing {

struct ClothGrid {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> triangles;
};

inline ClothGrid makeClothGrid(int n, float size) {
  ClothGrid grid;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      grid.positions.push_back({size * float(i) / float(n - 1), -size * float(j) / float(n - 1), 0.0f});
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const auto a = static_cast<std::uint32_t>(j * n + i), b = a + 1, c = a + static_cast<std::uint32_t>(n),
                 d = c + 1;
      grid.triangles.insert(grid.triangles.end(), {a, c, b, b, c, d});
    }
  return grid;
}

}  // namespace mane::testing
