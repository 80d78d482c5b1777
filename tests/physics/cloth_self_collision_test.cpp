// Cloth that collides with itself (physics/cloth_self_collision.hpp), and cloth that rests on a
// pattern other than the shape it starts in (ClothSettings::pattern).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "physics/cloth.hpp"
#include "tests/support/cloth_grid.hpp"

namespace mane::physics {
namespace {

using mane::testing::makeClothGrid;

// Two sheets in one cloth, lying flat (the grid's XY plane turned into XZ): a pinned floor 0.6 m
// square at y = 0 and, 5 cm above its middle, a free sheet 0.3 m square that gravity drops on it.
struct TwoSheets {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint32_t> floor;  // every vertex of the floor: the pins
  std::uint32_t firstFree = 0;
};

TwoSheets twoSheets() {
  TwoSheets sheets;
  const auto add = [&](int n, float size, const glm::vec3& corner) {
    const auto first = static_cast<std::uint32_t>(sheets.positions.size());
    const auto grid = makeClothGrid(n, size);
    for (const glm::vec3& p : grid.positions) sheets.positions.push_back(corner + glm::vec3(p.x, 0.0f, -p.y));
    for (std::uint32_t index : grid.triangles) sheets.triangles.push_back(first + index);
    return first;
  };
  add(13, 0.6f, {0, 0, 0});
  for (std::uint32_t v = 0; v < sheets.positions.size(); ++v) sheets.floor.push_back(v);
  sheets.firstFree = add(9, 0.3f, {0.15f, 0.05f, 0.15f});
  return sheets;
}

// The falling sheet comes to rest on the floor, every vertex no nearer its plane than the
// thickness (less float rounding), and lies there (within a millimetre of it) rather than
// bouncing; without self collision it falls straight through.
TEST(ClothSelfCollision, ASheetDroppedOnAnotherRestsAtTheThickness) {
  const TwoSheets sheets = twoSheets();
  constexpr float kThickness = 0.01f;
  const auto lowestAndHighest = [&](float thickness) {
    ClothSettings settings;
    settings.selfCollisionThickness = thickness;
    auto cloth = Cloth::create(sheets.positions, sheets.triangles, sheets.floor, settings);
    EXPECT_TRUE(cloth.has_value()) << cloth.error().message;
    std::pair<float, float> range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    if (!cloth) return range;
    for (int frame = 0; frame < 60; ++frame) {
      EXPECT_TRUE(cloth->advance(1.0 / 60.0).has_value());
      for (std::size_t v = sheets.firstFree; v < sheets.positions.size(); ++v)
        range.first = std::min(range.first, cloth->particles().positions[v].y);
    }
    for (std::size_t v = sheets.firstFree; v < sheets.positions.size(); ++v)
      range.second = std::max(range.second, cloth->particles().positions[v].y);
    return range;
  };
  const auto [lowest, highest] = lowestAndHighest(kThickness);
  EXPECT_GE(lowest, kThickness - 1e-5f);
  EXPECT_LE(highest, kThickness + 0.001f) << "the sheet should lie on the floor after a second";
  EXPECT_LT(lowestAndHighest(0.0f).first, -0.5f) << "without self collision the sheet falls through";
}

// A sheet folded onto itself by a body that swings it round: the same state for 1, 2 and 4
// threads (self collision runs on the calling thread, between the parallel phases).
TEST(ClothSelfCollision, ThreadCountDoesNotChangeTheResult) {
  const auto grid = makeClothGrid(72, 0.4f);  // 5,184 vertices: two workers' worth
  std::uint64_t hashes[3];
  const unsigned threads[3] = {1, 2, 4};
  for (int run = 0; run < 3; ++run) {
    ClothSettings settings;
    settings.selfCollisionThickness = 0.004f;
    auto cloth = Cloth::create(grid.positions, grid.triangles, std::vector<std::uint32_t>{0, 71}, settings);
    ASSERT_TRUE(cloth.has_value());
    for (int frame = 0; frame < 10; ++frame) {
      ASSERT_TRUE(cloth->setBodyTransform(glm::rotate(glm::mat4(1.0f), 0.05f * float(frame), {0, 1, 0})).has_value());
      ASSERT_TRUE(cloth->advance(1.0 / 60.0, threads[run]).has_value());
    }
    hashes[run] = cloth->stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

// A sheet started rolled into a half cylinder, with its flat grid as its pattern and no gravity,
// unrolls: its far corner ends (almost) the sheet's length from the pin above it, in whatever
// direction it unrolled. With no pattern it keeps its roll: the far corner stays a diameter away.
TEST(ClothPattern, ARolledSheetWithAFlatPatternUnrolls) {
  constexpr int kN = 12;
  constexpr float kSize = 0.3f;
  const auto flat = makeClothGrid(kN, kSize);
  std::vector<glm::vec3> rolled;
  const float radius = kSize / std::numbers::pi_v<float>;
  for (const glm::vec3& p : flat.positions) {
    const float angle = -p.y / radius;  // rows roll round the x axis
    rolled.push_back({p.x, -radius * std::sin(angle), radius * (1.0f - std::cos(angle))});
  }
  std::vector<std::uint32_t> topRow;
  for (std::uint32_t i = 0; i < kN; ++i) topRow.push_back(i);
  const auto farCornerFromItsPin = [&](bool withPattern) {
    ClothSettings settings;
    settings.solver.gravity = {0, 0, 0};
    settings.bendingStiffness = 1.0f;
    settings.solver.constraintIterations = 20;
    if (withPattern) settings.pattern = flat.positions;
    auto cloth = Cloth::create(rolled, flat.triangles, topRow, settings);
    EXPECT_TRUE(cloth.has_value()) << cloth.error().message;
    if (!cloth) return 0.0f;
    for (int frame = 0; frame < 240; ++frame) EXPECT_TRUE(cloth->advance(1.0 / 60.0).has_value());
    return glm::distance(cloth->particles().positions[kN * kN - 1], flat.positions[kN - 1]);
  };
  EXPECT_GT(farCornerFromItsPin(true), 0.95f * kSize) << "a flat sheet's far corner is its length from its pin";
  EXPECT_NEAR(farCornerFromItsPin(false), 2.0f * radius, 0.01f * kSize) << "with no pattern the roll is its rest shape";
}

TEST(ClothPattern, BadPatternsAndThicknessesAreNamed) {
  const auto grid = makeClothGrid(3, 1.0f);
  const auto message = [&](ClothSettings settings) {
    auto cloth = Cloth::create(grid.positions, grid.triangles, {}, settings);
    return cloth ? std::string("(created)") : cloth.error().message;
  };
  ClothSettings settings;
  settings.pattern = {{0, 0, 0}};
  EXPECT_NE(message(settings).find("ClothSettings.pattern: 1 points for 9 vertices"), std::string::npos);
  settings.pattern = grid.positions;
  settings.pattern[5].y = std::nanf("");
  EXPECT_NE(message(settings).find("ClothSettings.pattern: point 5 is NaN"), std::string::npos);
  settings.pattern.clear();
  settings.selfCollisionThickness = -0.001f;
  EXPECT_NE(message(settings).find("ClothSettings.selfCollisionThickness"), std::string::npos);
}

}  // namespace
}  // namespace mane::physics
