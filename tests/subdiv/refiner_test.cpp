// Uniform Catmull-Clark refinement and cage validation.
//
// Oracles: (1) Euler's formula. Every level of a closed genus-0 quad mesh has F = 6·4^L faces,
// E = 2F edges and V = E − F + 2 vertices. (2) Catmull-Clark's convex-hull property and
// symmetry: the refined cube stays inside the cage and symmetric about the origin. (3) Exact
// refinement rules on the unit cube (corners ±1): after one level a face point is the face
// centroid (0,0,±1) and an original corner moves to (Q + 2R + (n−3)S)/n with n = 3 — that is
// ±(5/9, 5/9, 5/9) (Catmull & Clark 1978).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "subdiv/refiner.hpp"

namespace mane::subdiv {
namespace {

Cage unitCube() {
  Cage cage;
  cage.positions = {{-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, -1}, {1, -1, -1}};
  cage.faceSizes = {4, 4, 4, 4, 4, 4};
  // The OpenSubdiv regression cube's faces, counter-clockwise seen from outside.
  cage.faceVertices = {0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4};
  return cage;
}

TEST(UniformRefinement, CubeCountsFollowEulersFormula) {
  for (int level = 1; level <= 4; ++level) {
    auto mesh = refineUniformly(unitCube(), level);
    ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
    const std::size_t faces = 6u << (2 * level);
    EXPECT_EQ(mesh->quads.size(), 4 * faces) << "level " << level;
    EXPECT_EQ(mesh->positions.size(), 2 * faces - faces + 2) << "level " << level;
  }
}

TEST(UniformRefinement, CubeFirstLevelMatchesTheRules) {
  auto mesh = refineUniformly(unitCube(), 1);
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  auto has = [&](glm::vec3 expected) {
    return std::any_of(mesh->positions.begin(), mesh->positions.end(),
                       [&](glm::vec3 p) { return glm::length(p - expected) < 1e-6f; });
  };
  EXPECT_TRUE(has({0, 0, 1}));
  EXPECT_TRUE(has({0, 0, -1}));
  EXPECT_TRUE(has({5.0f / 9, 5.0f / 9, 5.0f / 9}));
  EXPECT_TRUE(has({-5.0f / 9, -5.0f / 9, -5.0f / 9}));
  // Edge points: (2 ends + 2 adjacent face points) / 4 = (0, 3/4, 3/4) for the +Y+Z edge.
  EXPECT_TRUE(has({0, 0.75f, 0.75f}));
}

TEST(UniformRefinement, StaysInsideTheCageAndSymmetric) {
  auto mesh = refineUniformly(unitCube(), 3);
  ASSERT_TRUE(mesh.has_value());
  for (const glm::vec3& p : mesh->positions) {
    EXPECT_LE(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1.0f);
    const bool mirrored = std::any_of(mesh->positions.begin(), mesh->positions.end(),
                                      [&](glm::vec3 q) { return glm::length(q + p) < 1e-5f; });
    EXPECT_TRUE(mirrored) << p.x << "," << p.y << "," << p.z;
  }
}

TEST(CageValidation, NamesTheProblem) {
  Cage outOfRange = unitCube();
  outOfRange.faceVertices[5] = 42;
  EXPECT_NE(refineUniformly(outOfRange, 1).error().message.find("vertex 42"), std::string::npos);

  Cage nonManifold = unitCube();
  // A third face on edge (0, 1): a fin hanging off the bottom front edge.
  nonManifold.positions.push_back({0, -2, 1});
  nonManifold.faceSizes.push_back(3);
  nonManifold.faceVertices.insert(nonManifold.faceVertices.end(), {1, 0, 8});
  const auto error = validateCage(nonManifold);
  ASSERT_FALSE(error.has_value());
  EXPECT_NE(error.error().message.find("edge (0, 1)"), std::string::npos) << error.error().message;

  Cage flat = unitCube();
  flat.positions.push_back({2, 2, 2});
  flat.positions.push_back({3, 3, 3});
  flat.positions.push_back({4, 4, 4});
  flat.faceSizes.push_back(3);
  flat.faceVertices.insert(flat.faceVertices.end(), {8, 9, 10});
  EXPECT_NE(validateCage(flat).error().message.find("zero area"), std::string::npos);

  EXPECT_FALSE(refineUniformly(unitCube(), 0).has_value());
}

}  // namespace
}  // namespace mane::subdiv
