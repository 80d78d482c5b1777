// Guides laid over their body at rest (physics/groom_drape.hpp), the parting's comb
// (physics/groom_generator.hpp) and the barycentric blend kept to guides that leave the scalp
// alike (physics/interpolation.hpp).
//
// Oracles: a ball's distance is |p − c| − r in closed form, so every laid particle's clearance is
// checked against it; segment lengths are the grown ones; a chain that droops turns towards
// gravity and, past the ball, hangs straight down; a comb that lays the first centimetres holds
// them at the layer; the parting's comb is its closed form on either side and across its fade.

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/groom_drape.hpp"
#include "physics/groom_generator.hpp"
#include "physics/interpolation.hpp"

namespace mane::physics {
namespace {

constexpr float kBallRadius = 0.08f;

ColliderSet ball() {
  ColliderSet set;
  set.spheres.push_back({.centre = glm::vec3(0.0f), .radius = kBallRadius});
  set.thickness = 0.002f;
  return set;
}

// A straight guide of `count` particles `spacing` apart from `root` along `direction`.
std::vector<glm::vec3> straightGuide(const glm::vec3& root, const glm::vec3& direction, int count, float spacing) {
  std::vector<glm::vec3> guide;
  for (int i = 0; i < count; ++i) guide.push_back(root + glm::normalize(direction) * (spacing * float(i)));
  return guide;
}

TEST(GroomDrape, WithoutCollidersOrDroopTheGuideStaysAsGrown) {
  std::vector<std::vector<glm::vec3>> guides{straightGuide({0.0f, 0.1f, 0.0f}, {1.0f, 2.0f, -0.5f}, 12, 0.02f)};
  const auto grown = guides;
  ASSERT_TRUE(drapeGuides(guides, {}, {.droop = 0.0f}).has_value());
  for (std::size_t i = 0; i < grown[0].size(); ++i)
    EXPECT_LT(glm::length(guides[0][i] - grown[0][i]), 1e-5f) << "particle " << i;
}

// Strands grown sideways from the ball's top, in several directions: laid over it, every particle
// clears it by the layer and the thickness, every segment keeps its length, and past the ball
// the strand hangs down.
TEST(GroomDrape, StrandsLaidOverABallClearItKeepTheirLengthsAndHangBelowIt) {
  const ColliderSet set = ball();
  const DrapeSettings settings{.down = {0.0f, -9.81f, 0.0f}, .droop = 80.0f, .layer = 0.001f, .combedLength = 0.0f};
  std::vector<std::vector<glm::vec3>> guides;
  for (const glm::vec3& along : {glm::vec3(1, 0.2f, 0), glm::vec3(-1, 0.2f, 0.3f), glm::vec3(0.2f, 0.2f, -1)})
    guides.push_back(straightGuide({0.0f, kBallRadius, 0.0f}, along, 16, 0.025f));
  const auto grown = guides;
  ASSERT_TRUE(drapeGuides(guides, set, settings).has_value());
  for (std::size_t g = 0; g < guides.size(); ++g) {
    EXPECT_EQ(guides[g][0], grown[g][0]) << "the root stays";
    for (std::size_t i = 1; i < guides[g].size(); ++i) {
      EXPECT_NEAR(glm::length(guides[g][i] - guides[g][i - 1]), 0.025f, 1e-5f) << "guide " << g << " segment " << i;
      EXPECT_GE(glm::length(guides[g][i]) - kBallRadius, settings.layer + set.thickness - 1e-4f)
          << "guide " << g << " particle " << i;
    }
    const glm::vec3 last = glm::normalize(guides[g].back() - guides[g][guides[g].size() - 2]);
    EXPECT_LT(last.y, -0.99f) << "guide " << g << " hangs below the ball";
    EXPECT_LT(guides[g].back().y, -kBallRadius) << "guide " << g;
  }
}

// Combed along its first 6 cm, a strand lies on the ball there: at the layer, not above it.
TEST(GroomDrape, TheCombedLengthLiesOnTheLayer) {
  const ColliderSet set = ball();
  const DrapeSettings settings{.droop = 80.0f, .layer = 0.001f, .combedLength = 0.06f};
  std::vector<std::vector<glm::vec3>> guides{straightGuide({0.0f, kBallRadius, 0.0f}, {1.0f, 0.3f, 0.0f}, 16, 0.01f)};
  ASSERT_TRUE(drapeGuides(guides, set, settings).has_value());
  for (std::size_t i = 1; i <= 6; ++i)
    EXPECT_NEAR(glm::length(guides[0][i]) - kBallRadius, settings.layer + set.thickness, 2e-4f) << "particle " << i;
}

TEST(GroomDrape, SettingsOutOfRangeAreRefusedByName) {
  std::vector<std::vector<glm::vec3>> guides{straightGuide({0, 0, 0}, {0, 1, 0}, 4, 0.01f)};
  const auto message = [&](const DrapeSettings& settings) {
    auto laid = drapeGuides(guides, {}, settings);
    return laid ? std::string() : laid.error().message;
  };
  EXPECT_NE(message({.down = glm::vec3(0.0f)}).find("down"), std::string::npos);
  EXPECT_NE(message({.droop = -1.0f}).find("droop"), std::string::npos);
  EXPECT_NE(message({.layer = NAN}).find("layer"), std::string::npos);
  EXPECT_NE(message({.combedLength = -0.1f}).find("combedLength"), std::string::npos);
  // A segment of no length or not finite anywhere along a guide fails, naming it, and changes
  // no guide.
  for (const glm::vec3& third : {glm::vec3(0.0f, 0.01f, 0.0f), glm::vec3(0.0f, INFINITY, 0.0f)}) {
    std::vector<std::vector<glm::vec3>> flawed{straightGuide({0, 0, 0}, {1, 0, 0}, 3, 0.01f),
                                               {glm::vec3(0.0f), glm::vec3(0.0f, 0.01f, 0.0f), third}};
    const auto before = flawed;
    auto laid = drapeGuides(flawed, {}, {.droop = 50.0f});
    ASSERT_FALSE(laid.has_value());
    EXPECT_NE(laid.error().message.find("guide 1's segment 2"), std::string::npos) << laid.error().message;
    EXPECT_EQ(flawed, before);
  }
}

TEST(GroomParting, CombsEachSideAwayFromThePartingAndFadesBehindIt) {
  GroomSettings settings;
  settings.comb = {0.0f, 0.2f, -1.5f};
  EXPECT_EQ(combAt(settings, {0.05f, 0.1f, 0.05f}), settings.comb) << "no parting: the comb as given";
  settings.partingComb = 2.0f;
  settings.partingX = 0.01f;
  settings.partingBackZ = -0.02f;
  EXPECT_EQ(combAt(settings, {0.02f, 0.1f, 0.05f}), glm::vec3(2.0f, 0.2f, -1.5f));
  EXPECT_EQ(combAt(settings, {0.0f, 0.1f, 0.05f}), glm::vec3(-2.0f, 0.2f, -1.5f));
  EXPECT_EQ(combAt(settings, {0.02f, 0.1f, -0.03f}), settings.comb) << "behind the parting";
  const glm::vec3 halfway = combAt(settings, {0.02f, 0.1f, -0.02f + 0.5f * kPartingFade});
  EXPECT_NEAR(halfway.x, 1.0f, 1e-5f);
}

// Guides combed apart either side of a parting, two columns a side, leaving the scalp along ±x
// and then falling side by side (their root-to-tip chords within 8° of each other): no dense
// strand blends guides of both sides, most blend guides of their own side, and with every blend
// allowed some cross.
TEST(DenseStrands, BarycentricStrandsBlendOnlyGuidesThatLeaveTheScalpAlike) {
  std::vector<std::vector<glm::vec3>> guides;
  for (const float x : {-0.004f, -0.002f, 0.002f, 0.004f})
    for (int k = 0; k < 10; ++k) {
      const glm::vec3 root(x, 0.0f, 0.004f * float(k));
      std::vector<glm::vec3> guide{root, root + 0.02f * glm::normalize(glm::vec3(x < 0.0f ? -1.0f : 1.0f, 0.3f, 0.0f))};
      for (int i = 0; i < 6; ++i) guide.push_back(guide.back() + glm::vec3(0.0f, -0.02f, 0.0f));
      guides.push_back(guide);
    }
  const auto sideOf = [&](std::uint32_t guide) { return guides[guide][0].x < 0.0f ? 0 : 1; };
  struct Blends {
    int crossing = 0;
    int withinSide = 0;
  };
  const auto blends = [&](float minBlendCosine) {
    DenseGroomSettings settings;
    settings.blend = GuideBlend::kBarycentric;
    settings.strandCount = 800;
    settings.minBlendCosine = minBlendCosine;
    auto layout = buildDenseStrandLayout(guides, settings);
    EXPECT_TRUE(layout.has_value());
    Blends result;
    for (const DenseStrand& strand : layout->strands) {
      if (strand.guideCount < 3) continue;
      const bool crosses =
          sideOf(strand.guides[1]) != sideOf(strand.guides[0]) || sideOf(strand.guides[2]) != sideOf(strand.guides[0]);
      ++(crosses ? result.crossing : result.withinSide);
    }
    return result;
  };
  const Blends filtered = blends(DenseGroomSettings{}.minBlendCosine);
  EXPECT_EQ(filtered.crossing, 0);
  EXPECT_GT(filtered.withinSide, 400);
  EXPECT_GT(blends(-1.0f).crossing, 50);
}

}  // namespace
}  // namespace mane::physics
