// Wind field and segment drag.
//
// Oracles: the drag law's geometry (a segment along the wind feels nothing, one across it feels
// k·|w − v|, at 45° it feels the normal component, k·|w|·sin 45°), the gust bounds and the
// smoothstep's continuity, the travel delay of a gust front, and bit-identical repeats.

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/wind.hpp"

namespace mane::physics {
namespace {

TEST(Wind, SteadyWindHasTheSpeedAndDirectionAsked) {
  const WindField wind({.direction = {0, 0, 2}, .speed = 3.0f});
  EXPECT_EQ(wind.velocityAt({1, 2, 3}, 0.0), glm::vec3(0, 0, 3));
  EXPECT_EQ(wind.velocityAt({-5, 0, 9}, 17.25), glm::vec3(0, 0, 3));
}

TEST(Wind, DragActsOnlyAcrossTheSegment) {
  const glm::vec3 air(4, 0, 0);
  const float k = 2.0f;
  // Along the wind: no force (exactly: the normal component is zero).
  EXPECT_EQ(windAcceleration(air, glm::vec3(0), glm::vec3(1, 0, 0), k), glm::vec3(0));
  // Across it: the whole relative velocity.
  EXPECT_EQ(windAcceleration(air, glm::vec3(0), glm::vec3(0, 1, 0), k), glm::vec3(8, 0, 0));
  // At 45°: |a| = k·|w|·sin 45° = 8·√½, perpendicular to the axis.
  const glm::vec3 axis = glm::normalize(glm::vec3(1, 1, 0));
  const glm::vec3 a = windAcceleration(air, glm::vec3(0), axis, k);
  EXPECT_NEAR(glm::length(a), 8.0f * std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(glm::dot(a, axis), 0.0f, 1e-6f);
  // A particle already moving with the air feels nothing.
  EXPECT_EQ(windAcceleration(air, air, glm::vec3(0, 1, 0), k), glm::vec3(0));
}

TEST(Wind, GustsStayWithinTheAmplitudeAndVarySmoothly) {
  const WindField wind({.speed = 5.0f, .gustAmplitude = 2.0f, .gustPeriod = 0.5f, .seed = 7});
  float lowest = 1e9f, highest = -1e9f, largestStep = 0.0f;
  const double dt = 1.0 / 1000.0;
  float previous = wind.velocityAt({0, 0, 0}, 0.0).x;
  for (int i = 1; i <= 20000; ++i) {
    const float speed = wind.velocityAt({0, 0, 0}, i * dt).x;
    lowest = std::min(lowest, speed);
    highest = std::max(highest, speed);
    largestStep = std::max(largestStep, std::abs(speed - previous));
    previous = speed;
  }
  EXPECT_GE(lowest, 3.0f);
  EXPECT_LE(highest, 7.0f);
  EXPECT_GT(highest - lowest, 1.0f) << "20 s of gusts should vary the speed";
  // Smoothstep's slope is at most 1.5 per period: |Δspeed| ≤ 1.5·(2·amplitude)·dt/period.
  EXPECT_LE(largestStep, 1.5f * 4.0f * dt / 0.5 + 1e-5f);
}

TEST(Wind, AGustFrontTravelsWithTheAir) {
  const WindField wind({.direction = {1, 0, 0}, .speed = 4.0f, .gustAmplitude = 1.0f, .seed = 3});
  // 2 m downwind the air arrives 0.5 s later: same speed, half a second later.
  for (double t : {0.7, 1.9, 3.3})
    EXPECT_FLOAT_EQ(wind.velocityAt({2, 0, 0}, t + 0.5).x, wind.velocityAt({0, 0, 0}, t).x);
}

TEST(Wind, SameSeedSameWindOtherSeedOtherWind) {
  const WindSettings settings{.speed = 1.0f, .gustAmplitude = 1.0f, .seed = 11};
  WindSettings other = settings;
  other.seed = 12;
  EXPECT_EQ(WindField(settings).velocityAt({0.3f, 0, 0}, 2.7), WindField(settings).velocityAt({0.3f, 0, 0}, 2.7));
  EXPECT_NE(WindField(settings).gust(2.7), WindField(other).gust(2.7));
}

TEST(Wind, BadSettingsAreNamed) {
  EXPECT_NE(validateWind({.direction = {0, 0, 0}}).error().message.find("direction"), std::string::npos);
  EXPECT_NE(validateWind({.speed = -1.0f}).error().message.find("speed"), std::string::npos);
  EXPECT_NE(validateWind({.gustPeriod = 0.0f}).error().message.find("gustPeriod"), std::string::npos);
  EXPECT_TRUE(validateWind({}).has_value());
}

}  // namespace
}  // namespace mane::physics
