// Points bound to a triangle mesh (physics::SurfaceBinding): they bind at height 0 on the
// surface and evaluate back to themselves, follow a rigid motion of the mesh, stay on their
// triangles of a skinned, bent bar, agree with a brute-force closest-point search, and bad input
// is named.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"
#include "physics/sdf.hpp"
#include "physics/skinning.hpp"
#include "physics/surface_binding.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;

// `count` points on the surface of `mesh`: a random triangle each, random barycentrics.
std::vector<glm::vec3> pointsOnSurface(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                                       std::size_t count, std::uint64_t seed) {
  SplitMix64 rng(seed);
  const std::size_t triangles = indices.size() / 3;
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < count; ++i) {
    const auto t = static_cast<std::size_t>(rng.nextFloat(0.0f, 1.0f) * static_cast<float>(triangles)) % triangles;
    float u = rng.nextFloat(0.0f, 1.0f), v = rng.nextFloat(0.0f, 1.0f);
    if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
    const glm::vec3 a = positions[indices[3 * t]], b = positions[indices[3 * t + 1]], c = positions[indices[3 * t + 2]];
    points.push_back(a + (b - a) * u + (c - a) * v);
  }
  return points;
}

glm::vec3 transformed(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

TEST(SurfaceBinding, PointsOnTheMeshBindAtHeightZeroAndEvaluateToThemselves) {
  const TriangleMesh mesh = makeIcosphere(0.1f, 3);
  const auto points = pointsOnSurface(mesh.positions, mesh.indices, 500, 3);
  auto binding = SurfaceBinding::create(mesh.positions, mesh.indices, points);
  ASSERT_TRUE(binding) << binding.error().message;
  // The points were made in float at 0.1 m: a few 1e-8 m of rounding off the plane.
  EXPECT_LT(binding->largestHeight(), 1e-7f);
  for (const SurfacePoint& point : binding->points()) {
    EXPECT_LT(std::abs(point.height), 1e-7f);
    EXPECT_GE(std::min({point.barycentric.x, point.barycentric.y, point.barycentric.z}), -1e-5f);
  }
  std::vector<glm::vec3> evaluated(points.size());
  ASSERT_TRUE(binding->evaluate(mesh.positions, {}, evaluated, {}, {}));
  for (std::size_t i = 0; i < points.size(); ++i)
    EXPECT_LT(glm::distance(evaluated[i], points[i]), 1e-6f) << "point " << i;
}

TEST(SurfaceBinding, PointsOffTheSurfaceComeBackAtTheirHeight) {
  // A flat square (two triangles) and points above, below and beside it: the rest mesh gives
  // each point back (barycentrics of its plane projection, signed height).
  const std::vector<glm::vec3> square = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 1, 3, 2};
  const std::vector<glm::vec3> points = {{0.2f, 0.3f, 0.05f}, {0.7f, 0.6f, -0.1f}, {1.2f, 0.5f, 0.0f}};
  auto binding = SurfaceBinding::create(square, indices, points);
  ASSERT_TRUE(binding);
  EXPECT_FLOAT_EQ(binding->points()[0].height, 0.05f);
  EXPECT_FLOAT_EQ(binding->points()[1].height, -0.1f);
  EXPECT_EQ(binding->points()[2].triangle, 1u);
  EXPECT_NEAR(binding->largestHeight(), 0.2f, 1e-6f);  // the point beside the square, 0.2 m off
  std::vector<glm::vec3> evaluated(points.size()), normals(points.size()), tangents(points.size());
  ASSERT_TRUE(binding->evaluate(square, {}, evaluated, normals, tangents));
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_LT(glm::distance(evaluated[i], points[i]), 1e-6f) << "point " << i;
    EXPECT_EQ(normals[i], glm::vec3(0, 0, 1));
  }
  EXPECT_EQ(tangents[0], glm::vec3(1, 0, 0));  // triangle 0's first edge, 0 → 1
}

