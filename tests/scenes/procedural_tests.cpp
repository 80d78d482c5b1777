// The procedural meshes against geometry: the sphere's radius, normals, closure, outward winding
// and area; the translucency test objects' (cube with a hollow, torus) closure by position,
// enclosed volume and normals; and smooth normals against the sphere's exact ones.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include <glm/geometric.hpp>

#include "render/luts/solid_voxels.hpp"
#include "scenes/procedural.hpp"

namespace mane::scenes {
namespace {

using PositionKey = std::tuple<float, float, float>;

/// Positions compared by value (−0 equals +0), as render::voxelizeSolid compares them.
PositionKey keyOf(const glm::vec3& p) {
  return {p.x, p.y, p.z};
}

/// Directed edges a→b without a matching b→a, counted with multiplicity, vertices compared by
/// position: 0 for a closed, consistently wound mesh whatever its seams duplicate.
int unmatchedEdges(const Mesh& mesh) {
  std::map<std::pair<PositionKey, PositionKey>, int> directed;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (std::size_t e = 0; e < 3; ++e) {
      const PositionKey a = keyOf(mesh.positions[mesh.indices[t + e]]);
      const PositionKey b = keyOf(mesh.positions[mesh.indices[t + (e + 1) % 3]]);
      ++directed[{a, b}];
    }
  }
  int unmatched = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    unmatched += std::abs(count - (reverse == directed.end() ? 0 : reverse->second));
  }
  return unmatched;
}

