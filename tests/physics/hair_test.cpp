// The hair system: input validation with clear messages, roots following the head, and
// detection of non-finite state during simulation, reported with the strand index; the groom
// generator. The strand kernels are tested in hair_kernels_test.cpp.

#include <cmath>
#include <limits>
#include <string>
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

Strands threeStraightStrands() {
  Strands strands;
  for (int s = 0; s < 3; ++s) {
    std::vector<glm::vec3> strand;
    for (int i = 0; i < 6; ++i) strand.push_back({0.05f * static_cast<float>(s), -0.05f * static_cast<float>(i), 0.0f});
    strands.push_back(strand);
  }
  return strands;
}

std::string createError(const Strands& strands) {
  auto hair = HairSystem::create(strands, SolverSettings{});
  EXPECT_FALSE(hair);
  return hair ? std::string() : hair.error().message;
}

TEST(HairInput, EmptyGroomIsRejected) {
  EXPECT_THAT(createError({}), HasSubstr("empty"));
}

TEST(HairInput, StrandWithOnePointIsRejectedByIndex) {
  Strands strands = threeStraightStrands();
  strands[1].resize(1);
  const std::string message = createError(strands);
  EXPECT_THAT(message, HasSubstr("strand 1"));
  EXPECT_THAT(message, HasSubstr("at least 2"));
}

TEST(HairInput, NaNAndInfinityAreRejectedWithStrandAndParticle) {
  Strands strands = threeStraightStrands();
  strands[2][3].y = std::numeric_limits<float>::quiet_NaN();
  std::string message = createError(strands);
  EXPECT_THAT(message, HasSubstr("strand 2, particle 3"));
  EXPECT_THAT(message, HasSubstr("not finite"));

  strands = threeStraightStrands();
  strands[0][5].z = -std::numeric_limits<float>::infinity();
  message = createError(strands);
  EXPECT_THAT(message, HasSubstr("strand 0, particle 5"));
}

TEST(HairInput, ZeroLengthSegmentIsRejectedWithStrandAndParticle) {
  Strands strands = threeStraightStrands();
  strands[1][4] = strands[1][3];
  const std::string message = createError(strands);
  EXPECT_THAT(message, HasSubstr("strand 1, particle 4"));
  EXPECT_THAT(message, HasSubstr("zero-length"));
}

TEST(HairInput, BadSettingsAndTransformsAreRejected) {
  SolverSettings settings;
  settings.constraintIterations = 0;
  auto hair = HairSystem::create(threeStraightStrands(), settings);
  ASSERT_FALSE(hair);
  EXPECT_THAT(hair.error().message, HasSubstr("constraintIterations"));

  auto good = HairSystem::create(threeStraightStrands(), SolverSettings{});
  ASSERT_TRUE(good);
  glm::mat4 broken(1.0f);
  broken[3][1] = std::numeric_limits<float>::quiet_NaN();
  auto set = good->setHeadTransform(broken);
  ASSERT_FALSE(set);
  EXPECT_THAT(set.error().message, HasSubstr("column 3, row 1"));
  auto advanced = good->advance(-1.0, 1);
  ASSERT_FALSE(advanced);
  EXPECT_THAT(advanced.error().message, HasSubstr("frame duration"));
  EXPECT_TRUE(good->advance(1.0 / 60.0, 1));  // the rejected transform changed nothing
}

TEST(HairSystem, RootsFollowTheHeadTransform) {
  // After a frame the roots sit exactly where the head transform puts their rest positions
  // (the last fixed step of a 1/60 s frame at 1/120 s ends on the frame's end), up to float
  // rounding of the interpolation (1e-6 m).
  auto hair = HairSystem::create(threeStraightStrands(), SolverSettings{});
  ASSERT_TRUE(hair);
  const glm::mat4 head =
      glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, 0.2f, 0.3f)), 0.3f, glm::vec3(0.0f, 0.0f, 1.0f));
  ASSERT_TRUE(hair->setHeadTransform(head));
  ASSERT_TRUE(hair->advance(1.0 / 60.0, 1));
  for (std::size_t s = 0; s < hair->strandCount(); ++s) {
    const glm::vec3 expected = glm::vec3(head * glm::vec4(hair->strands()[s].rootLocal, 1.0f));
    const glm::vec3 root = hair->strandPositions(s).front();
    for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(root[axis], expected[axis], 1e-6f);
  }
  EXPECT_EQ(hair->stepCount(), 2u);
}

