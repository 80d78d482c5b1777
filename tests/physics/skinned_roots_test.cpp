// Roots on a skinned mesh (HairSystem::setRootTargets): roots reach their targets, targets that
// reproduce a rigid head reproduce the rigid simulation, normals turn the rest shape, bad input
// is rejected by strand.

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;
using Strands = std::vector<std::vector<glm::vec3>>;

// A straight strand of `count` points from `root` along `direction`, 1 cm apart.
std::vector<glm::vec3> straightStrand(const glm::vec3& root, const glm::vec3& direction, int count) {
  std::vector<glm::vec3> points;
  for (int i = 0; i < count; ++i) points.push_back(root + direction * (0.01f * static_cast<float>(i)));
  return points;
}

glm::vec3 transformed(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

TEST(SkinnedRoots, RootsEndTheFrameOnTheirTargets) {
  const Strands strands = {straightStrand({0.0f, 0.1f, 0.0f}, {0.0f, 1.0f, 0.0f}, 6),
                           straightStrand({0.05f, 0.08f, 0.0f}, {1.0f, 0.0f, 0.0f}, 6)};
  auto hair = HairSystem::create(strands, {});
  ASSERT_TRUE(hair);
  EXPECT_FALSE(hair->rootsSkinned());
  const std::vector<glm::vec3> targets = {{0.01f, 0.12f, -0.02f}, {0.07f, 0.05f, 0.01f}};
  const std::vector<glm::vec3> normals = {{0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  ASSERT_TRUE(hair->setRootTargets(targets, normals));
  EXPECT_TRUE(hair->rootsSkinned());
  ASSERT_TRUE(hair->advance(1.0 / 60.0));
  // x = from + (target − from)·1: at most a rounding step (1e-7 m at these magnitudes) away.
  for (std::size_t s = 0; s < strands.size(); ++s) {
    const glm::vec3 root = hair->strandPositions(s)[0];
    EXPECT_LT(glm::length(root - targets[s]), 1e-7f) << "strand " << s;
  }
  // The head transform no longer moves them; teleport hands them back to the head.
  ASSERT_TRUE(hair->setHeadTransform(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f))));
  ASSERT_TRUE(hair->advance(1.0 / 60.0));
  EXPECT_LT(glm::length(hair->strandPositions(0)[0] - targets[0]), 1e-7f);
  ASSERT_TRUE(hair->teleport(glm::mat4(1.0f)));
  EXPECT_FALSE(hair->rootsSkinned());
  EXPECT_EQ(hair->strandPositions(1)[0], strands[1][0]);
}

TEST(SkinnedRoots, TargetsThatFollowARigidHeadGiveTheRigidSimulation) {
  // The oracle: roots and normals carried by a turning, moving head are exactly what the rigid
  // head transform does, so both systems simulate the same motion. Shape constraints (the normal
  // turns their frame) and gravity on; the two differ only by rounding in the root placement.
  GroomSettings groom;
  groom.seed = 4;
  groom.strandCount = 24;
  groom.particlesPerStrand = 12;
  groom.strandLength = 0.2f;
  groom.curlRadius = 0.004f;
  const auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  SolverSettings settings;
  settings.shapeStiffness = 0.6f;
  auto rigid = HairSystem::create(*strands, settings);
  auto skinned = HairSystem::create(*strands, settings);
  ASSERT_TRUE(rigid && skinned);
  std::vector<glm::vec3> targets(strands->size()), normals(strands->size());
  for (int frame = 1; frame <= 60; ++frame) {
    const float t = static_cast<float>(frame) / 60.0f;
    glm::mat4 head = glm::translate(glm::mat4(1.0f), glm::vec3(0.05f * std::sin(3.0f * t), 0.0f, 0.0f));
    head = glm::rotate(head, 0.8f * std::sin(2.0f * t), glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f)));
    ASSERT_TRUE(rigid->setHeadTransform(head));
    ASSERT_TRUE(skinned->setHeadTransform(head));
    for (std::size_t s = 0; s < strands->size(); ++s) {
      targets[s] = transformed(head, (*strands)[s][0]);
      normals[s] = glm::mat3(head) * skinned->rootRestNormals()[s];
    }
    ASSERT_TRUE(skinned->setRootTargets(targets, normals));
    ASSERT_TRUE(rigid->advance(1.0 / 60.0));
    ASSERT_TRUE(skinned->advance(1.0 / 60.0));
  }
  float worst = 0.0f;
  for (std::size_t i = 0; i < rigid->particles().size(); ++i)
    worst = std::max(worst, glm::length(rigid->particles().positions[i] - skinned->particles().positions[i]));
  // Rounding differences of ~1e-7 m per step, amplified a little by the constraints.
  EXPECT_LT(worst, 1e-4f);
}

TEST(SkinnedRoots, TurningTheNormalTurnsTheRestShape) {
  // A stiff strand (shape stiffness 1, no gravity) growing along +y; its root normal turns to +x
  // while the root stays put: the strand settles along +x, the rest shape turned by the arc
  // from +y to +x (a rotation of −90° about z).
  const Strands strands = {straightStrand({0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 8)};
  SolverSettings settings;
  settings.shapeStiffness = 1.0f;
  settings.gravity = glm::vec3(0.0f);
  settings.damping = 0.2f;
  auto hair = HairSystem::create(strands, settings);
  ASSERT_TRUE(hair);
  EXPECT_NEAR(hair->rootRestNormals()[0].y, 1.0f, 1e-7f);
  const std::vector<glm::vec3> root = {glm::vec3(0.0f)}, normal = {glm::vec3(1.0f, 0.0f, 0.0f)};
  for (int frame = 0; frame < 120; ++frame) {
    ASSERT_TRUE(hair->setRootTargets(root, normal));
    ASSERT_TRUE(hair->advance(1.0 / 60.0));
  }
  const auto x = hair->strandPositions(0);
  for (std::size_t i = 0; i < x.size(); ++i)
    EXPECT_LT(glm::length(x[i] - glm::vec3(0.01f * static_cast<float>(i), 0.0f, 0.0f)), 1e-4f) << "particle " << i;
}

TEST(SkinnedRoots, BadTargetsAreRejectedByStrandAndChangeNothing) {
  const Strands strands = {straightStrand({0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 4),
                           straightStrand({0.1f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 4)};
  auto hair = HairSystem::create(strands, {});
  ASSERT_TRUE(hair);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<glm::vec3> one = {glm::vec3(0.0f)}, two = {glm::vec3(0.0f), glm::vec3(0.1f, 0.0f, 0.0f)};
  auto result = hair->setRootTargets(one, std::vector<glm::vec3>{up});
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("1 positions for 2 strands"));
  result = hair->setRootTargets(std::vector<glm::vec3>{glm::vec3(0.0f), glm::vec3(nan, 0.0f, 0.0f)},
                                std::vector<glm::vec3>{up, up});
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("strand 1"));
  result = hair->setRootTargets(two, std::vector<glm::vec3>{up, glm::vec3(0.0f)});
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("strand 1"));
  EXPECT_FALSE(hair->rootsSkinned());
  result = hair->setRootRestNormals(std::vector<glm::vec3>{up});
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("1 normals for 2 strands"));
}

}  // namespace
}  // namespace mane::physics
