// Wind in the hair step (HairSystem::setWind): the drag law of wind.hpp applied to each
// non-root particle's segment inside the Verlet kick.
//
// Oracles: the equilibrium angle of a two-particle strand in a steady cross wind (derived
// below), no effect at all from wind along a straight strand, gusts that change the state (and a
// seed that reproduces it), and thread-count independence.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/wind.hpp"

namespace mane::physics {
namespace {

using Strands = std::vector<std::vector<glm::vec3>>;

TEST(WindHair, NoWindByDefaultAndBadWindIsRejected) {
  auto hair = HairSystem::create(Strands{{{0, 0, 0}, {0, -0.1f, 0}}}, SolverSettings{});
  ASSERT_TRUE(hair);
  EXPECT_FALSE(hair->wind());
  auto refused = hair->setWind({.speed = -1.0f});
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, ::testing::HasSubstr("speed"));
  EXPECT_FALSE(hair->wind());
  ASSERT_TRUE(hair->setWind({.speed = 2.0f}));
  ASSERT_TRUE(hair->wind());
  EXPECT_EQ(hair->wind()->speed, 2.0f);
  hair->clearWind();
  EXPECT_FALSE(hair->wind());
}

TEST(WindHair, SteadyCrossWindTiltsATwoParticleStrandToTheDragGravityBalance) {
  // Reference: a strand of two particles (root fixed, tip at distance L) in a horizontal wind of
  // speed W. At rest (v = 0) at angle θ from the vertical the segment's axis is
  // a = (sin θ, −cos θ, 0). The drag law is a = k·(w − v)⊥ = k·(w − (w·a)·a); removing the axial
  // part does not change the component along the swing direction n = (cos θ, sin θ, 0), which is
  // k·W·cos θ. Gravity's component along n is −g·sin θ; the distance constraint absorbs the
  // axial parts. Equilibrium: k·W·cos θ = g·sin θ, so tan θ = k·w⊥/g with w⊥ = W, the wind
  // across the strand's rest direction. With k = 2 /s, W = 3 m/s: θ = atan(6/9.81) = 0.5489 rad.
  // Tolerance 1e-4 rad: after 20 s the swing has decayed (damping 1 %/step and the drag itself,
  // time constant 1/k = 0.5 s) far below that; the fixed point of the discrete step is exact up
  // to float rounding (≈ 1e-7).
  constexpr float kDrag = 2.0f, kWind = 3.0f, kLength = 0.1f;
  SolverSettings settings;
  auto hair = HairSystem::create(Strands{{{0, 0, 0}, {0, -kLength, 0}}}, settings);
  ASSERT_TRUE(hair);
  ASSERT_TRUE(hair->setWind({.direction = {1, 0, 0}, .speed = kWind, .dragPerSecond = kDrag}));
  for (int frame = 0; frame < 20 * 60; ++frame) ASSERT_TRUE(hair->advance(1.0 / 60.0, 1));
  const glm::vec3 tip = hair->strandPositions(0)[1];
  const double angle = std::atan2(static_cast<double>(tip.x), -static_cast<double>(tip.y));
  const double expected = std::atan(static_cast<double>(kDrag) * kWind / -static_cast<double>(settings.gravity.y));
  std::printf("cross wind: θ = %.6f rad, expected atan(kW/g) = %.6f rad\n", angle, expected);
  EXPECT_NEAR(angle, expected, 1e-4);
  EXPECT_NEAR(std::sqrt(tip.x * tip.x + tip.y * tip.y + tip.z * tip.z), kLength, 1e-6f);
  EXPECT_EQ(tip.z, 0.0f);  // nothing pushes out of the plane of wind and gravity
}

TEST(WindHair, WindAlongAStraightVerticalStrandDoesNothing) {
  // Up or down a vertical hanging strand the wind has no component across any segment: the
  // drag is exactly zero and the state matches the windless run bit for bit (tolerance 0).
  Strands strands;
  for (int s = 0; s < 3; ++s) {
    std::vector<glm::vec3> strand;
    for (int i = 0; i < 8; ++i) strand.push_back({0.05f * static_cast<float>(s), -0.02f * static_cast<float>(i), 0.0f});
    strands.push_back(strand);
  }
  const auto run = [&](bool windy, glm::vec3 direction) {
    auto hair = HairSystem::create(strands, SolverSettings{});
    EXPECT_TRUE(hair);
    if (windy) {
      EXPECT_TRUE(hair->setWind({.direction = direction, .speed = 5.0f, .gustAmplitude = 2.0f}));
    }
    for (int frame = 0; frame < 120; ++frame) EXPECT_TRUE(hair->advance(1.0 / 60.0, 1));
    return hair->stateHash();
  };
  const std::uint64_t still = run(false, {});
  EXPECT_EQ(run(true, {0, 1, 0}), still);
  EXPECT_EQ(run(true, {0, -1, 0}), still);
  EXPECT_NE(run(true, {1, 0, 0}), still);  // control: across the strand it does act
}

std::vector<std::vector<glm::vec3>> curlyGroom() {
  GroomSettings groom;
  groom.seed = 77;
  groom.strandCount = 301;  // 7·43: uneven ranges for 2, 3 and 4 workers
  groom.particlesPerStrand = 16;
  groom.strandLength = 0.3f;
  groom.curlRadius = 0.006f;
  groom.curlAnglePerSegment = 0.8f;
  auto strands = generateGroom(groom);
  EXPECT_TRUE(strands);
  return *strands;
}

std::uint64_t windyRun(const std::vector<std::vector<glm::vec3>>& strands, const WindSettings* wind, unsigned threads) {
  auto hair = HairSystem::create(strands, SolverSettings{});
  EXPECT_TRUE(hair);
  if (wind) {
    EXPECT_TRUE(hair->setWind(*wind));
  }
  const double dts[] = {1.0 / 60.0, 1.0 / 75.0, 1.0 / 144.0};
  double t = 0.0;
  for (int frame = 0; frame < 90; ++frame) {
    t += dts[frame % 3];
    EXPECT_TRUE(hair->setHeadTransform(glm::translate(glm::mat4(1.0f), glm::vec3(0.05f * static_cast<float>(t), 0, 0))));
    EXPECT_TRUE(hair->advance(dts[frame % 3], threads));
  }
  return hair->stateHash();
}

TEST(WindHair, GustsChangeTheStateAndTheSeedReproducesIt) {
  const auto strands = curlyGroom();
  const WindSettings steady{.direction = {1, 0, 0.5f}, .speed = 4.0f};
  WindSettings gusty = steady;
  gusty.gustAmplitude = 3.0f;
  gusty.gustPeriod = 0.3f;
  WindSettings otherSeed = gusty;
  otherSeed.seed = 2;
  const std::uint64_t calm = windyRun(strands, nullptr, 1);
  const std::uint64_t steadyHash = windyRun(strands, &steady, 1);
  const std::uint64_t gustyHash = windyRun(strands, &gusty, 1);
  EXPECT_NE(steadyHash, calm);
  EXPECT_NE(gustyHash, steadyHash);
  EXPECT_EQ(windyRun(strands, &gusty, 1), gustyHash);
  EXPECT_NE(windyRun(strands, &otherSeed, 1), gustyHash);
}

TEST(WindHair, ThreadCountDoesNotChangeTheResultWithWind) {
  const auto strands = curlyGroom();
  const WindSettings wind{.direction = {1, 0.2f, 0.5f}, .speed = 4.0f, .gustAmplitude = 3.0f, .gustPeriod = 0.4f};
  const std::uint64_t reference = windyRun(strands, &wind, 1);
  for (unsigned threads : {2u, 3u, 4u}) EXPECT_EQ(windyRun(strands, &wind, threads), reference) << threads << " threads";
}

}  // namespace
}  // namespace mane::physics
