#include "tests/render/voxel_test_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace mane::render::test {

namespace {

// Appends triangle (a, b, c), reversed if its normal does not point along `outward`: each
// generator states which way is out at a triangle and lets this pick the winding.
void addTriangle(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, const glm::vec3& outward) {
  const glm::vec3& pa = mesh.positions[a];
  const glm::vec3 normal = glm::cross(mesh.positions[b] - pa, mesh.positions[c] - pa);
  if (glm::dot(normal, outward) < 0.0f) std::swap(b, c);
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

glm::vec3 centroid(const TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  return (mesh.positions[a] + mesh.positions[b] + mesh.positions[c]) / 3.0f;
}

}  // namespace

TriangleMesh box(const glm::vec3& lo, const glm::vec3& hi) {
  TriangleMesh mesh;
  for (std::uint32_t corner = 0; corner < 8; ++corner) {
    mesh.positions.emplace_back(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
  }
  // Each face: the corners with bit `axis` equal to `side`, as a cycle around the face.
  for (int axis = 0; axis < 3; ++axis) {
    for (std::uint32_t side = 0; side < 2; ++side) {
      const std::uint32_t bit = 1u << axis, u = 1u << ((axis + 1) % 3), v = 1u << ((axis + 2) % 3);
      const std::uint32_t base = side ? bit : 0;
      const std::uint32_t q[4] = {base, base | u, base | u | v, base | v};
      glm::vec3 out(0.0f);
      out[axis] = side ? 1.0f : -1.0f;
      addTriangle(mesh, q[0], q[1], q[2], out);
      addTriangle(mesh, q[0], q[2], q[3], out);
    }
  }
  return mesh;
}

TriangleMesh sphere(const glm::vec3& centre, float radius, int rings, int segments, bool inward) {
  TriangleMesh mesh;
  const double pi = std::numbers::pi;
  mesh.positions.push_back(centre + glm::vec3(0.0f, 0.0f, radius));
  for (int r = 1; r < rings; ++r) {
    const double polar = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * pi * s / segments;
      mesh.positions.push_back(centre + radius * glm::vec3(std::sin(polar) * std::cos(azimuth),
                                                           std::sin(polar) * std::sin(azimuth), std::cos(polar)));
    }
  }
  mesh.positions.push_back(centre - glm::vec3(0.0f, 0.0f, radius));
  const auto ring = [&](int r, int s) { return static_cast<std::uint32_t>(1 + (r - 1) * segments + s % segments); };
  const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
  const float sense = inward ? -1.0f : 1.0f;
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    addTriangle(mesh, a, b, c, sense * (centroid(mesh, a, b, c) - centre));
  };
  for (int s = 0; s < segments; ++s) {
    add(0, ring(1, s), ring(1, s + 1));
    add(south, ring(rings - 1, s), ring(rings - 1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      add(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      add(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  }
  return mesh;
}

TriangleMesh torus(float major, float minor, int majorSegments, int minorSegments) {
  TriangleMesh mesh;
  const double pi = std::numbers::pi;
  for (int i = 0; i < majorSegments; ++i) {
    const double theta = 2.0 * pi * i / majorSegments;
    for (int j = 0; j < minorSegments; ++j) {
      const double phi = 2.0 * pi * j / minorSegments;
      const double ring = major + minor * std::cos(phi);
      mesh.positions.emplace_back(ring * std::cos(theta), ring * std::sin(theta), minor * std::sin(phi));
    }
  }
  const auto at = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % majorSegments) * minorSegments + j % minorSegments);
  };
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const glm::vec3 p = centroid(mesh, a, b, c);
    const glm::vec3 core = major * glm::normalize(glm::vec3(p.x, p.y, 0.0f));  // nearest tube centre
    addTriangle(mesh, a, b, c, p - core);
  };
  for (int i = 0; i < majorSegments; ++i) {
    for (int j = 0; j < minorSegments; ++j) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return mesh;
}

TriangleMesh octahedron(const glm::vec3& centre, float radius) {
  TriangleMesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {-1.0f, 1.0f}) {
      glm::vec3 p = centre;
      p[axis] += side * radius;
      mesh.positions.push_back(p);
    }
  }
  // Vertex 2·axis + (side > 0); one face per octant.
  for (std::uint32_t x = 0; x < 2; ++x) {
    for (std::uint32_t y = 2; y < 4; ++y) {
      for (std::uint32_t z = 4; z < 6; ++z) addTriangle(mesh, x, y, z, centroid(mesh, x, y, z) - centre);
    }
  }
  return mesh;
}

TriangleMesh transformed(TriangleMesh mesh, const glm::mat3& rotation, const glm::vec3& offset) {
  for (glm::vec3& p : mesh.positions) p = rotation * p + offset;
  return mesh;
}

TriangleMesh combined(TriangleMesh a, const TriangleMesh& b) {
  const auto base = static_cast<std::uint32_t>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (const std::uint32_t i : b.indices) a.indices.push_back(base + i);
  return a;
}

double boxChord(const glm::dvec3& p, const glm::dvec3& q, const glm::dmat3& rotation, const glm::dvec3& centre,
                const glm::dvec3& half) {
  const glm::dvec3 a = glm::transpose(rotation) * (p - centre), d = glm::transpose(rotation) * (q - p);
  double t0 = 0.0, t1 = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (d[axis] == 0.0) {
      if (std::abs(a[axis]) > half[axis]) return 0.0;
      continue;
    }
    double enter = (-half[axis] - a[axis]) / d[axis], leave = (half[axis] - a[axis]) / d[axis];
    if (enter > leave) std::swap(enter, leave);
    t0 = std::max(t0, enter);
    t1 = std::min(t1, leave);
  }
  return t1 > t0 ? (t1 - t0) * glm::length(q - p) : 0.0;
}

double boxDepth(const glm::dvec3& p, const glm::dmat3& rotation, const glm::dvec3& centre, const glm::dvec3& half) {
  const glm::dvec3 a = glm::transpose(rotation) * (p - centre);
  return std::min({half.x - std::abs(a.x), half.y - std::abs(a.y), half.z - std::abs(a.z)});
}

double ballChord(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& c, double r) {
  const glm::dvec3 d = q - p, f = p - c;
  const double a = glm::dot(d, d), b = glm::dot(f, d), k = glm::dot(f, f) - r * r;
  const double discriminant = b * b - a * k;
  if (discriminant <= 0.0) return 0.0;
  const double root = std::sqrt(discriminant);
  const double t0 = std::max(0.0, (-b - root) / a), t1 = std::min(1.0, (-b + root) / a);
  return t1 > t0 ? (t1 - t0) * std::sqrt(a) : 0.0;
}

double torusInside(const glm::dvec3& p, const glm::dvec3& q, double major, double minor) {
  const auto inside = [&](double t) {
    const glm::dvec3 x = p + t * (q - p);
    const double ring = std::sqrt(x.x * x.x + x.y * x.y) - major;
    return ring * ring + x.z * x.z < minor * minor;
  };
  constexpr int kSteps = 4000;
  double length = 0.0, t = 0.0, enteredAt = 0.0;
  bool in = inside(0.0);
  for (int s = 1; s <= kSteps; ++s) {
    const double tNext = static_cast<double>(s) / kSteps;
    if (inside(tNext) != in) {
      double lo = t, hi = tNext;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (inside(mid) == in ? lo : hi) = mid;
      }
      if (in) length += hi - enteredAt;
      enteredAt = hi;
      in = !in;
    }
    t = tNext;
  }
  if (in) length += 1.0 - enteredAt;
  return length * glm::length(q - p);
}

}  // namespace mane::render::test
