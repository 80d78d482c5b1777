// Wind on cloth.
//
// Oracles: a flat plate's normal force, ½ ρ C A (u·n)|u·n|: a free sheet square to the wind
// accelerates at ½ ρ C |w|² / σ at every vertex (Verlet moves it a·h² in its first step from
// rest); a sheet along the wind feels nothing; turned 60° from square it feels cos² 60° of that,
// along its normal; a sheet moving with the air feels nothing; and the state is the same for 1, 2
// and 4 threads. The push on the whole sheet is the pressure on its area, at its centre.

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/cloth.hpp"

namespace mane::physics {
namespace {

// A free 1 m sheet of side × side vertices in the plane whose normal is `normal`.
ClothSettings freeSheet(const glm::vec3& normal, const glm::vec3& wind, int side = 9) {
  ClothSettings settings;
  settings.solver.gravity = glm::vec3(0.0f);
  settings.solver.damping = 0.0f;
  settings.solver.constraintIterations = 1;
  const glm::vec3 n = glm::normalize(normal);
  const glm::vec3 u = glm::normalize(glm::cross(std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), n));
  const glm::vec3 v = glm::cross(n, u);
  const int kN = side;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i)
      settings.positions.push_back((float(i) / (kN - 1) - 0.5f) * u + (float(j) / (kN - 1) - 0.5f) * v);
  for (int j = 0; j + 1 < kN; ++j)
    for (int i = 0; i + 1 < kN; ++i) {
      const auto a = std::uint32_t(j * kN + i);
      settings.triangles.insert(settings.triangles.end(), {a, a + 1, a + kN, a + 1, a + kN + 1, a + kN});
    }
  settings.wind = ClothWind{.velocity = wind, .arealDensity = 0.4f, .dragCoefficient = 1.2f};
  return settings;
}

// Each vertex's displacement after one step from rest, over h².
std::vector<glm::vec3> firstStepAccelerations(const ClothSettings& settings) {
  auto cloth = Cloth::create(settings);
  EXPECT_TRUE(cloth) << cloth.error().message;
  const std::vector<glm::vec3> before = cloth->particles().positions;
  const float h = float(settings.solver.fixedStep);
  EXPECT_TRUE(cloth->advance(settings.solver.fixedStep, 1u));
  std::vector<glm::vec3> a;
  for (std::size_t i = 0; i < before.size(); ++i) a.push_back((cloth->particles().positions[i] - before[i]) / (h * h));
  return a;
}

TEST(ClothWind, ASheetSquareToTheWindFeelsTheDynamicPressureEverywhere) {
  const glm::vec3 wind(0.0f, 0.0f, 8.0f);
  const ClothSettings settings = freeSheet({0, 0, 1}, wind);
  const float expected = 0.5f * kClothAirDensity * 1.2f * 64.0f / 0.4f;
  // The constraint sweep finds every edge at rest length (the sheet moves as one): nothing else moves it.
  for (const glm::vec3& a : firstStepAccelerations(settings)) {
    EXPECT_NEAR(a.z, expected, 1e-3f * expected);
    EXPECT_NEAR(a.x, 0.0f, 1e-3f * expected);
    EXPECT_NEAR(a.y, 0.0f, 1e-3f * expected);
  }
}

TEST(ClothWind, ThePushOnTheWholeSheetIsThePressureOnItsAreaAtItsCentre) {
  const glm::vec3 wind(0.0f, 0.0f, 8.0f);
  ClothSettings settings = freeSheet({0, 0, 1}, wind);
  // Held along its top edge, as a sail is: the pins feel the air as the rest do.
  for (std::uint32_t v = 72; v < 81; ++v) settings.pinnedVertices.push_back(v);
  auto cloth = Cloth::create(settings);
  ASSERT_TRUE(cloth) << cloth.error().message;
  EXPECT_EQ(cloth->windPush(glm::vec3(0.0f)).force, glm::vec3(0.0f));  // before any step
  ASSERT_TRUE(cloth->advance(settings.solver.fixedStep, 1u));
  // ½ ρ C |w|² on its 1 m², at its centre: about a point 2 m below it, a moment of 2 m × F.
  const float force = 0.5f * kClothAirDensity * 1.2f * 64.0f;
  const WindPush atCentre = cloth->windPush(glm::vec3(0.0f));
  EXPECT_NEAR(atCentre.force.z, force, 1e-4f * force);
  EXPECT_NEAR(glm::length(glm::vec2(atCentre.force)), 0.0f, 1e-4f * force);
  EXPECT_NEAR(glm::length(atCentre.moment), 0.0f, 1e-4f * force);
  const WindPush below = cloth->windPush({0.0f, -2.0f, 0.0f});
  EXPECT_NEAR(below.moment.x, 2.0f * force, 1e-4f * force);
  EXPECT_NEAR(below.moment.y, 0.0f, 1e-4f * force);
  EXPECT_NEAR(below.moment.z, 0.0f, 1e-4f * force);
}

