// Debris afloat.
//
// Oracles: in calm water a corner rests where its submerged share equals the wood's relative
// density, (½ − d) × thickness above the surface; the pieces keep their shape (rest lengths);
// on a wave they ride the surface; none lies inside a body among them; and equal settings give
// equal bits.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "physics/floating_debris.hpp"

namespace mane::physics {
namespace {

FloatingDebrisSettings pieces() {
  return {.pieces = 12,
          .centre = {5.0f, -3.0f},
          .radius = 20.0f,
          .size = 1.5f,
          .thickness = 0.12f,
          .relativeDensity = 0.4f};
}

OceanWaves oneWave() {
  const float k = 2.0f * std::numbers::pi_v<float> / 40.0f;
  return *OceanWaves::fromWaves({{.direction = {1.0f, 0.0f},
                                  .wavenumber = k,
                                  .angularFrequency = std::sqrt(kOceanGravity * k),
                                  .amplitude = 1.0f}},
                                0.5f);
}

TEST(FloatingDebris, InCalmWaterEachCornerRestsAtTheDraftOfItsDensity) {
  // Laid on a wave's slopes, up to a metre above and below the calm water it then falls into.
  auto debris = FloatingDebris::create(pieces(), oneWave(), 0.0);
  ASSERT_TRUE(debris) << debris.error().message;
  const OceanWaves calm = *OceanWaves::fromWaves({}, 0.0f);
  std::vector<glm::vec3> dropped(debris->corners().begin(), debris->corners().end());
  std::vector<float> lengths;
  for (std::size_t i = 0; i < dropped.size(); i += 3)
    for (int e = 0; e < 3; ++e) lengths.push_back(glm::distance(dropped[i + e], dropped[i + (e + 1) % 3]));
  for (int i = 0; i < 60 * 20; ++i) debris->step(calm, i / 60.0, 1.0f / 60.0f);
  const float rest = (0.5f - 0.4f) * 0.12f;
  const std::span<const glm::vec3> corners = debris->corners();
  ASSERT_EQ(corners.size(), 36u);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    EXPECT_NEAR(corners[i].y, rest, 1e-4f) << i;
  }
  for (std::size_t i = 0; i < corners.size(); i += 3)
    for (int e = 0; e < 3; ++e)
      EXPECT_NEAR(glm::distance(corners[i + e], corners[i + (e + 1) % 3]), lengths[i + e], 1e-4f);
  // Strewn over the disc asked for, where they fell.
  for (const glm::vec3& c : dropped)
    EXPECT_LT(glm::distance(glm::vec2(c.x, c.z), glm::vec2(5.0f, -3.0f)), 20.0f + 1.5f);
}

TEST(FloatingDebris, OnAWaveThePiecesRideTheSurface) {
  const std::optional<OceanWaves> wave = oneWave();
  auto debris = FloatingDebris::create(pieces(), *wave, 0.0);
  ASSERT_TRUE(debris);
  float worst = 0.0f;
  float lowest = 1e9f;
  float highest = -1e9f;
  for (int i = 1; i <= 60 * 30; ++i) {
    const double t = i / 60.0;
    debris->step(*wave, t, 1.0f / 60.0f);
    const std::span<const glm::vec3> corners = debris->corners();
    for (std::size_t p = 0; p < corners.size(); p += 3) {
      const glm::vec3 centroid = (corners[p] + corners[p + 1] + corners[p + 2]) / 3.0f;
      const float surface = wave->surfaceAt({centroid.x, centroid.z}, t).position.y;
      worst = std::max(worst, std::abs(centroid.y - surface));
      if (p == 0) {
        lowest = std::min(lowest, centroid.y);
        highest = std::max(highest, centroid.y);
      }
    }
  }
  // Within a few thicknesses of a surface that rises and falls 2 m, and moving with it.
  EXPECT_LT(worst, 0.25f);
  EXPECT_GT(highest - lowest, 1.8f);
}

TEST(FloatingDebris, EqualSettingsGiveEqualBits) {
  const auto sea = OceanWaves::create({.windSpeed = 12.0f});
  ASSERT_TRUE(sea);
  auto a = FloatingDebris::create(pieces(), *sea, 3.0);
  auto b = FloatingDebris::create(pieces(), *sea, 3.0);
  ASSERT_TRUE(a && b);
  for (int i = 1; i <= 120; ++i) {
    a->step(*sea, 3.0 + i / 60.0, 1.0f / 60.0f);
    b->step(*sea, 3.0 + i / 60.0, 1.0f / 60.0f);
  }
  EXPECT_EQ(std::memcmp(a->corners().data(), b->corners().data(), a->corners().size_bytes()), 0);
}

// Where the disc's middle is a body's ellipsoid (a hull 30 m × 8 m × 6 m, bobbing a metre and
// turning as it rides for ten seconds), none of the pieces is strewn inside it and no corner ends a step inside
// it: each lies at 1 or more in the ellipsoid's own unit-sphere coordinates (less float rounding).
TEST(FloatingDebris, APieceNeverLiesInsideTheBodyAmongThem) {
  const auto sea = OceanWaves::create({.windSpeed = 12.0f});
  ASSERT_TRUE(sea);
  const auto hullAt = [](double t) {
    const float bob = float(std::sin(0.8 * t)), yaw = 0.3f * float(std::sin(0.2 * t));
    const glm::mat4 placed =
        glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(5.0f, bob, -3.0f)), yaw, glm::vec3(0.0f, 1.0f, 0.0f));
    return DebrisObstacle{.worldFromUnitSphere = glm::scale(placed, glm::vec3(15.0f, 3.0f, 4.0f))};
  };
  const auto deepest = [&](const FloatingDebris& debris, double t) {
    const glm::mat4 toSphere = glm::inverse(hullAt(t).worldFromUnitSphere);
    float least = 1e9f;
    for (const glm::vec3& c : debris.corners())
      least = std::min(least, glm::length(glm::vec3(toSphere * glm::vec4(c, 1.0f))));
    return least;
  };
  FloatingDebrisSettings settings = pieces();
  settings.pieces = 100;
  const DebrisObstacle start = hullAt(0.0);
  auto debris = FloatingDebris::create(settings, *sea, 0.0, &start);
  ASSERT_TRUE(debris) << debris.error().message;
  EXPECT_GE(deepest(*debris, 0.0), 1.0f - 1e-5f) << "strewn inside the body";
  auto without = FloatingDebris::create(settings, *sea, 0.0);
  ASSERT_TRUE(without);
  EXPECT_LT(deepest(*without, 0.0), 1.0f) << "the test's disc should reach into the body";
  float least = 1e9f;
  for (int i = 1; i <= 60 * 10; ++i) {
    const double t = i / 60.0;
    const DebrisObstacle hull = hullAt(t);
    debris->step(*sea, t, 1.0f / 60.0f, &hull);
    least = std::min(least, deepest(*debris, t));
  }
  EXPECT_GE(least, 1.0f - 1e-5f) << "a corner ended a step inside the body";
  const DebrisObstacle flat{.worldFromUnitSphere = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 1.0f))};
  EXPECT_FALSE(FloatingDebris::create(settings, *sea, 0.0, &flat)) << "an obstacle flattened to a disc";
}

TEST(FloatingDebris, RefusesSettingsOutOfRangeByName) {
  const OceanWaves calm = *OceanWaves::fromWaves({}, 0.0f);
  const auto refused = [&calm](FloatingDebrisSettings s, const char* field) {
    const auto debris = FloatingDebris::create(s, calm, 0.0);
    ASSERT_FALSE(debris) << field;
    EXPECT_NE(debris.error().message.find(field), std::string::npos) << debris.error().message;
  };
  FloatingDebrisSettings s = pieces();
  s.pieces = -1;
  refused(s, "pieces");
  s = pieces();
  s.size = 0.0f;
  refused(s, "size");
  s = pieces();
  s.relativeDensity = 1.0f;
  refused(s, "relativeDensity");
  s = pieces();
  s.thickness = NAN;
  refused(s, "thickness");
  s = pieces();
  s.constraintIterations = 0;
  refused(s, "constraintIterations");
}

}  // namespace
}  // namespace mane::physics
