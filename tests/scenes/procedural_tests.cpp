// The procedural sphere against geometry: radius, normals, closure, outward winding, area;
// and smooth normals against the sphere's exact ones.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include <glm/geometric.hpp>

#include "scenes/procedural.hpp"

namespace mane::scenes {
namespace {

TEST(ProceduralSphere, CountsFollowTheDocumentedFormula) {
  const Mesh sphere = makeSphere(8, 12, 2.0f);
  EXPECT_EQ(sphere.vertexCount(), 9u * 13u);
  EXPECT_EQ(sphere.triangleCount(), 2u * 12u * (8u - 1u));
  EXPECT_EQ(validate(sphere), "");
  EXPECT_EQ(sphere.uvs.size(), sphere.vertexCount());
}

TEST(ProceduralSphere, PointsLieOnTheSphereWithRadialNormals) {
  const float radius = 0.37f;
  const Mesh sphere = makeSphere(16, 24, radius);
  for (std::size_t i = 0; i < sphere.vertexCount(); ++i) {
    EXPECT_NEAR(glm::length(sphere.positions[i]), radius, 1e-6f);
    EXPECT_NEAR(glm::distance(sphere.normals[i], sphere.positions[i] / radius), 0.0f, 1e-5f);
  }
  const Bounds box = sphere.bounds();
  EXPECT_NEAR(box.max.y, radius, 1e-6f);  // poles on ±Y
  EXPECT_NEAR(box.min.y, -radius, 1e-6f);
}

TEST(ProceduralSphere, IsClosedAndWindsOutward) {
  const Mesh sphere = makeSphere(12, 20, 1.0f);
  // Weld by position (the seam and poles repeat positions), then every edge must be shared
  // by exactly two triangles, in opposite directions.
  std::map<std::tuple<float, float, float>, int> weld;
  std::vector<int> id(sphere.vertexCount());
  for (std::size_t i = 0; i < id.size(); ++i) {
    const glm::vec3 p = glm::round(sphere.positions[i] * 1e5f);
    id[i] = weld.try_emplace({p.x, p.y, p.z}, static_cast<int>(weld.size())).first->second;
  }
  std::map<std::pair<int, int>, int> directed;
  double area = 0.0;
  for (std::size_t t = 0; t < sphere.indices.size(); t += 3) {
    const glm::vec3& a = sphere.positions[sphere.indices[t]];
    const glm::vec3& b = sphere.positions[sphere.indices[t + 1]];
    const glm::vec3& c = sphere.positions[sphere.indices[t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    EXPECT_GT(glm::dot(n, a + b + c), 0.0f) << "triangle " << t / 3 << " faces inward";
    area += 0.5 * glm::length(n);
    for (int e = 0; e < 3; ++e) {
      ++directed[{id[sphere.indices[t + e]], id[sphere.indices[t + (e + 1) % 3]]}];
    }
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "open edge";
  }
  // The inscribed polyhedron's area is below 4π and converges to it; at 12×20 it is within
  // 4% (the error falls as the square of the angular step).
  EXPECT_LT(area, 4.0 * std::numbers::pi);
  EXPECT_GT(area, 0.96 * 4.0 * std::numbers::pi);
}

TEST(SmoothNormals, ApproachTheSphereNormals) {
  Mesh sphere = makeSphere(32, 64, 1.0f);
  const std::vector<glm::vec3> exact = sphere.normals;
  computeSmoothNormals(sphere);
  // Pole vertices are separate copies that each see one triangle, whose normal leans by
  // about half the polar step (180°/32 / 2 ≈ 2.8°, distance 0.049); 0.07 (4°) bounds it.
  // One pole copy per column goes unused (see makeSphere); it keeps the +Y default.
  std::vector<bool> used(exact.size(), false);
  for (std::uint32_t index : sphere.indices) used[index] = true;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    if (!used[i]) continue;
    EXPECT_NEAR(glm::length(sphere.normals[i]), 1.0f, 1e-5f);
    EXPECT_LT(glm::distance(sphere.normals[i], exact[i]), 0.07f) << "vertex " << i;
  }
}

TEST(SmoothNormals, UnusedVertexGetsUp) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  mesh.indices = {0, 1, 2};
  computeSmoothNormals(mesh);
  EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.normals[3], glm::vec3(0, 1, 0));
}

}  // namespace
}  // namespace mane::scenes
