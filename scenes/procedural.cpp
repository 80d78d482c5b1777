#include "scenes/procedural.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace mane::scenes {
namespace {

/// (cos, sin) of turn·k/steps for k = 0..steps, computed in double.
std::vector<glm::vec2> stepsAround(int steps, double turn) {
  std::vector<glm::vec2> angles;
  for (int k = 0; k <= steps; ++k) {
    const double angle = turn * static_cast<double>(k) / static_cast<double>(steps);
    angles.emplace_back(static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle)));
  }
  return angles;
}

// The ends are set exactly: in float, sin(2π) is 1.7e-7 and sin(π) −8.7e-8, which would leave a
// duplicated seam column or a pole copy a hair away from its twin and the mesh open by position.

/// `stepsAround` a full turn, the last entry a bitwise copy of the first (a closed seam).
std::vector<glm::vec2> fullTurn(int steps) {
  std::vector<glm::vec2> angles = stepsAround(steps, 2.0 * std::numbers::pi);
  angles.front() = {1.0f, 0.0f};
  angles.back() = angles.front();
  return angles;
}

/// `stepsAround` a half turn, from exactly (1, 0) to exactly (−1, 0) (the poles).
std::vector<glm::vec2> halfTurn(int steps) {
  std::vector<glm::vec2> angles = stepsAround(steps, std::numbers::pi);
  angles.front() = {1.0f, 0.0f};
  angles.back() = {-1.0f, 0.0f};
  return angles;
}

/// Index of vertex (row, column) in a grid of rows with `columns` vertices each.
std::uint32_t gridIndex(int row, int column, int columns) {
  return static_cast<std::uint32_t>(row * columns + column);
}

/// The same surface seen from the other side: normals negated, every triangle's winding reversed.
Mesh turnedInsideOut(Mesh mesh) {
  for (glm::vec3& normal : mesh.normals) normal = -normal;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  return mesh;
}

/// Appends `part`'s vertices and triangles to `mesh` (both with normals and UVs).
void append(Mesh& mesh, const Mesh& part) {
  const auto offset = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
  mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
  mesh.uvs.insert(mesh.uvs.end(), part.uvs.begin(), part.uvs.end());
  for (std::uint32_t index : part.indices) mesh.indices.push_back(offset + index);
}

/// The cube [−halfSide, halfSide]³: 4 vertices per face (flat normals), 2 triangles each.
Mesh makeCube(float halfSide) {
  Mesh cube;
  for (int axis = 0; axis < 3; ++axis) {
    for (const float sign : {1.0f, -1.0f}) {
      glm::vec3 normal(0.0f);
      normal[axis] = sign;
      // Tangents with u × v = normal, so (−−, +−, ++) turns counter-clockwise seen from outside.
      glm::vec3 u(0.0f);
      glm::vec3 v(0.0f);
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = 1.0f;
      if (sign < 0.0f) std::swap(u, v);
      const auto first = static_cast<std::uint32_t>(cube.positions.size());
      for (const glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        cube.positions.push_back(halfSide * (normal + corner.x * u + corner.y * v));
        cube.normals.push_back(normal);
        cube.uvs.emplace_back(0.5f * (corner.x + 1.0f), 0.5f * (1.0f - corner.y));  // v down
      }
      cube.indices.insert(cube.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    }
  }
  return cube;
}

}  // namespace

