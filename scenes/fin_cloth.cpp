#include "scenes/fin_cloth.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace mane::scenes {

FinCloth makeFin(const FinShape& shape) {
  FinCloth fin;
  fin.mesh.name = "procedural:fin";
  const int gaps = shape.rays - 1;
  const int columns = gaps * kFinColumnsPerGap + 1;
  fin.columns = columns;
  const double spread = glm::radians(static_cast<double>(shape.spreadDegrees));
  // Where the vertex would lie were the membrane flat: on its column's line from the root, cut
  // back between the rays by sin(π·t) of the gap, t the share of the way from one ray to the next.
  auto flatPoint = [&](int row, int column) {
    const double across = double(column) / double(columns - 1);
    const double t = double(column % kFinColumnsPerGap) / double(kFinColumnsPerGap);
    const double angle = spread * (across - 0.5);
    const double rayLength = double(shape.length) * (1.0 - (1.0 - double(shape.taper)) * across);
    const double reach = rayLength * (1.0 - double(shape.scallop) * std::sin(std::numbers::pi * t));
    const double along = reach * double(row) / double(shape.rows - 1);
    return glm::dvec3(double(shape.root) * (across - 0.5) + along * std::sin(angle), -along * std::cos(angle), 0.0);
  };
  for (int row = 0; row < shape.rows; ++row)
    for (int column = 0; column < columns; ++column) {
      // Each ray stands out of the membrane by `pleat` of the gap beside it, alternately on the
      // +z and −z side: the membrane folds along the rays, and their ridges catch the light.
      const int gap = std::min(column / kFinColumnsPerGap, gaps - 1);
      const double width =
          glm::distance(flatPoint(row, gap * kFinColumnsPerGap), flatPoint(row, (gap + 1) * kFinColumnsPerGap));
      glm::dvec3 point = flatPoint(row, column);
      if (column % kFinColumnsPerGap == 0)
        point.z = double(shape.pleat) * width * ((column / kFinColumnsPerGap) % 2 == 0 ? 1.0 : -1.0);
      fin.mesh.positions.emplace_back(point);
      fin.mesh.uvs.emplace_back(float(column) / float(columns - 1), float(row) / float(shape.rows - 1));
    }
  for (int row = 0; row + 1 < shape.rows; ++row)
    for (int column = 0; column + 1 < columns; ++column) {
      const auto a = static_cast<std::uint32_t>(row * columns + column), b = a + 1;
      const auto c = a + static_cast<std::uint32_t>(columns), d = c + 1;
      // Counter-clockwise seen from +z, the diagonals alternating so that it bends alike both ways.
      if ((row + column) % 2 == 0)
        fin.mesh.indices.insert(fin.mesh.indices.end(), {a, c, b, b, c, d});
      else
        fin.mesh.indices.insert(fin.mesh.indices.end(), {a, c, d, a, d, b});
    }
  computeSmoothNormals(fin.mesh);
  for (std::uint32_t v = 0; v < static_cast<std::uint32_t>(2 * columns); ++v) fin.base.push_back(v);
  for (int row = 2; row < shape.rows; ++row)
    for (int ray = 0; ray < shape.rays; ++ray) {
      const float alongRay = float(row - 1) / float(shape.rows - 2);
      fin.holds.push_back({static_cast<std::uint32_t>(row * columns + ray * kFinColumnsPerGap),
                           shape.rayStiffness * (1.0f - 0.5f * alongRay)});
    }
  return fin;
}

}  // namespace mane::scenes
