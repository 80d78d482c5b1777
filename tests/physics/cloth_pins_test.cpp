// Cloth pins that follow per-pin targets (Cloth::setPinTargets), as a host's skinned vertices
// would: pins end the frame on their targets, the thread count does not change the result,
// targets carried by a rigid body reproduce the body-transform simulation bit for bit, and bad
// targets are rejected by pin.

#include <cmath>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/cloth.hpp"
#include "tests/support/cloth_grid.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;
using Pins = std::vector<std::uint32_t>;

using Grid = mane::testing::ClothGrid;
using mane::testing::makeClothGrid;

glm::vec3 transformed(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

TEST(ClothPins, PinnedVerticesAreListedOnceInFirstAppearanceOrder) {
  const Grid grid = makeClothGrid(6, 0.4f);
  auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{5, 0, 5, 2}, {});
  ASSERT_TRUE(cloth) << cloth.error().message;
  EXPECT_EQ(std::vector<std::uint32_t>(cloth->pinnedVertices().begin(), cloth->pinnedVertices().end()),
            (Pins{5, 0, 2}));
  EXPECT_FALSE(cloth->pinsFollowTargets());
}

TEST(ClothPins, PinsEndTheFrameExactlyOnTheirTargets) {
  const Grid grid = makeClothGrid(8, 0.4f);
  auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 7, 3}, {});
  ASSERT_TRUE(cloth);
  // Targets that no rigid motion of the pins gives (the pins spread apart and twist). Pin 1
  // (vertex 7, x = 0.4 m) goes to x = 3e-9 m: 0.4 + (3e-9 − 0.4) rounds to 0 in float, so only
  // placing the pin on the target itself lands it there.
  const std::vector<glm::vec3> targets = {{-0.05f, 0.02f, 0.01f}, {3e-9f, 0.03f, -0.04f}, {0.2f, 0.08f, 0.05f}};
  ASSERT_TRUE(cloth->setPinTargets(targets));
  EXPECT_TRUE(cloth->pinsFollowTargets());
  // 1/60 s is two whole 1/120 s steps: the last ends on the frame's end, where the pin is placed
  // on its target itself, not on from + (target − from)·1 (which may round off it).
  ASSERT_TRUE(cloth->advance(1.0 / 60.0));
  for (std::size_t p = 0; p < targets.size(); ++p)
    EXPECT_EQ(cloth->particles().positions[cloth->pinnedVertices()[p]], targets[p]) << "pin " << p;
  // The body transform no longer moves the pins.
  ASSERT_TRUE(cloth->setBodyTransform(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f))));
  ASSERT_TRUE(cloth->advance(1.0 / 60.0));
  for (std::size_t p = 0; p < targets.size(); ++p)
    EXPECT_EQ(cloth->particles().positions[cloth->pinnedVertices()[p]], targets[p]) << "pin " << p;
}

TEST(ClothPins, ThreadCountDoesNotChangeTheResult) {
  // 128² = 16,384 vertices: enough for several workers (Cloth::advance takes one per 4,096).
  const Grid grid = makeClothGrid(128, 0.6f);
  const Pins pins = {0, 32, 64, 96, 127};
  std::uint64_t hashes[3];
  const unsigned threads[3] = {1, 2, 4};
  for (int run = 0; run < 3; ++run) {
    auto cloth = Cloth::create(grid.positions, grid.triangles, pins, {});
    ASSERT_TRUE(cloth);
    std::vector<glm::vec3> targets(pins.size());
    for (int frame = 1; frame <= 10; ++frame) {
      // Each pin bobs with its own phase: a deforming edge, as on a skinned shoulder.
      for (std::size_t p = 0; p < pins.size(); ++p)
        targets[p] = grid.positions[pins[p]] + glm::vec3(0.0f, 0.03f * std::sin(0.4f * float(frame) + float(p)), 0.0f);
      ASSERT_TRUE(cloth->setPinTargets(targets));
      ASSERT_TRUE(cloth->advance(1.0 / 60.0, threads[run]));
    }
    hashes[run] = cloth->stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

TEST(ClothPins, TargetsCarriedByARigidBodyReproduceTheBodyTransformBitForBit) {
  // The oracle: targets computed as body · rest (the same product the cloth forms for its pins)
  // give each pin the same straight path as setBodyTransform: both start the frame on the last
  // placement (a target-following pin ends every frame exactly on its target) and blend to the
  // new one with the same arithmetic. Colliders follow the body in both. So the states are equal
  // bit for bit, as long as every frame ends on a whole fixed step (1/60 s here): otherwise the
  // body-carried pin restarts from the body's last placement, the target-following one from
  // where its last step left it.
  const Grid grid = makeClothGrid(10, 0.5f);
  const Pins pins = {0, 4, 9};
  ClothSettings settings;
  auto carried = Cloth::create(grid.positions, grid.triangles, pins, settings);
  auto targeted = Cloth::create(grid.positions, grid.triangles, pins, settings);
  ASSERT_TRUE(carried && targeted);
  ColliderSet ball;
  ball.spheres = {{{0.25f, -0.35f, 0.05f}, 0.12f}};
  ball.friction = 0.2f;
  ASSERT_TRUE(carried->setColliders(ball));
  ASSERT_TRUE(targeted->setColliders(ball));
  std::vector<glm::vec3> targets(pins.size());
  for (int frame = 1; frame <= 90; ++frame) {
    const float t = float(frame) / 60.0f;
    glm::mat4 body = glm::translate(glm::mat4(1.0f), glm::vec3(0.1f * std::sin(2.0f * t), 0.0f, 0.05f * t));
    body = glm::rotate(body, 0.6f * std::sin(1.5f * t), glm::normalize(glm::vec3(0.1f, 1.0f, 0.2f)));
    ASSERT_TRUE(carried->setBodyTransform(body));
    ASSERT_TRUE(targeted->setBodyTransform(body));  // its colliders still follow the body
    for (std::size_t p = 0; p < pins.size(); ++p) targets[p] = transformed(body, grid.positions[pins[p]]);
    ASSERT_TRUE(targeted->setPinTargets(targets));
    ASSERT_TRUE(carried->advance(1.0 / 60.0));
    ASSERT_TRUE(targeted->advance(1.0 / 60.0));
  }
  EXPECT_EQ(carried->stateHash(), targeted->stateHash());
}

TEST(ClothPins, BadTargetsAreRejectedByPinAndChangeNothing) {
  const Grid grid = makeClothGrid(4, 0.3f);
  auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 3}, {});
  ASSERT_TRUE(cloth);
  auto result = cloth->setPinTargets(std::vector<glm::vec3>{glm::vec3(0.0f)});
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("1 positions for 2 pinned vertices"));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  result = cloth->setPinTargets(std::vector<glm::vec3>{glm::vec3(0.0f), glm::vec3(0.0f, nan, 0.0f)});
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("pin target 1 (vertex 3)"));
  EXPECT_FALSE(cloth->pinsFollowTargets());
}

}  // namespace
}  // namespace mane::physics