Mesh makeSphere(int rings, int segments, float radius) {
  rings = std::max(rings, 2);
  segments = std::max(segments, 3);
  Mesh mesh;
  mesh.name = "procedural:sphere";
  const std::vector<glm::vec2> polar = halfTurn(rings);       // 0 at +Y
  const std::vector<glm::vec2> azimuth = fullTurn(segments);  // 0 at +Z
  const int columns = segments + 1;
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s <= segments; ++s) {
      const float sinPolar = polar[r].y;
      const glm::vec3 n(sinPolar * azimuth[s].y, polar[r].x, sinPolar * azimuth[s].x);
      mesh.positions.push_back(n * radius);
      mesh.normals.push_back(n);
      mesh.uvs.emplace_back(static_cast<float>(s) / static_cast<float>(segments),
                            static_cast<float>(r) / static_cast<float>(rings));
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = gridIndex(r, s, columns);
      const std::uint32_t b = gridIndex(r + 1, s, columns);  // one ring further south
      // The pole rows collapse to a point: emit only the triangle with area.
      if (r != 0) mesh.indices.insert(mesh.indices.end(), {a, b, a + 1});
      if (r != rings - 1) mesh.indices.insert(mesh.indices.end(), {a + 1, b, b + 1});
    }
  }
  return mesh;
}

Mesh makeCubeWithHollow(float halfSide, float hollowRadius, int hollowRings, int hollowSegments) {
  Mesh mesh = makeCube(halfSide);
  append(mesh, turnedInsideOut(makeSphere(hollowRings, hollowSegments, hollowRadius)));
  mesh.name = "procedural:cube_with_hollow";
  return mesh;
}

Mesh makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments) {
  majorSegments = std::max(majorSegments, 3);
  minorSegments = std::max(minorSegments, 3);
  Mesh mesh;
  mesh.name = "procedural:torus";
  const std::vector<glm::vec2> around = fullTurn(majorSegments);  // φ, 0 at +X
  const std::vector<glm::vec2> tube = fullTurn(minorSegments);    // θ, 0 outermost
  const int columns = minorSegments + 1;
  for (int i = 0; i <= majorSegments; ++i) {
    const glm::vec3 radial(around[i].x, 0.0f, around[i].y);
    for (int j = 0; j <= minorSegments; ++j) {
      const glm::vec3 n = tube[j].x * radial + glm::vec3(0.0f, tube[j].y, 0.0f);
      mesh.positions.push_back(majorRadius * radial + minorRadius * n);
      mesh.normals.push_back(n);
      mesh.uvs.emplace_back(static_cast<float>(i) / static_cast<float>(majorSegments),
                            static_cast<float>(j) / static_cast<float>(minorSegments));
    }
  }
  // ∂P/∂θ × ∂P/∂φ points away from the tube, so (a, a + θ, a + θ + φ) winds counter-clockwise
  // seen from outside.
  for (int i = 0; i < majorSegments; ++i) {
    for (int j = 0; j < minorSegments; ++j) {
      const std::uint32_t a = gridIndex(i, j, columns);
      const std::uint32_t b = gridIndex(i + 1, j, columns);  // one step further around the axis
      mesh.indices.insert(mesh.indices.end(), {a, a + 1, b + 1, a, b + 1, b});
    }
  }
  return mesh;
}