TEST(SurfaceBinding, PointsFollowARigidMotionOfTheMesh) {
  const TriangleMesh mesh = makeIcosphere(0.1f, 3);
  auto points = pointsOnSurface(mesh.positions, mesh.indices, 300, 5);
  // Half of them lifted off the surface by up to 2 cm (a strand's root above the skin).
  for (std::size_t i = 0; i < points.size(); i += 2) points[i] *= 1.0f + 0.2f * float(i % 7) / 7.0f;
  auto binding = SurfaceBinding::create(mesh.positions, mesh.indices, points);
  ASSERT_TRUE(binding);
  glm::mat4 motion = glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, -1.2f, 0.7f));
  motion = glm::rotate(motion, 1.1f, glm::normalize(glm::vec3(0.3f, 1.0f, -0.5f)));
  std::vector<glm::vec3> moved(mesh.positions.size());
  for (std::size_t v = 0; v < moved.size(); ++v) moved[v] = transformed(motion, mesh.positions[v]);
  std::vector<glm::vec3> evaluated(points.size()), normals(points.size()), tangents(points.size());
  ASSERT_TRUE(binding->evaluate(moved, {}, evaluated, normals, tangents));
  // Float rounding of a rotation and a translation of ~1 m: a few 1e-7 m.
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_LT(glm::distance(evaluated[i], transformed(motion, points[i])), 1e-5f) << "point " << i;
    EXPECT_NEAR(glm::length(normals[i]), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(tangents[i]), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(normals[i], tangents[i]), 0.0f, 1e-6f);
  }
}

// A square tube 1 m long along x, 0.1 m across, in 20 rings of 4 vertices; joint 0 holds the
// first half, joint 1 the second, blended over the middle rings.
SkinnedMeshData twoJointBar() {
  SkinnedMeshData bar;
  constexpr int kRings = 21;
  const glm::vec2 corners[4] = {{-0.05f, -0.05f}, {0.05f, -0.05f}, {0.05f, 0.05f}, {-0.05f, 0.05f}};
  bar.influencesPerVertex = 2;
  bar.jointCount = 2;
  for (int r = 0; r < kRings; ++r) {
    const float x = float(r) / float(kRings - 1);
    const float second = std::clamp((x - 0.35f) / 0.3f, 0.0f, 1.0f);
    for (const glm::vec2& c : corners) {
      bar.positions.push_back({x, c.x, c.y});
      bar.joints.insert(bar.joints.end(), {0u, 1u});
      bar.weights.insert(bar.weights.end(), {1.0f - second, second});
    }
  }
  for (std::uint32_t r = 0; r + 1 < kRings; ++r)
    for (std::uint32_t k = 0; k < 4; ++k) {
      const std::uint32_t a = 4 * r + k, b = 4 * r + (k + 1) % 4, c = a + 4, d = b + 4;
      bar.indices.insert(bar.indices.end(), {a, b, c, b, d, c});
    }
  return bar;
}

TEST(SurfaceBinding, PointsStayOnTheirTrianglesOfABentSkinnedBar) {
  auto bar = SkinnedMesh::create(twoJointBar());
  ASSERT_TRUE(bar) << bar.error().message;
  const auto& rest = bar->data();
  const auto points = pointsOnSurface(rest.positions, rest.indices, 400, 9);
  auto binding = SurfaceBinding::create(rest.positions, rest.indices, points);
  ASSERT_TRUE(binding);
  // Joint 1 turns the far half by 70° about z through the bar's middle.
  const glm::mat4 bend = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.0f, 0.0f)) *
                         glm::rotate(glm::mat4(1.0f), glm::radians(70.0f), glm::vec3(0, 0, 1)) *
                         glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.0f, 0.0f));
  const std::vector<glm::mat4> joints = {glm::mat4(1.0f), bend};
  DeformedSurface deformed;
  ASSERT_TRUE(bar->deform(joints, {}, deformed));
  std::vector<glm::vec3> evaluated(points.size());
  ASSERT_TRUE(binding->evaluate(deformed.positions, {}, evaluated, {}, {}));
  // The reference: the point's distance to its own deformed triangle (plane and inside at
  // once), in double. Rounding of the float blend at 1 m: well under 1e-6 m.
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::uint32_t t = binding->points()[i].triangle;
    const glm::dvec3 a(deformed.positions[rest.indices[3 * t]]), b(deformed.positions[rest.indices[3 * t + 1]]),
        c(deformed.positions[rest.indices[3 * t + 2]]);
    const glm::dvec3 p(evaluated[i]);
    const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
    EXPECT_LT(std::abs(glm::dot(p - a, normal)), 1e-6) << "point " << i << " off its plane";
    int feature = 0;
    EXPECT_LT(glm::distance(p, closestPointOnTriangle(p, a, b, c, feature)), 1e-6)
        << "point " << i << " outside its triangle";
  }
}

