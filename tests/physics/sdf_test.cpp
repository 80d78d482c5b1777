// The signed distance field of a triangle mesh (physics/sdf.hpp) against analytic distances:
// a sphere (icosphere mesh) and a cube, with the sign right inside and outside, the exact
// point–triangle distance against brute-force sampling of the triangle, and the contact cells
// that cull samples against the node values they summarise.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"
#include "physics/sdf.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;

float norm(const glm::vec3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

// How far the icosphere's faces sink below the sphere it is inscribed in: R minus the smallest
// distance from the centre to a face's plane. Every point of the mesh lies within this of the
// sphere, so the mesh's distance field is within it of the sphere's, |p| − R.
float sagitta(const TriangleMesh& mesh, float radius) {
  double nearest = radius;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    glm::dvec3 n = glm::dvec3(glm::cross(b - a, c - a));
    n /= std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    nearest = std::min(nearest, std::abs(n.x * a.x + n.y * a.y + n.z * a.z));
  }
  return static_cast<float>(radius - nearest);
}

TEST(SignedDistanceField, IcosphereMatchesTheAnalyticSphereWithinTheResolutionBound) {
  // Reference: the sphere's signed distance |p| − R. Tolerance: the mesh's sagitta (faces are
  // inside the sphere by at most that) plus √3·h, the most a trilinear sample of a 1-Lipschitz
  // function can differ from it inside a cell of size h.
  constexpr float kRadius = 0.1f;
  const TriangleMesh mesh = makeIcosphere(kRadius, 4);
  ASSERT_EQ(mesh.indices.size(), 3u * 5120u);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices, {.resolution = 48});
  ASSERT_TRUE(sdf) << sdf.error().message;
  EXPECT_EQ(sdf->dimensions(), glm::ivec3(48));
  const float h = sdf->cellSize();
  const float tolerance = sagitta(mesh, kRadius) + std::sqrt(3.0f) * h;

  SplitMix64 rng(7);
  float worst = 0.0f;
  int inside = 0, outside = 0;
  for (int n = 0; n < 20000; ++n) {
    const glm::vec3 lo = sdf->origin(), hi = sdf->upperCorner();
    const glm::vec3 p(rng.nextFloat(lo.x, hi.x), rng.nextFloat(lo.y, hi.y), rng.nextFloat(lo.z, hi.z));
    const float exact = norm(p) - kRadius;
    const float d = sdf->sample(p);
    worst = std::max(worst, std::abs(d - exact));
    ASSERT_NEAR(d, exact, tolerance) << "at (" << p.x << ", " << p.y << ", " << p.z << ")";
    // The sign is right wherever the analytic distance exceeds the bound.
    if (exact < -tolerance) {
      EXPECT_LT(d, 0.0f);
      ++inside;
    }
    if (exact > tolerance) {
      EXPECT_GT(d, 0.0f);
      ++outside;
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
  RecordProperty("max_error_m", std::to_string(worst));
  RecordProperty("bound_m", std::to_string(tolerance));
  std::printf("icosphere SDF: h = %.5f m, max |error| = %.6f m, bound = %.6f m\n", h, worst, tolerance);

  // At the grid nodes of the narrow band (within 2 cells of the mesh; no interpolation) the field
  // is the mesh's exact distance, so within the sagitta of the sphere's (plus float rounding).
  // Farther out the sweeps give the distance to a nearby triangle: never below the exact one.
  const glm::ivec3 dims = sdf->dimensions();
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const glm::vec3 p = sdf->origin() + glm::vec3(i, j, k) * h;
        const float value = sdf->values()[static_cast<std::size_t>(i + dims.x * (j + dims.y * k))];
        const float exact = norm(p) - kRadius;
        if (std::abs(value) <= 2.0f * h) {
          ASSERT_NEAR(value, exact, sagitta(mesh, kRadius) + 1e-6f) << i << ", " << j << ", " << k;
        } else {
          ASSERT_GE(std::abs(value), std::abs(exact) - sagitta(mesh, kRadius) - 1e-6f) << i << ", " << j << ", " << k;
        }
      }
}