/// Volume enclosed by a closed mesh, by the divergence theorem: Σ a · (b × c) / 6 over its
/// triangles, in double. Positive when wound counter-clockwise seen from outside the material.
double enclosedVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]);
    const glm::dvec3 b(mesh.positions[mesh.indices[t + 1]]);
    const glm::dvec3 c(mesh.positions[mesh.indices[t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

/// The area of a regular k-gon over that of its circumcircle: k·sin(2π/k) / 2π, which is at
/// least 1 − (2π/k)²/6 (sin x ≥ x − x³/6).
double inscribedPolygonFraction(int k) {
  const double step = 2.0 * std::numbers::pi / k;
  return std::sin(step) / step;
}

/// The triangle's normal by its winding, unnormalised.
glm::vec3 windingNormal(const Mesh& mesh, std::size_t triangle) {
  const glm::vec3& a = mesh.positions[mesh.indices[3 * triangle]];
  const glm::vec3& b = mesh.positions[mesh.indices[3 * triangle + 1]];
  const glm::vec3& c = mesh.positions[mesh.indices[3 * triangle + 2]];
  return glm::cross(b - a, c - a);
}

/// Every triangle winds the way its vertices' normals point.
void expectWindingFollowsNormals(const Mesh& mesh) {
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::vec3 n = windingNormal(mesh, t);
    for (std::size_t c = 0; c < 3; ++c) {
      ASSERT_GT(glm::dot(n, mesh.normals[mesh.indices[3 * t + c]]), 0.0f) << "triangle " << t << " corner " << c;
    }
  }
}

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

TEST(ProceduralSphere, IsClosedByExactPositionAtItsSeamAndPoles) {
  // Without the seam and poles set exactly, sin(2π) and sin(π) in float leave the duplicated
  // copies 1e-7 away from their twins, and the voxelizer's closedness check fails.
  EXPECT_EQ(unmatchedEdges(makeSphere(12, 20, 0.5f)), 0);
}

// The voxelized-translucency paper's hollow cube: [−1, 1]³ minus a ball of radius 0.5, at 16
// rings × 32 segments.
constexpr int kHollowRings = 16;
constexpr int kHollowSegments = 32;

TEST(ProceduralCubeWithHollow, IsClosedByPositionWithUvsForEveryVertex) {
  const Mesh mesh = makeCubeWithHollow(1.0f, 0.5f, kHollowRings, kHollowSegments);
  EXPECT_EQ(validate(mesh), "");
  EXPECT_EQ(mesh.uvs.size(), mesh.vertexCount());
  EXPECT_EQ(mesh.normals.size(), mesh.vertexCount());
  EXPECT_EQ(mesh.triangleCount(), 12u + 2u * kHollowSegments * (kHollowRings - 1u));
  EXPECT_EQ(unmatchedEdges(mesh), 0);
  EXPECT_EQ(mesh.bounds().min, glm::vec3(-1.0f));
  EXPECT_EQ(mesh.bounds().max, glm::vec3(1.0f));
}

TEST(ProceduralCubeWithHollow, EnclosesTheCubeMinusTheBallWithinTheInscribedPolygonError) {
  const double radius = 0.5;
  const double ball = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  const double analytic = 8.0 - ball;
  const double volume = enclosedVolume(makeCubeWithHollow(1.0f, 0.5f, kHollowRings, kHollowSegments));
  // The hollow is a convex polyhedron inscribed in the ball, so the mesh holds at least the
  // analytic volume. Its horizontal sections are regular 32-gons (area fraction s(32) of their
  // circles) of a solid of revolution whose meridian polygon, 16 chords of a semicircle, holds
  // the disc of radius r·cos(π/32): the hollow is at least s(32)·cos³(π/32) of the ball.
  const double hollowFraction =
      inscribedPolygonFraction(kHollowSegments) * std::pow(std::cos(std::numbers::pi / (2.0 * kHollowRings)), 3.0);
  const double bound = ball * (1.0 - hollowFraction);  // 0.011, 0.14 % of the volume
  // 1e-5: float positions (6e-8 relative) and the double sum, far below the bound.
  EXPECT_GE(volume, analytic - 1e-5);
  EXPECT_LE(volume, analytic + bound + 1e-5);
}

TEST(ProceduralCubeWithHollow, NormalsPointAwayFromTheMaterial) {
  const Mesh mesh = makeCubeWithHollow(1.0f, 0.5f, kHollowRings, kHollowSegments);
  std::size_t hollowVertices = 0;
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    const glm::vec3& n = mesh.normals[i];
    if (std::abs(glm::length(p) - 0.5f) < 1e-5f) {
      // On the hollow: towards its centre, into the empty space.
      EXPECT_LT(glm::distance(n, -p / 0.5f), 1e-5f) << "vertex " << i;
      ++hollowVertices;
    } else {
      // On the cube: a face's flat outward normal, ±x, ±y or ±z, on that face.
      EXPECT_FLOAT_EQ(glm::length(n), 1.0f) << "vertex " << i;
      EXPECT_FLOAT_EQ(glm::dot(p, n), 1.0f) << "vertex " << i;
      EXPECT_EQ(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0f) << "vertex " << i;
    }
  }
  EXPECT_EQ(hollowVertices, (kHollowRings + 1u) * (kHollowSegments + 1u));
  expectWindingFollowsNormals(mesh);
}

TEST(ProceduralCubeWithHollow, VoxelizesWithAnEmptyHollow) {
  // At 16³ cells of 1/8: the centre cells are inside the hollow, those midway to a face in the
  // material, so the solid fraction of the grid is the cube minus the ball's (within a voxel).
  const Mesh mesh = makeCubeWithHollow(1.0f, 0.5f, kHollowRings, kHollowSegments);
  auto voxels = render::voxelizeSolid(mesh.positions, mesh.indices, 16);
  ASSERT_TRUE(voxels.has_value()) << voxels.error().message;
  EXPECT_FALSE(voxels->isSolid(8, 8, 8));   // centre (0.0625, ...): in the hollow
  EXPECT_TRUE(voxels->isSolid(13, 8, 8));   // x = 0.6875: between the hollow and the face
  EXPECT_TRUE(voxels->isSolid(0, 15, 0));   // a corner cell
  EXPECT_FALSE(voxels->isSolid(8, 10, 7));  // y = 0.3125 above the centre: still in the hollow
}

// The voxelized-translucency paper's torus: major radius 1, minor 0.4, around +Y.
constexpr float kMajorRadius = 1.0f;
constexpr float kMinorRadius = 0.4f;
constexpr int kMajorSegments = 48;
constexpr int kMinorSegments = 24;

TEST(ProceduralTorus, IsClosedByPositionAndLiesFlatAroundY) {
  const Mesh torus = makeTorus(kMajorRadius, kMinorRadius, kMajorSegments, kMinorSegments);
  EXPECT_EQ(validate(torus), "");
  EXPECT_EQ(torus.vertexCount(), (kMajorSegments + 1u) * (kMinorSegments + 1u));
  EXPECT_EQ(torus.triangleCount(), 2u * kMajorSegments * kMinorSegments);
  EXPECT_EQ(torus.uvs.size(), torus.vertexCount());
  EXPECT_EQ(unmatchedEdges(torus), 0);
  const Bounds box = torus.bounds();
  EXPECT_NEAR(box.max.y, kMinorRadius, 1e-6f);  // θ = π/2 is a vertex row (24 is divisible by 4)
  EXPECT_NEAR(box.min.y, -kMinorRadius, 1e-6f);
  EXPECT_NEAR(box.max.x, kMajorRadius + kMinorRadius, 1e-6f);
  EXPECT_NEAR(box.min.x, -(kMajorRadius + kMinorRadius), 1e-6f);
  EXPECT_NEAR(box.max.z, kMajorRadius + kMinorRadius, 1e-6f);
}

TEST(ProceduralTorus, EnclosesPappusVolumeWithinTheInscribedPolygonError) {
  const double analytic = 2.0 * std::numbers::pi * std::numbers::pi * kMajorRadius * kMinorRadius * kMinorRadius;
  const double volume = enclosedVolume(makeTorus(kMajorRadius, kMinorRadius, kMajorSegments, kMinorSegments));
  // Its quads are planar trapezoids; each wedge between two meridians holds sin(2π/N) times the
  // first moment ∫ρ dA of the tube's inscribed n-gon, which is its area times R. Hence exactly
  // V·s(N)·s(n), and 0 ≤ V − V_mesh ≤ V·((2π/N)² + (2π/n)²)/6.
  const double exact = analytic * inscribedPolygonFraction(kMajorSegments) * inscribedPolygonFraction(kMinorSegments);
  EXPECT_NEAR(volume, exact, 1e-5 * analytic);  // float positions
  const double step = 2.0 * std::numbers::pi;
  const double bound = analytic * (std::pow(step / kMajorSegments, 2) + std::pow(step / kMinorSegments, 2)) / 6.0;
  EXPECT_LE(volume, analytic + 1e-5);
  EXPECT_GE(volume, analytic - bound - 1e-5);  // bound: 1.4 % of the volume
}

TEST(ProceduralTorus, NormalsPointAwayFromTheTubeCore) {
  const Mesh torus = makeTorus(kMajorRadius, kMinorRadius, kMajorSegments, kMinorSegments);
  for (std::size_t i = 0; i < torus.vertexCount(); ++i) {
    const glm::vec3& p = torus.positions[i];
    const glm::vec3 core = kMajorRadius * glm::normalize(glm::vec3(p.x, 0.0f, p.z));
    EXPECT_NEAR(glm::distance(p, core), kMinorRadius, 1e-6f) << "vertex " << i;
    EXPECT_LT(glm::distance(torus.normals[i], (p - core) / kMinorRadius), 1e-5f) << "vertex " << i;
  }
  expectWindingFollowsNormals(torus);
}

TEST(ProceduralTorus, VoxelizesWithAnEmptyHole) {
  const Mesh torus = makeTorus(kMajorRadius, kMinorRadius, kMajorSegments, kMinorSegments);
  auto voxels = render::voxelizeSolid(torus.positions, torus.indices, 28);
  ASSERT_TRUE(voxels.has_value()) << voxels.error().message;
  // Cells of 0.1 across x and z: the centre column is the hole, x = 1.05 lies in the tube.
  const glm::ivec3 hole = voxels->cellAt(glm::dvec3(0.0, 0.0, 0.0));
  const glm::ivec3 tube = voxels->cellAt(glm::dvec3(1.05, 0.0, 0.05));
  EXPECT_FALSE(voxels->isSolid(hole.x, hole.y, hole.z));
  EXPECT_TRUE(voxels->isSolid(tube.x, tube.y, tube.z));
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
TEST(ProceduralPlane, IsAFloorOfTheAskedSideFacingUp) {
  const Mesh plane = makePlane(0.5f);
  ASSERT_EQ(plane.indices.size(), 6u);
  ASSERT_EQ(plane.uvs.size(), plane.positions.size());
  float area = 0.0f;
  for (std::size_t t = 0; t < plane.indices.size(); t += 3) {
    const glm::vec3 a = plane.positions[plane.indices[t]], b = plane.positions[plane.indices[t + 1]],
                    c = plane.positions[plane.indices[t + 2]];
    const glm::vec3 twice = glm::cross(b - a, c - a);
    EXPECT_GT(twice.y, 0.0f) << "counter-clockwise seen from above";
    area += 0.5f * glm::length(twice);
  }
  EXPECT_FLOAT_EQ(area, 1.0f);
  for (const glm::vec3& p : plane.positions) {
    EXPECT_EQ(p.y, 0.0f);
    EXPECT_EQ(std::max(std::abs(p.x), std::abs(p.z)), 0.5f);
  }
  for (const glm::vec3& n : plane.normals) EXPECT_EQ(n, glm::vec3(0.0f, 1.0f, 0.0f));
}

}  // namespace mane::scenes
