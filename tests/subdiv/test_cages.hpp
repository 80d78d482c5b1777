#pragma once
// Procedural cages shared by the subdivision tests, each chosen for a known limit surface.

#include <cmath>
#include <cstdint>
#include <numbers>

#include <glm/geometric.hpp>

#include "subdiv/cage.hpp"

namespace mane::subdiv::testing {

/// The OpenSubdiv regression cube (corners ±1), faces counter-clockwise from outside.
inline Cage unitCube() {
  Cage cage;
  cage.positions = {{-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, -1}, {1, -1, -1}};
  cage.faceSizes = {4, 4, 4, 4, 4, 4};
  cage.faceVertices = {0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4};
  return cage;
}

/// A (cells × cells) open quad grid in the xy plane with unit spacing and heights z(x, y):
/// vertex (row r, column c) is r·(cells+1)+c at (c, r, z); face (r, c) is r·cells+c with
/// corners (r,c), (r,c+1), (r+1,c+1), (r+1,c), so u runs along x and v along y.
template <class Height>
Cage heightGrid(int cells, Height height) {
  Cage cage;
  for (int r = 0; r <= cells; ++r)
    for (int c = 0; c <= cells; ++c) cage.positions.emplace_back(float(c), float(r), height(r, c));
  const auto vertex = [&](int r, int c) { return std::uint32_t(r * (cells + 1) + c); };
  for (int r = 0; r < cells; ++r)
    for (int c = 0; c < cells; ++c) {
      cage.faceSizes.push_back(4);
      cage.faceVertices.insert(cage.faceVertices.end(),
                               {vertex(r, c), vertex(r, c + 1), vertex(r + 1, c + 1), vertex(r + 1, c)});
    }
  return cage;
}

/// A latitude-longitude sphere of `radius` about the origin: `segments` quads around each of
/// `rings` − 2 bands, closed at each pole by a fan of triangles around a pole vertex (an
/// extraordinary vertex of valence `segments`). Ring r (0 at the south pole's band) spans
/// latitudes −π/2 + π·r/rings to −π/2 + π·(r+1)/rings; quad (ring r, segment s) is face
/// segments·r + s for r in 1..rings−2 (faces of ring 0 and rings−1 are the fans, numbered
/// the same way). u runs eastwards, v northwards: normals point outwards.
inline Cage uvSphere(int segments, int rings, float radius) {
  Cage cage;
  // Vertex 0: south pole; then rings−1 latitude circles of `segments`; last: north pole.
  cage.positions.emplace_back(0.0f, 0.0f, -radius);
  for (int r = 1; r < rings; ++r) {
    const double latitude = -std::numbers::pi / 2 + std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double longitude = 2.0 * std::numbers::pi * s / segments;
      cage.positions.emplace_back(radius * std::cos(latitude) * std::cos(longitude),
                                  radius * std::cos(latitude) * std::sin(longitude), radius * std::sin(latitude));
    }
  }
  cage.positions.emplace_back(0.0f, 0.0f, radius);
  const auto north = std::uint32_t(cage.positions.size() - 1);
  const auto onCircle = [&](int circle, int s) { return std::uint32_t(1 + (circle - 1) * segments + (s % segments)); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      if (r == 0) {
        cage.faceSizes.push_back(3);
        // The band's quad with its southern side collapsed into the pole.
        cage.faceVertices.insert(cage.faceVertices.end(), {0u, onCircle(1, s + 1), onCircle(1, s)});
      } else if (r == rings - 1) {
        cage.faceSizes.push_back(3);
        cage.faceVertices.insert(cage.faceVertices.end(), {onCircle(r, s), onCircle(r, s + 1), north});
      } else {
        cage.faceSizes.push_back(4);
        cage.faceVertices.insert(cage.faceVertices.end(),
                                 {onCircle(r, s), onCircle(r, s + 1), onCircle(r + 1, s + 1), onCircle(r + 1, s)});
      }
    }
  return cage;
}

/// An open tube of `segments` quads around the z axis and `rings` quads along it (spacing
/// `step`), vertices on the circle of `radius`; u runs around (counter-clockwise seen from
/// +z), v along +z, so normals point outwards. Face (ring r, segment s) is r·segments+s.
inline Cage openCylinder(int segments, int rings, float radius, float step) {
  Cage cage;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double angle = 2.0 * std::numbers::pi * s / segments;
      cage.positions.emplace_back(radius * std::cos(angle), radius * std::sin(angle), step * r);
    }
  const auto vertex = [&](int r, int s) { return std::uint32_t(r * segments + (s % segments)); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      cage.faceSizes.push_back(4);
      cage.faceVertices.insert(cage.faceVertices.end(),
                               {vertex(r, s), vertex(r, s + 1), vertex(r + 1, s + 1), vertex(r + 1, s)});
    }
  return cage;
}

}  // namespace mane::subdiv::testing
