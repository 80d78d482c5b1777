// Procedural guides rooted on a mesh region.
//
// Oracles: every root lies in one of the region's triangles (barycentric coordinates in [0, 1]
// up to rounding) and never in the others; roots spread by area (two triangles with areas 3:1
// receive 3:1 of 8,000 roots, within 4 binomial standard deviations); a straight strand grows
// along its triangle's outward normal; the same seed gives the same bytes.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"

namespace mane::physics {
namespace {

// Three triangles in the y = 0 plane facing +Y (counter-clockwise seen from above): A has area
// 1.5, B has 0.5, C (not in the region) has 2.
const std::vector<glm::vec3> kPositions{{0, 0, 0}, {0, 0, -1}, {3, 0, 0},    // A
                                        {5, 0, 0}, {5, 0, -1}, {6, 0, 0},    // B
                                        {9, 0, 0}, {9, 0, -2}, {11, 0, 0}};  // C
const std::vector<std::uint32_t> kIndices{0, 2, 1, 3, 5, 4, 6, 8, 7};
const std::vector<std::uint32_t> kScalp{0, 1};

TEST(GroomOnMesh, RootsSpreadByAreaOverTheRegionOnly) {
  GroomSettings settings;
  settings.strandCount = 8000;
  settings.particlesPerStrand = 3;
  auto strands = generateGroomOnMesh(settings, kPositions, kIndices, kScalp);
  ASSERT_TRUE(strands.has_value()) << strands.error().message;
  int onA = 0, onB = 0;
  for (const auto& strand : *strands) {
    const glm::vec3 root = strand.front();
    EXPECT_NEAR(root.y, 0.0f, 1e-6f);
    if (root.x <= 3.0f + 1e-5f) {
      ++onA;
      EXPECT_GE(root.x, -1e-5f);
      EXPECT_LE(-root.z, 1.0f - root.x / 3.0f + 1e-5f);  // inside A's hypotenuse
    } else {
      ++onB;
      EXPECT_GE(root.x, 5.0f - 1e-5f);
      EXPECT_LE(root.x, 6.0f + 1e-5f);
    }
  }
  EXPECT_EQ(onA + onB, 8000);
  // Expected 6,000 : 2,000; σ = √(n·p·(1 − p)) = √(8000·0.75·0.25) ≈ 38.7.
  EXPECT_NEAR(onA, 6000, 4 * 38.7);
}

// Densities 1 : 3 on triangles of areas 3 : 1 give both the same share of the roots.
TEST(GroomOnMesh, RootsSpreadByAreaTimesDensity) {
  GroomSettings settings;
  settings.strandCount = 8000;
  settings.particlesPerStrand = 3;
  const std::vector<float> density{1.0f, 3.0f};
  auto strands = generateGroomOnMesh(settings, kPositions, kIndices, kScalp, density);
  ASSERT_TRUE(strands.has_value()) << strands.error().message;
  const auto onA = std::count_if(strands->begin(), strands->end(),
                                 [](const std::vector<glm::vec3>& strand) { return strand.front().x <= 3.0f + 1e-5f; });
  // Expected 4,000 : 4,000; σ = √(8000·0.5·0.5) ≈ 44.7.
  EXPECT_NEAR(double(onA), 4000.0, 4 * 44.7);
  const std::vector<float> wrongCount{1.0f};
  EXPECT_NE(generateGroomOnMesh(settings, kPositions, kIndices, kScalp, wrongCount).error().message.find("1 densities"),
            std::string::npos);
  const std::vector<float> negative{1.0f, -1.0f};
  EXPECT_NE(generateGroomOnMesh(settings, kPositions, kIndices, kScalp, negative).error().message.find("density"),
            std::string::npos);
}

TEST(GroomOnMesh, StraightStrandsGrowAlongTheFaceNormal) {
  GroomSettings settings;
  settings.strandCount = 50;
  settings.strandLength = 0.2f;
  auto strands = generateGroomOnMesh(settings, kPositions, kIndices, kScalp);
  ASSERT_TRUE(strands.has_value());
  for (const auto& strand : *strands) {
    const glm::vec3 axis = glm::normalize(strand.back() - strand.front());
    EXPECT_NEAR(axis.y, 1.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(strand.back(), strand.front()), 0.2f, 0.2f * settings.lengthJitter + 1e-6f);
  }
  auto again = generateGroomOnMesh(settings, kPositions, kIndices, kScalp);
  EXPECT_EQ(*again, *strands);
}

// Combed, a strand on the +Y face grows along n + c_t, c_t the comb's part along the face: the
// comb (1, 5, −1) leans it along (1, 0, −1), 54.7° from the normal (tan = √2), whatever its part
// along the normal (5). Its roots and lengths are those of the uncombed groom with the same seed.
TEST(GroomOnMesh, CombedStrandsLeanAlongTheCombsPartOnTheScalp) {
  GroomSettings settings;
  settings.strandCount = 50;
  settings.strandLength = 0.2f;
  const auto straight = generateGroomOnMesh(settings, kPositions, kIndices, kScalp);
  settings.comb = {1.0f, 5.0f, -1.0f};
  const auto combed = generateGroomOnMesh(settings, kPositions, kIndices, kScalp);
  ASSERT_TRUE(straight.has_value() && combed.has_value());
  const glm::vec3 expected = glm::normalize(glm::vec3(1.0f, 1.0f, -1.0f));
  for (std::size_t s = 0; s < combed->size(); ++s) {
    const std::vector<glm::vec3>& strand = (*combed)[s];
    EXPECT_EQ(strand.front(), (*straight)[s].front()) << "strand " << s;
    EXPECT_LT(glm::distance(glm::normalize(strand.back() - strand.front()), expected), 1e-6f) << "strand " << s;
    EXPECT_NEAR(glm::distance(strand.back(), strand.front()),
                glm::distance((*straight)[s].back(), (*straight)[s].front()), 1e-6f)
        << "strand " << s;
  }
  settings.comb.x = std::nanf("");
  EXPECT_NE(generateGroomOnMesh(settings, kPositions, kIndices, kScalp).error().message.find("comb must be finite"),
            std::string::npos);
}

TEST(GroomOnMesh, BadRegionsAreNamed) {
  const GroomSettings settings;
  EXPECT_NE(generateGroomOnMesh(settings, kPositions, kIndices, {}).error().message.find("no triangles"),
            std::string::npos);
  const std::vector<std::uint32_t> outside{7};
  EXPECT_NE(generateGroomOnMesh(settings, kPositions, kIndices, outside).error().message.find("scalp triangle 7"),
            std::string::npos);
  const std::vector<std::uint32_t> badIndex{0, 1, 99};
  const std::vector<std::uint32_t> first{0};
  EXPECT_NE(generateGroomOnMesh(settings, kPositions, badIndex, first).error().message.find("vertex 99"),
            std::string::npos);
  const std::vector<glm::vec3> flat{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<std::uint32_t> line{0, 1, 2};
  EXPECT_NE(generateGroomOnMesh(settings, flat, line, first).error().message.find("no area"), std::string::npos);
}

}  // namespace
}  // namespace mane::physics