TEST(ClothWind, ASheetAlongTheWindFeelsNothingAndATurnedOneItsNormalShare) {
  const glm::vec3 wind(0.0f, 0.0f, 8.0f);
  for (const glm::vec3& a : firstStepAccelerations(freeSheet({1, 0, 0}, wind))) EXPECT_EQ(a, glm::vec3(0.0f));
  // Turned 60° from square: (u·n)² = cos² 60° of the square sheet's, along the normal.
  const glm::vec3 normal(std::sin(1.04719755f), 0.0f, std::cos(1.04719755f));
  const float expected = 0.5f * kClothAirDensity * 1.2f * 64.0f / 0.4f * 0.25f;
  for (const glm::vec3& a : firstStepAccelerations(freeSheet(normal, wind))) {
    EXPECT_NEAR(glm::length(a), expected, 2e-3f * expected);
    EXPECT_NEAR(glm::dot(glm::normalize(a), normal), 1.0f, 1e-4f);
  }
}

TEST(ClothWind, ASheetMovingWithTheAirFeelsNothing) {
  ClothSettings settings = freeSheet({0, 0, 1}, glm::vec3(0.0f, 0.0f, 3.0f));
  auto cloth = Cloth::create(settings);
  ASSERT_TRUE(cloth);
  // Run until the sheet has nearly caught up with the air: the pressure falls as (w − v)².
  for (int i = 0; i < 2000; ++i) ASSERT_TRUE(cloth->advance(settings.solver.fixedStep, 1u));
  const Particles& p = cloth->particles();
  const float speed = (p.positions[0].z - p.previousPositions[0].z) / float(settings.solver.fixedStep);
  EXPECT_GT(speed, 2.5f);
  EXPECT_LT(speed, 3.0f + 1e-4f);
}

TEST(ClothWind, ThreadCountDoesNotChangeTheResult) {
  // A sail pinned along its top edge in a gusting crosswind, with gravity; enough vertices
  // (96²) for the step to split across the workers.
  constexpr int kN = 96;
  ClothSettings settings = freeSheet({0, 0, 1}, glm::vec3(2.0f, 0.0f, 9.0f), kN);
  settings.solver.gravity = glm::vec3(0.0f, -9.81f, 0.0f);
  settings.solver.constraintIterations = 4;
  for (std::uint32_t i = (kN - 1) * kN; i < std::uint32_t(kN * kN); ++i) settings.pinnedVertices.push_back(i);
  std::uint64_t hashes[3] = {};
  const unsigned threads[3] = {1, 2, 4};
  for (int t = 0; t < 3; ++t) {
    auto cloth = Cloth::create(settings);
    ASSERT_TRUE(cloth);
    for (int frame = 0; frame < 10; ++frame) {
      ASSERT_TRUE(cloth->setWind(glm::vec3(2.0f, 0.0f, 9.0f + float(frame % 7))));
      ASSERT_TRUE(cloth->advance(1.0 / 60.0, threads[t]));
    }
    hashes[t] = cloth->stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

TEST(ClothWind, RefusesWindOutOfRangeByName) {
  ClothSettings settings = freeSheet({0, 0, 1}, glm::vec3(0.0f));
  settings.wind->arealDensity = 0.0f;
  auto cloth = Cloth::create(settings);
  ASSERT_FALSE(cloth);
  EXPECT_NE(cloth.error().message.find("arealDensity"), std::string::npos);
  settings = freeSheet({0, 0, 1}, glm::vec3(NAN));
  EXPECT_FALSE(Cloth::create(settings));
}

}  // namespace
}  // namespace mane::physics