TEST(SurfaceBinding, ClosestTriangleAgreesWithABruteForceSearch) {
  // A lumpy ellipsoid and points scattered around and inside it.
  TriangleMesh mesh = makeIcosphere(1.0f, 4);
  SplitMix64 rng(21);
  for (glm::vec3& p : mesh.positions) p *= glm::vec3(0.09f, 0.11f, 0.1f) * rng.nextFloat(0.9f, 1.1f);
  std::vector<glm::vec3> points;
  for (int i = 0; i < 400; ++i)
    points.push_back({rng.nextFloat(-0.2f, 0.2f), rng.nextFloat(-0.2f, 0.2f), rng.nextFloat(-0.2f, 0.2f)});
  auto binding = SurfaceBinding::create(mesh.positions, mesh.indices, points);
  ASSERT_TRUE(binding);
  double largest = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 p(points[i]);
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t bestTriangle = 0;
    for (std::uint32_t t = 0; t < mesh.indices.size() / 3; ++t) {
      int feature = 0;
      const double d =
          glm::distance(p, closestPointOnTriangle(p, glm::dvec3(mesh.positions[mesh.indices[3 * t]]),
                                                  glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]),
                                                  glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]]), feature));
      if (d < best) best = d, bestTriangle = t;  // strict: the lowest index among equals
    }
    largest = std::max(largest, best);
    EXPECT_EQ(binding->points()[i].triangle, bestTriangle) << "point " << i;
  }
  EXPECT_NEAR(binding->largestHeight(), largest, 1e-7);
}

TEST(SurfaceBinding, EquallyCloseTrianglesGoToTheLowestIndex) {
  // A fan of 8 triangles around vertex 0; a point straight above vertex 0 is exactly as close to
  // all of them (the same corner). 8 triangles make two leaves of the search tree; triangle 0
  // (centroid at +x) sits in the one searched second, so the tie is met and must be broken.
  std::vector<glm::vec3> fan = {{0, 0, 0}};
  std::vector<std::uint32_t> indices;
  for (std::uint32_t k = 0; k < 8; ++k) {
    const float angle = glm::radians(45.0f * float(k));
    fan.push_back({std::cos(angle), std::sin(angle), 0.0f});
    indices.insert(indices.end(), {0u, 1 + k, 1 + (k + 1) % 8});
  }
  auto binding = SurfaceBinding::create(fan, indices, std::vector<glm::vec3>{{0.0f, 0.0f, 0.3f}});
  ASSERT_TRUE(binding);
  EXPECT_EQ(binding->points()[0].triangle, 0u);
}

TEST(SurfaceBinding, DegenerateTrianglesAreSkippedAndCollapsedOnesKeepTheirNormal) {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 1, 3};  // triangle 0 is a line
  auto binding = SurfaceBinding::create(positions, indices, std::vector<glm::vec3>{{0.5f, 0.0f, 0.1f}});
  ASSERT_TRUE(binding);
  EXPECT_EQ(binding->points()[0].triangle, 1u);
  // Every vertex on one point: no face normal, so the one from binding time holds.
  const std::vector<glm::vec3> collapsed(positions.size(), glm::vec3(0.3f));
  glm::vec3 position, normal, tangent;
  ASSERT_TRUE(binding->evaluate(collapsed, {}, {&position, 1}, {&normal, 1}, {&tangent, 1}));
  EXPECT_EQ(normal, glm::vec3(0, 0, 1));
  EXPECT_NEAR(glm::length(tangent), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(normal, tangent), 0.0f, 1e-6f);
}

