// Fur that moves (scenes/fur_dynamics.hpp): simulated guides on a sphere turned into per-vertex
// leans, checked against what gravity must do to short strands standing out of a ball:
//  - without gravity and motion the guides stay at rest: every lean is zero;
//  - under gravity, fur on the equator (normal horizontal) leans down along the surface, fur on
//    the poles (gravity along the strand) does not lean sideways;
//  - leans are tangent to the surface and never longer than kMaxFurLean;
//  - the state is the same for 1 and 2 threads.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scenes/fur_dynamics.hpp"
#include "scenes/procedural.hpp"

namespace mane::scenes {
namespace {

constexpr float kThickness = 0.01f;  // 1 cm of fur on a 10 cm ball

FurDynamicsSettings settings(glm::vec3 gravity) {
  FurDynamicsSettings result{.guides = 400, .thickness = kThickness};
  result.solver.gravity = gravity;
  result.solver.shapeStiffness = 0.5f;
  result.solver.damping = 0.05f;
  return result;
}

TEST(FurDynamics, FurAtRestDoesNotLean) {
  const Mesh ball = makeSphere(16, 32, 1.0f);
  auto fur = FurDynamics::create(ball, 0.1f, settings(glm::vec3(0.0f)), glm::mat4(1.0f));
  ASSERT_TRUE(fur.has_value()) << fur.error().message;
  ASSERT_TRUE(fur->advance(glm::mat4(1.0f), 0.5, 1).has_value());
  ASSERT_EQ(fur->leans().size(), ball.positions.size());
  for (const glm::vec3& lean : fur->leans()) ASSERT_LT(glm::length(lean), 1e-3f);
}

TEST(FurDynamics, GravityCombsTheSidesDownAndLeavesThePolesStanding) {
  const Mesh ball = makeSphere(16, 32, 1.0f);
  auto fur = FurDynamics::create(ball, 0.1f, settings(glm::vec3(0.0f, -9.81f, 0.0f)), glm::mat4(1.0f));
  ASSERT_TRUE(fur.has_value()) << fur.error().message;
  ASSERT_TRUE(fur->advance(glm::mat4(1.0f), 1.0, 1).has_value());
  std::size_t equator = 0, poles = 0;
  for (std::size_t v = 0; v < ball.positions.size(); ++v) {
    const glm::vec3 n = glm::normalize(ball.normals[v]);
    const glm::vec3 lean = fur->leans()[v];
    EXPECT_NEAR(glm::dot(lean, n), 0.0f, 1e-4f) << "vertex " << v << ": leans are tangent";
    EXPECT_LE(glm::length(lean), kMaxFurLean + 1e-5f);
    if (std::abs(n.y) < 0.2f) {
      EXPECT_LT(lean.y, -0.05f) << "vertex " << v << " on the equator leans down";
      ++equator;
    }
    if (std::abs(n.y) > 0.999f) {
      EXPECT_LT(glm::length(lean), 0.05f) << "vertex " << v << " at a pole stands";
      ++poles;
    }
  }
  EXPECT_GT(equator, 20u);
  EXPECT_GT(poles, 0u);
}

TEST(FurDynamics, TheStateDoesNotDependOnTheThreadCount) {
  const Mesh ball = makeSphere(16, 32, 1.0f);
  std::array<std::uint64_t, 2> hashes{};
  for (unsigned threads = 1; threads <= 2; ++threads) {
    auto fur = FurDynamics::create(ball, 0.1f, settings(glm::vec3(0.0f, -9.81f, 0.0f)), glm::mat4(1.0f));
    ASSERT_TRUE(fur.has_value());
    for (int frame = 0; frame < 30; ++frame) {
      const glm::mat4 body = glm::rotate(glm::mat4(1.0f), 0.05f * float(frame), glm::vec3(0, 1, 0));
      ASSERT_TRUE(fur->advance(body, 1.0 / 60.0, threads).has_value());
    }
    hashes[threads - 1] = fur->guides().stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

TEST(FurDynamics, RefusesMeshesWithoutNormalsAndNoGuides) {
  Mesh ball = makeSphere(8, 16, 1.0f);
  EXPECT_FALSE(FurDynamics::create(ball, 0.1f, {.guides = 0}, glm::mat4(1.0f)).has_value());
  ball.normals.clear();
  auto refused = FurDynamics::create(ball, 0.1f, {}, glm::mat4(1.0f));
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("normals"), std::string::npos);
}

}  // namespace
}  // namespace mane::scenes