TEST(SignedDistanceField, CubeMatchesTheAnalyticBoxDistance) {
  // A cube [−a, a]³ as 12 triangles. Reference: the exact box distance (Quilez): with
  // q = |p| − a per axis, |max(q, 0)| + min(max(qx, qy, qz), 0). The mesh is exact, so the
  // tolerance is the trilinear bound √3·h alone.
  constexpr float a = 0.05f;
  const std::vector<glm::vec3> corners = {{-a, -a, -a}, {a, -a, -a}, {a, a, -a}, {-a, a, -a},
                                          {-a, -a, a},  {a, -a, a},  {a, a, a},  {-a, a, a}};
  const std::vector<std::uint32_t> indices = {0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                              3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
  auto sdf = SignedDistanceField::build(corners, indices, {.resolution = 40});
  ASSERT_TRUE(sdf) << sdf.error().message;
  const float tolerance = std::sqrt(3.0f) * sdf->cellSize();
  SplitMix64 rng(3);
  for (int n = 0; n < 20000; ++n) {
    const glm::vec3 p(rng.nextFloat(-0.07f, 0.07f), rng.nextFloat(-0.07f, 0.07f), rng.nextFloat(-0.07f, 0.07f));
    const glm::vec3 q = glm::abs(p) - glm::vec3(a);
    const float exact = norm(glm::max(q, glm::vec3(0.0f))) + std::min(std::max({q.x, q.y, q.z}), 0.0f);
    const float d = sdf->sample(p);
    ASSERT_NEAR(d, exact, tolerance) << "at (" << p.x << ", " << p.y << ", " << p.z << ")";
    if (exact < -tolerance) {
      ASSERT_LT(d, 0.0f);
    }
    if (exact > tolerance) {
      ASSERT_GT(d, 0.0f);
    }
  }
  // Far outside the grid the sample stays positive and no farther than the true distance plus
  // the box's diagonal error.
  EXPECT_NEAR(sdf->sample({1.0f, 0.0f, 0.0f}), 1.0f - a, tolerance);
}

TEST(SignedDistanceField, GradientPointsOutwardWithUnitLength) {
  // Reference: ∇(|p| − R) = p/|p|. Within a cell the trilinear gradient of an exact distance
  // field is an average of finite differences; measured at points 0.5 R to 1.05 R from the
  // centre (inside the grid, away from the medial point at the centre), it must be within 0.1 of
  // unit length and within 8° of the radial direction (faces of this mesh span about 4°).
  const TriangleMesh mesh = makeIcosphere(0.1f, 4);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices);
  ASSERT_TRUE(sdf);
  SplitMix64 rng(11);
  for (int n = 0; n < 5000; ++n) {
    const glm::vec3 p(rng.nextFloat(-0.15f, 0.15f), rng.nextFloat(-0.15f, 0.15f), rng.nextFloat(-0.15f, 0.15f));
    if (norm(p) < 0.05f || norm(p) > 0.105f) continue;
    glm::vec3 g;
    const float d = sdf->sampleWithGradient(p, g);
    EXPECT_EQ(d, sdf->sample(p));
    EXPECT_NEAR(norm(g), 1.0f, 0.1f);
    EXPECT_GT(glm::dot(g / norm(g), p / norm(p)), std::cos(8.0f * 3.14159265f / 180.0f));
  }
}

TEST(SignedDistanceField, UnweldedSeamsGiveTheSameField) {
  // glTF meshes repeat vertices along UV seams. Giving every triangle its own three vertices
  // must not change a bit of the field (vertices are welded by position before pseudo-normals).
  const TriangleMesh mesh = makeIcosphere(0.1f, 2);
  std::vector<glm::vec3> split;
  std::vector<std::uint32_t> splitIndices;
  for (std::uint32_t index : mesh.indices) {
    splitIndices.push_back(static_cast<std::uint32_t>(split.size()));
    split.push_back(mesh.positions[index]);
  }
  auto welded = SignedDistanceField::build(mesh.positions, mesh.indices, {.resolution = 24});
  auto unwelded = SignedDistanceField::build(split, splitIndices, {.resolution = 24});
  ASSERT_TRUE(welded && unwelded);
  ASSERT_EQ(welded->values().size(), unwelded->values().size());
  EXPECT_EQ(std::memcmp(welded->values().data(), unwelded->values().data(), welded->values().size() * sizeof(float)),
            0);
}

TEST(SignedDistanceField, ClosestPointOnTriangleMatchesBruteForce) {
  // Reference: the smallest distance over a 400 × 400 barycentric lattice on the triangle. The
  // exact answer can never be farther than that minimum, and is no closer than it minus the
  // lattice spacing (the closest lattice point is within one spacing of the closest point).
  SplitMix64 rng(5);
  for (int n = 0; n < 200; ++n) {
    const auto random = [&] {
      return glm::dvec3(rng.nextFloat(-1.0f, 1.0f), rng.nextFloat(-1.0f, 1.0f), rng.nextFloat(-1.0f, 1.0f));
    };
    const glm::dvec3 a = random(), b = random(), c = random(), p = random() * 2.0;
    int feature = -1;
    const glm::dvec3 q = closestPointOnTriangle(p, a, b, c, feature);
    const double exact = glm::length(p - q);
    constexpr int kSteps = 400;
    double brute = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; i + j <= kSteps; ++j) {
        const double u = static_cast<double>(i) / kSteps, v = static_cast<double>(j) / kSteps;
        brute = std::min(brute, glm::length(p - (a + (b - a) * u + (c - a) * v)));
      }
    const double spacing = std::max({glm::length(b - a), glm::length(c - a), glm::length(c - b)}) / kSteps;
    EXPECT_LE(exact, brute + 1e-12);
    EXPECT_GE(exact, brute - spacing);
    EXPECT_GE(feature, 0);
    EXPECT_LE(feature, 6);
  }
}