TEST(HairSystem, HangingStrandStaysAtRestLengthAndBelowItsRoot) {
  // A strand grown straight down is already in equilibrium: after 1 s it must still hang
  // straight (x, z unchanged to 1e-6 m) with every segment at its rest length (1e-4 relative:
  // the residual of 4 sweeps against one step of gravity, g·h² ≈ 7e-4 m, spread over 5 links).
  auto hair = HairSystem::create(threeStraightStrands(), SolverSettings{});
  ASSERT_TRUE(hair);
  for (int frame = 0; frame < 60; ++frame) ASSERT_TRUE(hair->advance(1.0 / 60.0, 1));
  for (std::size_t s = 0; s < hair->strandCount(); ++s) {
    const auto x = hair->strandPositions(s);
    for (std::size_t i = 1; i < x.size(); ++i) {
      EXPECT_NEAR(x[i].x, x[0].x, 1e-6f);
      EXPECT_NEAR(x[i].z, 0.0f, 1e-6f);
      EXPECT_LE(x[i].y, x[i - 1].y);
      EXPECT_NEAR(x[i - 1].y - x[i].y, 0.05f, 0.05f * 1e-4f) << "strand " << s << " particle " << i;
    }
  }
}

TEST(HairSystem, NonFiniteStateIsDetectedAndReportedWithTheStrand) {
  // Strand 0 is rooted at the head origin, strand 1 at 0.1 m. A corrupted (finite, but absurd)
  // head transform scales by 1e21: strand 0's root stays at the origin, strand 1's root jumps
  // 1e20 m, and the squared segment length overflows float: its particles become NaN. The
  // advance must say so, name strand 1, and stop instead of carrying NaN forward.
  Strands strands(2);
  for (int i = 0; i < 5; ++i) {
    strands[0].push_back({0.0f, -0.05f * static_cast<float>(i), 0.0f});
    strands[1].push_back({0.1f, -0.05f * static_cast<float>(i), 0.0f});
  }
  auto hair = HairSystem::create(strands, SolverSettings{});
  ASSERT_TRUE(hair);
  ASSERT_TRUE(hair->advance(1.0 / 60.0, 2));
  ASSERT_TRUE(hair->setHeadTransform(glm::scale(glm::mat4(1.0f), glm::vec3(1e21f))));
  auto result = hair->advance(1.0 / 60.0, 2);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("strand 1"));
  EXPECT_THAT(result.error().message, HasSubstr("non-finite"));
  ASSERT_TRUE(hair->fault().has_value());
  EXPECT_EQ(hair->fault()->strand, 1u);
  EXPECT_EQ(hair->fault()->step, 3u);  // the first step of the second frame
  for (const glm::vec3& p : hair->strandPositions(0)) EXPECT_TRUE(std::isfinite(p.y));

  // Stopped: later frames report the same fault and do not step.
  const auto steps = hair->stepCount();
  auto again = hair->advance(1.0 / 60.0, 2);
  ASSERT_FALSE(again);
  EXPECT_THAT(again.error().message, HasSubstr("strand 1"));
  EXPECT_EQ(hair->stepCount(), steps);

  // A teleport resets the groom to rest under a sane transform and clears the fault.
  ASSERT_TRUE(hair->teleport(glm::mat4(1.0f)));
  EXPECT_FALSE(hair->fault().has_value());
  EXPECT_TRUE(hair->advance(1.0 / 60.0, 2));
}


TEST(GroomGenerator, SameSeedSameGroomAndRootsOnTheScalpCap) {
  GroomSettings settings;
  settings.strandCount = 50;
  settings.particlesPerStrand = 10;
  settings.curlRadius = 0.01f;
  auto a = generateGroom(settings);
  auto b = generateGroom(settings);
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->size(), 50u);
  for (std::size_t s = 0; s < a->size(); ++s) {
    ASSERT_EQ((*a)[s].size(), 10u);
    for (std::size_t i = 0; i < 10; ++i) ASSERT_EQ((*a)[s][i], (*b)[s][i]);
    // Root on the sphere (radius 0.1 m, 1e-6 m for the float normalisation) within the cap.
    const glm::vec3 root = (*a)[s][0];
    EXPECT_NEAR(std::sqrt(root.x * root.x + root.y * root.y + root.z * root.z), 0.1f, 1e-6f);
    EXPECT_GE(root.y / 0.1f, settings.capMinNormalY - 1e-5f);
  }
  settings.seed = 2;
  auto c = generateGroom(settings);
  ASSERT_TRUE(c);
  EXPECT_NE((*a)[0][0], (*c)[0][0]);
  // And the result is a valid hair system input.
  EXPECT_TRUE(HairSystem::create(*a, SolverSettings{}));
}

TEST(GroomGenerator, SplitMix64MatchesTheReferenceSequence) {
  // First outputs of Vigna's splitmix64.c for seed 0 (also the seeding sequence quoted for
  // xoshiro): 0xE220A8397B1DCDAF, 0x6E789E6AA1B965F4, 0x06C45D188009454F.
  SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
  EXPECT_EQ(rng.next(), 0x06C45D188009454Full);
}

TEST(GroomGenerator, BadSettingsNameTheField) {
  GroomSettings settings;
  settings.particlesPerStrand = 1;
  auto groom = generateGroom(settings);
  ASSERT_FALSE(groom);
  EXPECT_THAT(groom.error().message, HasSubstr("particlesPerStrand"));
}

}  // namespace
}  // namespace mane::physics