Mesh makePlane(float halfSide) {
  Mesh mesh;
  mesh.name = "plane";
  const float h = halfSide;
  mesh.positions = {{-h, 0.0f, -h}, {-h, 0.0f, h}, {h, 0.0f, h}, {h, 0.0f, -h}};
  mesh.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
  mesh.uvs = {{0.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

Mesh makeHull(int stations, int sectionPoints) {
  Mesh mesh;
  mesh.name = "hull";
  const float pi = std::numbers::pi_v<float>;
  // Along the length t in [−1, 1] (stern to bow): the half beam, fuller aft than forward; the
  // keel's depth; the deck's height (its sheer).
  const auto halfBeam = [](float t) {
    const float fullness = t < 0.0f ? t * t * t * t : t * t;
    return 0.14f * std::sqrt(std::max(0.0f, 1.0f - fullness));
  };
  const auto keel = [](float t) { return 0.1f * (1.0f - 0.4f * t * t); };
  const auto deck = [](float t) { return 0.06f + 0.03f * t * t; };
  const auto point = [&](int station, int p) {
    const float t = -1.0f + 2.0f * float(station) / float(stations - 1);
    const float phi = -0.5f * pi + pi * float(p) / float(sectionPoints - 1);
    const float depth = deck(t) + keel(t);
    // sin φ across, and a U whose sides stand nearly upright: cos φ to the power 0.6.
    const float down = std::pow(std::max(0.0f, std::cos(phi)), 0.6f);
    return glm::vec3(0.5f * t, deck(t) - depth * down, halfBeam(t) * std::sin(phi));
  };
  for (int station = 0; station < stations; ++station)
    for (int p = 0; p < sectionPoints; ++p) {
      mesh.positions.push_back(point(station, p));
      mesh.uvs.emplace_back(float(station) / float(stations - 1), float(p) / float(sectionPoints - 1));
    }
  for (int station = 0; station + 1 < stations; ++station)
    for (int p = 0; p + 1 < sectionPoints; ++p) {
      const auto a = std::uint32_t(station * sectionPoints + p);
      const auto b = a + std::uint32_t(sectionPoints);
      // Counter-clockwise seen from outside: port (z < 0) to starboard runs under the keel.
      mesh.indices.insert(mesh.indices.end(), {a, b + 1, a + 1, a, b, b + 1});
    }
  computeSmoothNormals(mesh);
  // The deck: the sections' first and last points, again, facing up.
  const auto deckStart = std::uint32_t(mesh.positions.size());
  for (int station = 0; station < stations; ++station)
    for (int side : {0, sectionPoints - 1}) {
      const glm::vec3 p = point(station, side);
      mesh.positions.push_back(p);
      mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
      mesh.uvs.emplace_back(p.x + 0.5f, p.z / 0.28f + 0.5f);
    }
  for (int station = 0; station + 1 < stations; ++station) {
    const std::uint32_t port = deckStart + std::uint32_t(2 * station);
    const std::uint32_t starboard = port + 1;
    mesh.indices.insert(mesh.indices.end(), {port, starboard + 2, port + 2, port, starboard, starboard + 2});
  }
  return mesh;
}

Mesh makeSpar(float radius, int segments) {
  Mesh mesh;
  mesh.name = "spar";
  const float pi = std::numbers::pi_v<float>;
  for (int i = 0; i <= segments; ++i) {
    const float angle = 2.0f * pi * float(i) / float(segments);
    const glm::vec3 out(std::cos(angle), 0.0f, std::sin(angle));
    for (float y : {0.0f, 1.0f}) {
      mesh.positions.push_back(out * radius + glm::vec3(0.0f, y, 0.0f));
      mesh.normals.push_back(out);
      mesh.uvs.emplace_back(float(i) / float(segments), 1.0f - y);
    }
  }
  for (int i = 0; i < segments; ++i) {
    const auto a = std::uint32_t(2 * i);
    // Counter-clockwise seen from outside.
    mesh.indices.insert(mesh.indices.end(), {a, a + 1, a + 3, a, a + 3, a + 2});
  }
  for (float y : {0.0f, 1.0f}) {
    const auto centre = std::uint32_t(mesh.positions.size());
    const glm::vec3 normal(0.0f, y > 0.0f ? 1.0f : -1.0f, 0.0f);
    mesh.positions.emplace_back(0.0f, y, 0.0f);
    mesh.normals.push_back(normal);
    mesh.uvs.emplace_back(0.5f, 0.5f);
    for (int i = 0; i < segments; ++i) {
      const float angle = 2.0f * pi * float(i) / float(segments);
      mesh.positions.emplace_back(radius * std::cos(angle), y, radius * std::sin(angle));
      mesh.normals.push_back(normal);
      mesh.uvs.emplace_back(0.5f + 0.5f * std::cos(angle), 0.5f + 0.5f * std::sin(angle));
    }
    for (int i = 0; i < segments; ++i) {
      const std::uint32_t a = centre + 1 + std::uint32_t(i), b = centre + 1 + std::uint32_t((i + 1) % segments);
      if (y > 0.0f)
        mesh.indices.insert(mesh.indices.end(), {centre, b, a});
      else
        mesh.indices.insert(mesh.indices.end(), {centre, a, b});
    }
  }
  return mesh;
}

}  // namespace mane::scenes
