// A body floating on the sea.
//
// Oracles: Archimedes (a box of mass m floats with draft m / (ρ L W)); the heave of a box in
// calm water, a spring of stiffness ρ g L W on mass m (ω = √(g/d)); its roll, a pendulum of
// restoring moment m g GM with GM = d/2 + W²/(12 d) − H/2 (the metacentre's height above the
// centre of mass, e.g. Biran, "Ship Hydrostatics and Stability", 2003, ch. 2) over the box's
// moment m (W² + H²)/12; the steady heel under a beam wind, tan φ = M / (m g GM); and the
// constraints the demo sets (no drift, no yaw).

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/floating_body.hpp"

namespace mane::physics {
namespace {

constexpr float kRho = 1025.0f;

// A box L × H × W (x, y, z) about its centre, cut into n·m·k cells.
std::vector<HullCell> boxHull(glm::vec3 size, glm::ivec3 cells) {
  std::vector<HullCell> hull;
  const glm::vec3 cell = size / glm::vec3(cells);
  for (int i = 0; i < cells.x; ++i)
    for (int j = 0; j < cells.y; ++j)
      for (int k = 0; k < cells.z; ++k)
        hull.push_back({.centre = (glm::vec3(i, j, k) + 0.5f) * cell - 0.5f * size, .size = cell});
  return hull;
}

OceanWaves calmSea() {
  return *OceanWaves::fromWaves({}, 0.0f);
}

// Box 10 m long, 3 m high, 4 m wide, with a 1.2 m draft.
constexpr glm::vec3 kBox{10.0f, 3.0f, 4.0f};
constexpr float kDraft = 1.2f;

FloatingBodySettings boxSettings(float drag) {
  return {.mass = kRho * kBox.x * kBox.z * kDraft,
          .position = {0.0f, 0.0f, 0.0f},
          .waterDensity = kRho,
          .dragPerSecond = drag,
          .hull = boxHull(kBox, {10, 12, 16})};
}

// The time between the first and the last upward crossing of `level`, over their count − 1.
double period(const std::vector<float>& values, float level, double dt) {
  std::vector<double> crossings;
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (values[i - 1] < level && values[i] >= level) {
      const double t = (level - values[i - 1]) / (values[i] - values[i - 1]);
      crossings.push_back((static_cast<double>(i) - 1.0 + t) * dt);
    }
  }
  if (crossings.size() < 2) return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

TEST(FloatingBody, ABoxFloatsAtItsArchimedesDraft) {
  auto body = FloatingBody::create(boxSettings(2.0f));
  ASSERT_TRUE(body) << body.error().message;
  const OceanWaves sea = calmSea();
  for (int i = 0; i < 120 * 60; ++i) ASSERT_TRUE(body->step(sea, i / 120.0, 1.0f / 120.0f, glm::vec3(0.0f)));
  const float draft = 0.5f * kBox.y - body->state().height;
  EXPECT_NEAR(draft, kDraft, 0.01f * kDraft);
  EXPECT_NEAR(body->state().pitch, 0.0f, 1e-5f);
  EXPECT_NEAR(body->state().roll, 0.0f, 1e-5f);
}

TEST(FloatingBody, ABoxHeavesAtTheSpringFrequencyOfItsWaterplane) {
  auto body = FloatingBody::create(boxSettings(0.0f));
  ASSERT_TRUE(body);
  const float rest = 0.5f * kBox.y - kDraft;
  FloatingBodyState state;
  state.height = rest + 0.2f;
  body->setState(state);
  const OceanWaves sea = calmSea();
  const double dt = 1.0 / 240.0;
  std::vector<float> heights;
  for (int i = 0; i < 240 * 20; ++i) {
    ASSERT_TRUE(body->step(sea, i * dt, static_cast<float>(dt), glm::vec3(0.0f)));
    heights.push_back(body->state().height);
  }
  const double expected = 2.0 * std::numbers::pi / std::sqrt(kOceanGravity / kDraft);
  EXPECT_NEAR(period(heights, rest, dt) / expected, 1.0, 0.05);
}

TEST(FloatingBody, ABoxRollsAtItsMetacentricFrequency) {
  auto body = FloatingBody::create(boxSettings(0.0f));
  ASSERT_TRUE(body);
  const float d = kDraft;
  const float w = kBox.z;
  const float h = kBox.y;
  const double gm = d / 2.0 + w * w / (12.0 * d) - h / 2.0;
  ASSERT_GT(gm, 0.0);
  const double mass = body->settings().mass;
  EXPECT_NEAR(body->rollInertia(), mass * (w * w + h * h) / 12.0, 1e-4 * body->rollInertia());
  FloatingBodyState state;
  state.height = 0.5f * h - d;
  state.roll = 0.05f;
  body->setState(state);
  const OceanWaves sea = calmSea();
  const double dt = 1.0 / 240.0;
  std::vector<float> rolls;
  for (int i = 0; i < 240 * 30; ++i) {
    ASSERT_TRUE(body->step(sea, i * dt, static_cast<float>(dt), glm::vec3(0.0f)));
    rolls.push_back(body->state().roll);
  }
  const double expected = 2.0 * std::numbers::pi / std::sqrt(mass * kOceanGravity * gm / body->rollInertia());
  EXPECT_NEAR(period(rolls, 0.0f, dt) / expected, 1.0, 0.05);
}

TEST(FloatingBody, ABeamWindHeelsItToLeewardAsItsMetacentreAllows) {
  FloatingBodySettings settings = boxSettings(3.0f);
  settings.sailArea = 20.0f;
  settings.sailCentre = {0.0f, 6.0f, 0.0f};
  auto body = FloatingBody::create(settings);
  ASSERT_TRUE(body);
  const glm::vec3 wind(0.0f, 0.0f, 8.0f);  // towards starboard
  const OceanWaves sea = calmSea();
  FloatingBodyState state;
  state.height = 0.5f * kBox.y - kDraft;
  body->setState(state);
  for (int i = 0; i < 120 * 60; ++i) ASSERT_TRUE(body->step(sea, i / 120.0, 1.0f / 120.0f, wind));
  // The force ½ ρ_air A |w|² at 6 m over the centre of mass; GM as above.
  const double force = 0.5 * kAirDensity * settings.sailArea * 64.0;
  const double gm = kDraft / 2.0 + kBox.z * kBox.z / (12.0 * kDraft) - kBox.y / 2.0;
  const double expected = std::atan(force * 6.0 / (settings.mass * kOceanGravity * gm));
  EXPECT_GT(body->state().roll, 0.0f);  // starboard, the lee side, down
  EXPECT_NEAR(body->state().roll / expected, 1.0, 0.05);
}

TEST(FloatingBody, ALoadHandedToItHeelsItAsItsMetacentreAllows) {
  // What sails hanging from it hand on: 500 N to starboard, 6 m over the centre of mass (a
  // torque about the long axis); the same heel as the beam wind's on `sailArea` above.
  auto body = FloatingBody::create(boxSettings(3.0f));
  ASSERT_TRUE(body);
  const glm::vec3 force(0.0f, 0.0f, 500.0f);
  ASSERT_TRUE(body->setLoad(force, glm::cross(glm::vec3(0.0f, 6.0f, 0.0f), force)));
  const OceanWaves sea = calmSea();
  FloatingBodyState state;
  state.height = 0.5f * kBox.y - kDraft;
  body->setState(state);
  for (int i = 0; i < 120 * 60; ++i) ASSERT_TRUE(body->step(sea, i / 120.0, 1.0f / 120.0f, glm::vec3(0.0f)));
  const double gm = kDraft / 2.0 + kBox.z * kBox.z / (12.0 * kDraft) - kBox.y / 2.0;
  const double expected = std::atan(500.0 * 6.0 / (boxSettings(3.0f).mass * kOceanGravity * gm));
  EXPECT_GT(body->state().roll, 0.0f);
  EXPECT_NEAR(body->state().roll / expected, 1.0, 0.05);
  // A load that is not finite is refused, and the one held kept.
  EXPECT_FALSE(body->setLoad(glm::vec3(NAN), glm::vec3(0.0f)));
  EXPECT_FALSE(body->setLoad(glm::vec3(0.0f), glm::vec3(INFINITY)));
}

TEST(FloatingBody, ItsStateHasTheSameBitsWhateverThreadsFindTheWater) {
  const auto sea = OceanWaves::create({.windSpeed = 12.0f, .windDirection = {1.0f, 1.0f}});
  ASSERT_TRUE(sea);
  const glm::vec3 box(10.0f, 3.0f, 6.0f);
  const FloatingBodySettings settings{.mass = kRho * box.x * box.z * kDraft,
                                      .position = {30.0f, 0.3f, -12.0f},
                                      .heading = 0.6f,
                                      .waterDensity = kRho,
                                      .hull = boxHull(box, {10, 6, 8})};
  auto alone = FloatingBody::create(settings);
  auto shared = FloatingBody::create(settings);
  ASSERT_TRUE(alone && shared);
  const TaskRunner three = builtInTaskRunner(3);
  for (int i = 0; i < 240; ++i) {
    ASSERT_TRUE(alone->step(*sea, i / 60.0, 1.0f / 60.0f, glm::vec3(3.0f, 0.0f, 3.0f)));
    ASSERT_TRUE(shared->step(*sea, i / 60.0, 1.0f / 60.0f, glm::vec3(3.0f, 0.0f, 3.0f), three));
  }
  EXPECT_EQ(std::memcmp(&alone->state(), &shared->state(), sizeof(FloatingBodyState)), 0);
  EXPECT_NE(alone->state().pitch, 0.0f);
}

TEST(FloatingBody, OnARoughSeaItHeavesPitchesAndRollsButNeitherDriftsNorTurns) {
  const auto sea = OceanWaves::create({.windSpeed = 12.0f, .windDirection = {1.0f, 1.0f}});
  ASSERT_TRUE(sea);
  // A beamier box than the others (6 m: GM = 1.6 m), in coarse cells.
  const glm::vec3 box(10.0f, 3.0f, 6.0f);
  FloatingBodySettings settings{.mass = kRho * box.x * box.z * kDraft,
                                .position = {30.0f, 0.3f, -12.0f},
                                .waterDensity = kRho,
                                .dragPerSecond = 0.5f,
                                .hull = boxHull(box, {5, 6, 4})};
  settings.heading = 0.6f;
  auto body = FloatingBody::create(settings);
  ASSERT_TRUE(body);
  float lowest = 1e9f;
  float highest = -1e9f;
  float largestPitch = 0.0f;
  float largestRoll = 0.0f;
  for (int i = 0; i < 60 * 60; ++i) {
    ASSERT_TRUE(body->step(*sea, i / 60.0, 1.0f / 60.0f, glm::vec3(3.0f, 0.0f, 3.0f)));
    const glm::mat4 m = body->transform();
    ASSERT_EQ(m[3].x, 30.0f);
    ASSERT_EQ(m[3].z, -12.0f);
    // The bow's horizontal direction stays the heading's (cos 0.6, −sin 0.6).
    const glm::vec2 bow = glm::normalize(glm::vec2(m[0].x, m[0].z));
    ASSERT_NEAR(bow.x, std::cos(0.6f), 1e-5f);
    ASSERT_NEAR(bow.y, -std::sin(0.6f), 1e-5f);
    lowest = std::min(lowest, m[3].y);
    highest = std::max(highest, m[3].y);
    largestPitch = std::max(largestPitch, std::abs(body->state().pitch));
    largestRoll = std::max(largestRoll, std::abs(body->state().roll));
  }
  // It rides waves of 2.8 m significant height: it moves, and it stays afloat and upright.
  EXPECT_GT(highest - lowest, 0.5f);
  EXPECT_LT(highest - lowest, 6.0f);
  EXPECT_GT(largestPitch, 0.01f);
  EXPECT_GT(largestRoll, 0.01f);
  EXPECT_LT(largestPitch, 0.6f);
  EXPECT_LT(largestRoll, 0.6f);
}

TEST(FloatingBody, ItsWaterlineRunsRoundTheHullsSideAndCutsAtTheSpeedItSinks) {
  auto body = FloatingBody::create(boxSettings(0.0f));
  ASSERT_TRUE(body);
  FloatingBodyState state;
  state.height = 0.5f * kBox.y - kDraft;
  state.heaveVelocity = -1.5f;
  body->setState(state);
  ASSERT_TRUE(body->step(calmSea(), 0.0, 1e-6f, glm::vec3(0.0f)));
  // 10 × 16 columns: the outline holds 2·10 + 2·16 − 4 of them.
  const std::vector<WaterlineContact>& line = body->waterline();
  ASSERT_EQ(line.size(), 2u * 10u + 2u * 16u - 4u);
  for (const WaterlineContact& contact : line) {
    EXPECT_NEAR(contact.position.y, 0.0f, 1e-6f);
    // In still water everything rests where it is.
    EXPECT_NEAR(contact.rest.x, contact.position.x, 1e-5f);
    EXPECT_NEAR(contact.rest.y, contact.position.z, 1e-5f);
    // On the box's side, facing out of it.
    const bool endOn = std::abs(std::abs(contact.position.x) - 0.5f * kBox.x) < 1e-4f;
    const bool sideOn = std::abs(std::abs(contact.position.z) - 0.5f * kBox.z) < 1e-4f;
    EXPECT_TRUE(endOn || sideOn) << contact.position.x << ", " << contact.position.z;
    EXPECT_GT(glm::dot(contact.outward, glm::vec3(contact.position.x, 0.0f, contact.position.z)), 0.0f);
    EXPECT_NEAR(glm::length(contact.outward), 1.0f, 1e-6f);
    // Sinking at 1.5 m/s into still water: the cut is the sinking speed.
    EXPECT_NEAR(contact.cutSpeed, 1.5f, 1e-5f);
  }
  // Out of the water, nothing cuts it.
  state.height = 10.0f;
  body->setState(state);
  ASSERT_TRUE(body->step(calmSea(), 0.0, 1e-6f, glm::vec3(0.0f)));
  EXPECT_TRUE(body->waterline().empty());
}

TEST(FloatingBody, RefusesSettingsOutOfRangeByName) {
  const auto refused = [](FloatingBodySettings s, const char* field) {
    const auto body = FloatingBody::create(std::move(s));
    ASSERT_FALSE(body) << field;
    EXPECT_NE(body.error().message.find(field), std::string::npos) << body.error().message;
  };
  FloatingBodySettings good = boxSettings(1.0f);
  FloatingBodySettings s = good;
  s.mass = 0.0f;
  refused(s, "mass");
  s = good;
  s.hull.clear();
  refused(s, "hull");
  s = good;
  s.hull[3].size.y = 0.0f;
  refused(s, "hull cell 3");
  s = good;
  s.dragPerSecond = -1.0f;
  refused(s, "dragPerSecond");
  s = good;
  s.waterDensity = NAN;
  refused(s, "waterDensity");
}

}  // namespace
}  // namespace mane::physics