TEST(SignedDistanceField, ContactCellsMarkExactlyTheCellsWithANodeBelowTheContactLevel) {
  // Reference: each cell's 8 node values against contactLevel() (half a cell), cell by cell over
  // the whole grid of an ellipsoidal head. Then mayBeBelow may skip only points whose sample is
  // ≥ the level: 200,000 points in the contact box, levels 0 and 0.4 of a cell (below the
  // contact level), where the cells skip more than the box alone.
  TriangleMesh mesh = makeIcosphere(1.0f, 3);
  for (glm::vec3& p : mesh.positions) p *= glm::vec3(0.085f, 0.097f, 0.095f);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices, {.resolution = 40});
  ASSERT_TRUE(sdf);
  ASSERT_GT(sdf->contactLevel(), 0.0f);
  const glm::ivec3 dims = sdf->dimensions();
  const std::span<const float> v = sdf->values();
  const std::span<const std::uint32_t> cells = sdf->contactCells();
  ASSERT_EQ(cells.size(), (v.size() + 31) / 32);
  std::size_t marked = 0;
  for (int k = 0; k + 1 < dims.z; ++k)
    for (int j = 0; j + 1 < dims.y; ++j)
      for (int i = 0; i + 1 < dims.x; ++i) {
        const std::size_t n = static_cast<std::size_t>(i + dims.x * (j + dims.y * k));
        const std::size_t sy = static_cast<std::size_t>(dims.x), sz = sy * static_cast<std::size_t>(dims.y);
        const float lowest = std::min(
            {v[n], v[n + 1], v[n + sy], v[n + sy + 1], v[n + sz], v[n + sz + 1], v[n + sz + sy], v[n + sz + sy + 1]});
        const bool bit = (cells[n / 32] >> (n % 32) & 1u) != 0;
        ASSERT_EQ(bit, lowest < sdf->contactLevel()) << i << ", " << j << ", " << k;
        marked += bit;
      }
  EXPECT_GT(marked, 0u);
  const glm::vec3 lo = sdf->contactLower(), hi = sdf->contactUpper();
  SplitMix64 rng(5);
  for (const float level : {0.0f, 0.4f * sdf->cellSize()}) {
    int inBoxSkipped = 0;
    for (int n = 0; n < 200000; ++n) {
      const glm::vec3 p(rng.nextFloat(lo.x, hi.x), rng.nextFloat(lo.y, hi.y), rng.nextFloat(lo.z, hi.z));
      if (sdf->mayBeBelow(p, level)) continue;
      ++inBoxSkipped;
      ASSERT_GE(sdf->sample(p), level) << p.x << ", " << p.y << ", " << p.z;
    }
    EXPECT_GT(inBoxSkipped, 50000) << "the cells skip the box's corners, outside the head";
  }
}

TEST(SignedDistanceField, BadMeshesAreRejectedWithAReason) {
  const TriangleMesh mesh = makeIcosphere(0.1f, 1);
  const auto error = [](std::span<const glm::vec3> p, std::span<const std::uint32_t> i, SdfSettings s = {}) {
    auto sdf = SignedDistanceField::build(p, i, s);
    EXPECT_FALSE(sdf);
    return sdf ? std::string() : sdf.error().message;
  };
  EXPECT_THAT(error({}, {}), HasSubstr("empty"));
  std::vector<std::uint32_t> indices = mesh.indices;
  indices.pop_back();
  EXPECT_THAT(error(mesh.positions, indices), HasSubstr("multiple of 3"));
  indices = mesh.indices;
  indices[7] = 9999;
  EXPECT_THAT(error(mesh.positions, indices), HasSubstr("triangle 2"));
  std::vector<glm::vec3> positions = mesh.positions;
  positions[4].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(error(positions, mesh.indices), HasSubstr("vertex 4"));
  const std::vector<glm::vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<std::uint32_t> flat = {0, 1, 2};
  EXPECT_THAT(error(line, flat), HasSubstr("degenerate"));
  EXPECT_THAT(error(mesh.positions, mesh.indices, {.resolution = 3}), HasSubstr("resolution"));
}

}  // namespace
}  // namespace mane::physics
