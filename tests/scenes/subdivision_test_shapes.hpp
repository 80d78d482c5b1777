#pragma once
// Shapes and checks shared by the subdivision tests of scenes/ and subdiv/: a quad cage of the
// sphere as OBJ text, and the count of edges a closed triangle mesh must not have.

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>

#include "render/frame.hpp"

namespace mane::scenes::testing {

/// A latitude-longitude quad cage of the unit sphere as OBJ text: `segments` quads around each
/// of `rings` − 2 bands, closed by triangle fans around the poles, counter-clockwise from outside.
inline std::string quadSphereObj(int segments, int rings) {
  std::string obj = "v 0 -1 0\n";
  for (int r = 1; r < rings; ++r) {
    const double latitude = -M_PI / 2 + M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double longitude = 2.0 * M_PI * s / segments;
      obj += "v " + std::to_string(std::cos(latitude) * std::sin(longitude)) + " " +
             std::to_string(std::sin(latitude)) + " " + std::to_string(std::cos(latitude) * std::cos(longitude)) + "\n";
    }
  }
  obj += "v 0 1 0\n";
  const int north = 2 + (rings - 1) * segments;  // OBJ numbers from 1
  const auto at = [&](int ring, int s) { return std::to_string(2 + (ring - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    obj += "f 1 " + at(1, s + 1) + " " + at(1, s) + "\n";
    for (int r = 1; r + 1 < rings; ++r)
      obj += "f " + at(r, s) + " " + at(r, s + 1) + " " + at(r + 1, s + 1) + " " + at(r + 1, s) + "\n";
    obj += "f " + std::to_string(north) + " " + at(rings - 1, s) + " " + at(rings - 1, s + 1) + "\n";
  }
  return obj;
}

/// Directed edges whose reverse no triangle has, comparing corners by position (UV seams split
/// vertices, not the surface): 0 for a closed, consistently wound mesh without T-junctions.
/// Any mesh with `positions` and `indices`: render::MeshData, scenes::Mesh.
template <typename TriangleMesh>
std::size_t unmatchedEdges(const TriangleMesh& mesh) {
  using Point = std::tuple<float, float, float>;
  const auto at = [&](std::uint32_t v) {
    const auto& p = mesh.positions[v];
    return Point{p.x, p.y, p.z};
  };
  std::map<std::pair<Point, Point>, int> edges;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++edges[{at(mesh.indices[t + k]), at(mesh.indices[t + (k + 1) % 3])}];
  std::size_t unmatched = 0;
  for (const auto& [edge, count] : edges) {
    const auto reverse = edges.find({edge.second, edge.first});
    unmatched += (reverse == edges.end() || reverse->second != count) ? 1 : 0;
  }
  return unmatched;
}

}  // namespace mane::scenes::testing
