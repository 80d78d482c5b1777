// The node hierarchy: world matrices are parent × local whatever order the nodes are listed in,
// T·R·S composes as glTF defines, matrix nodes keep their matrix, and bad hierarchies are
// rejected naming the node.

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/skeleton.hpp"

namespace mane::physics {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr float kPi = std::numbers::pi_v<float>;

void expectMatrixNear(const glm::mat4& actual, const glm::mat4& expected, float tolerance) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(actual[c][r], expected[c][r], tolerance) << "column " << c << " row " << r;
  }
}

TEST(Skeleton, LocalMatrixIsTranslationTimesRotationTimesScale) {
  NodeTransform transform;
  transform.translation = {1.0f, 2.0f, 3.0f};
  transform.rotation = glm::angleAxis(0.5f * kPi, glm::vec3(0.0f, 0.0f, 1.0f));
  transform.scale = {2.0f, 3.0f, 4.0f};
  // (1, 0, 0) is scaled to (2, 0, 0), turned to (0, 2, 0), moved to (1, 4, 3).
  const glm::vec3 moved(localMatrix(transform) * glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  EXPECT_NEAR(moved.x, 1.0f, 1e-6f);
  EXPECT_NEAR(moved.y, 4.0f, 1e-6f);
  EXPECT_NEAR(moved.z, 3.0f, 1e-6f);
}

TEST(Skeleton, WorldMatricesComposeParentsFirstWhateverTheListingOrder) {
  // Listed child first: node 0's parent is node 2, node 2's parent is node 1 (the root).
  std::vector<SkeletonNode> nodes(3);
  nodes[0].parent = 2;
  nodes[0].rest.translation = {0.0f, 0.0f, 1.0f};
  nodes[1].rest.translation = {1.0f, 0.0f, 0.0f};
  nodes[1].rest.rotation = glm::angleAxis(0.5f * kPi, glm::vec3(0.0f, 1.0f, 0.0f));
  nodes[2].parent = 1;
  nodes[2].rest.scale = glm::vec3(2.0f);
  nodes[2].fixedMatrix = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 5.0f, 0.0f));  // used instead of TRS
  auto skeleton = Skeleton::create(nodes);
  ASSERT_TRUE(skeleton) << skeleton.error().message;
  EXPECT_THAT(skeleton->parentFirstOrder(), ElementsAre(1, 2, 0));
  auto world = skeleton->worldMatrices(skeleton->restPose());
  ASSERT_TRUE(world);
  const glm::mat4 w1 = localMatrix(nodes[1].rest);
  const glm::mat4 w2 = w1 * *nodes[2].fixedMatrix;
  const glm::mat4 w0 = w2 * localMatrix(nodes[0].rest);
  expectMatrixNear((*world)[1], w1, 0.0f);
  expectMatrixNear((*world)[2], w2, 0.0f);
  expectMatrixNear((*world)[0], w0, 0.0f);
  // By hand: node 0's origin is (0, 5, 1) in the root's frame; turning 90° about y takes
  // (x, y, z) to (z, y, −x), so (1, 5, 0), plus the root's translation: (2, 5, 0).
  EXPECT_NEAR((*world)[0][3].x, 2.0f, 1e-6f);
  EXPECT_NEAR((*world)[0][3].y, 5.0f, 1e-6f);
  EXPECT_NEAR((*world)[0][3].z, 0.0f, 1e-6f);
}

TEST(Skeleton, BadHierarchiesAreRejectedNamingTheNode) {
  std::vector<SkeletonNode> cycle(3);
  cycle[1].parent = 2;
  cycle[2].parent = 1;
  cycle[2].name = "Elbow";
  auto result = Skeleton::create(cycle);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("cycle"));
  EXPECT_THAT(result.error().message, HasSubstr("node 1"));

  std::vector<SkeletonNode> outOfRange(2);
  outOfRange[1].parent = 5;
  result = Skeleton::create(outOfRange);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("node 1 has parent 5"));

  std::vector<SkeletonNode> nan(1);
  nan[0].name = "Hip";
  nan[0].rest.translation.y = std::numeric_limits<float>::quiet_NaN();
  result = Skeleton::create(nan);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("node 0 ('Hip')"));

  auto fine = Skeleton::create(std::vector<SkeletonNode>(2));
  ASSERT_TRUE(fine);
  std::vector<glm::mat4> world(1);
  EXPECT_FALSE(fine->worldMatrices(fine->restPose().local, world));
}

}  // namespace
}  // namespace mane::physics