TEST(SurfaceBinding, VertexNormalsAreBlendedByTheWeights) {
  const std::vector<glm::vec3> triangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  auto binding = SurfaceBinding::create(triangle, indices, std::vector<glm::vec3>{{0.5f, 0.0f, 0.0f}});
  ASSERT_TRUE(binding);
  const std::vector<glm::vec3> normals = {glm::normalize(glm::vec3(-1, 0, 1)), glm::normalize(glm::vec3(1, 0, 1)),
                                          glm::vec3(0, 0, 1)};
  glm::vec3 position, normal;
  ASSERT_TRUE(binding->evaluate(triangle, normals, {&position, 1}, {&normal, 1}, {}));
  EXPECT_NEAR(glm::distance(normal, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);  // halfway: the two tilts cancel
}

TEST(SurfaceBinding, BadInputIsNamed) {
  const std::vector<glm::vec3> triangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  const std::vector<glm::vec3> point = {{0.2f, 0.2f, 0.0f}};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto failure = [](const Result<SurfaceBinding>& r) { return r ? std::string("no error") : r.error().message; };

  EXPECT_THAT(failure(SurfaceBinding::create({}, indices, point)), HasSubstr("mesh is empty"));
  EXPECT_THAT(failure(SurfaceBinding::create(triangle, std::vector<std::uint32_t>{0, 1}, point)),
              HasSubstr("not a multiple of 3"));
  EXPECT_THAT(failure(SurfaceBinding::create(triangle, std::vector<std::uint32_t>{0, 1, 3}, point)),
              HasSubstr("triangle 0 uses vertex 3 but the mesh has 3 vertices"));
  EXPECT_THAT(
      failure(SurfaceBinding::create(std::vector<glm::vec3>{{0, 0, 0}, {1, nan, 0}, {0, 1, 0}}, indices, point)),
      HasSubstr("mesh vertex 1 is NaN or infinite"));
  EXPECT_THAT(failure(SurfaceBinding::create(triangle, indices, std::vector<glm::vec3>{{0, 0, 0}, {nan, 0, 0}})),
              HasSubstr("point 1 is NaN or infinite"));
  EXPECT_THAT(failure(SurfaceBinding::create(std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, indices, point)),
              HasSubstr("all 1 triangles of the mesh have zero area"));

  auto binding = SurfaceBinding::create(triangle, indices, point);
  ASSERT_TRUE(binding);
  glm::vec3 out[2];
  auto evaluated = binding->evaluate(std::span(triangle).first(2), {}, {out, 1}, {}, {});
  ASSERT_FALSE(evaluated);
  EXPECT_THAT(evaluated.error().message, HasSubstr("has 2 vertices, the binding was made on 3"));
  evaluated = binding->evaluate(triangle, std::span(triangle).first(1), {out, 1}, {}, {});
  ASSERT_FALSE(evaluated);
  EXPECT_THAT(evaluated.error().message, HasSubstr("1 vertex normals for 3 vertices"));
  evaluated = binding->evaluate(triangle, {}, {out, 2}, {}, {});
  ASSERT_FALSE(evaluated);
  EXPECT_THAT(evaluated.error().message, HasSubstr("output positions span holds 2 entries for 1 bound points"));
  evaluated = binding->evaluate(triangle, {}, {out, 1}, {out, 2}, {});
  ASSERT_FALSE(evaluated);
  EXPECT_THAT(evaluated.error().message, HasSubstr("output normals span"));
}

}  // namespace
}  // namespace mane::physics
