// Dense strand interpolation: strands equal to their guide plus offset, barycentric combinations
// checked in double, clumping, length scale, head rotation, determinism across seeds and thread
// counts, the Nalu and 100,000-strand sizes, and errors for bad input.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"
#include "physics/interpolation.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;
using Strands = std::vector<std::vector<glm::vec3>>;

// Positions here are within 1 m of the origin, where a float ulp is at most 2⁻²⁴ m ≈ 6e-8 m.
// The formula rounds a few times per vertex (lerp, weighted sum, clump, offset), so results
// that agree "within float rounding" agree to a few tens of ulps: 1e-6 m.
constexpr double kRounding = 1e-6;

Strands nalu(std::size_t guides = 762, std::uint64_t seed = 7) {
  GroomSettings groom;
  groom.seed = seed;
  groom.strandCount = guides;
  groom.particlesPerStrand = 16;
  groom.strandLength = 0.3f;
  groom.curlRadius = 0.01f;  // curly guides, so that interpolation along them is not trivial
  return *generateGroom(groom);
}

std::vector<glm::vec3> flatten(const Strands& strands) {
  std::vector<glm::vec3> flat;
  for (const auto& strand : strands) flat.insert(flat.end(), strand.begin(), strand.end());
  return flat;
}

std::vector<glm::vec3> interpolate(const Strands& guides, const DenseStrandLayout& layout, unsigned threads = 1,
                                   std::vector<glm::vec3>* tangents = nullptr) {
  std::vector<glm::vec3> out(layout.vertexTotal());
  if (tangents) tangents->assign(layout.vertexTotal(), glm::vec3(0.0f));
  const std::vector<glm::vec3> flat = flatten(guides);
  auto done = interpolateDenseStrands(flat, layout, out,
                                      tangents ? std::span<glm::vec3>(*tangents) : std::span<glm::vec3>{}, threads);
  EXPECT_TRUE(done) << (done ? "" : done.error().message);
  return out;
}

double distance(const glm::dvec3& a, const glm::vec3& b) {
  const glm::dvec3 d = a - glm::dvec3(b);
  return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

// The primary guide's frame, computed independently in double from the guide roots.
struct FrameD {
  glm::dvec3 e1, e2, n;
};
FrameD frameOf(const Strands& guides, const DenseStrandLayout& layout, std::uint32_t guide) {
  const GuideFrameRef ref = layout.guideFrames[guide];
  const glm::dvec3 root(guides[guide][0]);
  const glm::dvec3 e1 = glm::normalize(glm::dvec3(guides[ref.partnerA][0]) - root);
  const glm::dvec3 n = glm::normalize(glm::cross(e1, glm::dvec3(guides[ref.partnerB][0]) - root));
  return {e1, glm::cross(n, e1), n};
}

TEST(DenseStrands, SingleGuideWithoutOffsetIsItsGuideBitForBit) {
  const Strands guides = nalu(50);
  DenseGroomSettings settings;
  settings.strandCount = 200;
  settings.rootSpread = 0.0f;
  settings.tipJitter = 0.0f;
  settings.lengthVariation = 0.0f;  // clumping stays random: with no offset it changes nothing
  const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
  const std::vector<glm::vec3> dense = interpolate(guides, layout);
  for (std::size_t s = 0; s < layout.strands.size(); ++s)
    for (std::size_t i = 0; i < 16; ++i) {
      const glm::vec3& expected = guides[layout.strands[s].guides[0]][i];
      ASSERT_EQ(0, std::memcmp(&dense[s * 16 + i], &expected, sizeof(glm::vec3))) << "strand " << s << " vertex " << i;
    }
}

// Three-guide strands whose three guide indices are the same guide: the weighted sum must give
// back that guide, plus the offset (1 − c·t)·F·(o + t·j), computed here in double.
TEST(DenseStrands, StrandsWhoseGuidesAreAllTheSameReproduceThatGuidePlusOffset) {
  const Strands guides = nalu(100);
  DenseGroomSettings settings;
  settings.strandCount = 300;
  settings.blend = GuideBlend::kBarycentric;
  settings.lengthVariation = 0.0f;
  settings.tipJitter = 0.01f;
  DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
  SplitMix64 rng(3);
  for (DenseStrand& strand : layout.strands) {
    ASSERT_EQ(strand.guideCount, 3u);
    strand.guides[1] = strand.guides[2] = strand.guides[0];
    strand.rootOffset = {rng.nextFloat(-0.01f, 0.01f), rng.nextFloat(-0.01f, 0.01f), rng.nextFloat(-0.001f, 0.001f)};
  }
  const std::vector<glm::vec3> dense = interpolate(guides, layout);
  double worst = 0.0;
  for (std::size_t s = 0; s < layout.strands.size(); ++s) {
    const DenseStrand& strand = layout.strands[s];
    const FrameD f = frameOf(guides, layout, strand.guides[0]);
    for (std::size_t i = 0; i < 16; ++i) {
      const double t = static_cast<double>(i) / 15.0;
      const glm::dvec3 d = glm::dvec3(strand.rootOffset) + t * glm::dvec3(strand.tipJitter);
      const glm::dvec3 expected =
          glm::dvec3(guides[strand.guides[0]][i]) + (1.0 - strand.clump * t) * (d.x * f.e1 + d.y * f.e2 + d.z * f.n);
      worst = std::max(worst, distance(expected, dense[s * 16 + i]));
    }
  }
  EXPECT_LT(worst, kRounding);
}

// Clumps with a radial profile: roots spread evenly over a disc round each guide; at the tip a
// clump's strands lie at radii ρ' (shares of (1 − c) times the disc's radius) whose distribution
// is the profile's, 1 − (1 − ρ'²)^(p+1), tested by the largest gap between it and the strands'
// (Kolmogorov–Smirnov: over 20,000 strands, a gap of 0.0096 is exceeded by chance 5 % of the time).
TEST(DenseStrands, ClumpedTipsLieRoundTheirGuideWithTheProfilesDensity) {
  const Strands guides = nalu(200);
  for (const float profile : {0.0f, 1.0f, 3.0f}) {
    DenseGroomSettings settings;
    settings.strandCount = 20000;
    settings.rootSpread = 0.5f;
    settings.tipJitter = 0.0f;
    settings.lengthVariation = 0.0f;
    settings.clump = 0.6f;
    settings.clumpVariation = 0.0f;
    settings.clumpProfile = profile;
    const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
    const std::vector<glm::vec3> dense = interpolate(guides, layout);
    const std::size_t nd = layout.vertexCount;
    std::vector<double> radii;
    for (std::size_t s = 0; s < layout.strands.size(); ++s) {
      const std::uint32_t home = layout.strands[s].guides[0];
      const glm::dvec3 root(guides[home][0]);
      // The disc's radius: rootSpread times the distance to the nearer of the guide's frame
      // partners, the nearest root at a usable distance.
      const GuideFrameRef partners = layout.guideFrames[home];
      const double disc = 0.5 * std::min(glm::length(glm::dvec3(guides[partners.partnerA][0]) - root),
                                         glm::length(glm::dvec3(guides[partners.partnerB][0]) - root));
      const glm::dvec3 tip = glm::dvec3(dense[s * nd + nd - 1]) - glm::dvec3(guides[home].back());
      radii.push_back(glm::length(tip) / ((1.0 - 0.6) * disc));
    }
    std::ranges::sort(radii);
    double gap = 0.0;
    for (std::size_t i = 0; i < radii.size(); ++i) {
      const double r = std::min(radii[i], 1.0);
      const double share = 1.0 - std::pow(1.0 - r * r, profile + 1.0);
      gap = std::max({gap, std::abs(share - double(i) / radii.size()), std::abs(share - double(i + 1) / radii.size())});
    }
    EXPECT_LT(radii.back(), 1.0 + 1e-4) << profile;
    RecordProperty("gap_profile_" + std::to_string(int(profile)), std::to_string(gap));
    EXPECT_LT(gap, 0.0096) << profile;
  }
  // A guide triangle's roots: the share of the way to the far side, 1 − w₀, carries the profile.
  DenseGroomSettings settings;
  settings.blend = GuideBlend::kBarycentric;
  settings.clumpVariation = 0.0f;
  settings.clumpProfile = 2.0f;
  const auto triangles = buildDenseStrandLayout(guides, settings);
  ASSERT_TRUE(triangles) << triangles.error().message;
  for (const DenseStrand& strand : triangles->strands) {
    if (strand.guideCount != 3) continue;
    const float scale = clumpProfileScale(1.0f - strand.weights[0], 2.0f);
    ASSERT_NEAR(1.0f - strand.clump, (1.0f - settings.clump) * scale, 1e-6f);
  }
  // The scale runs from 1/√(p + 1) at the centre to 1 at the rim, and is 1 without a profile.
  EXPECT_FLOAT_EQ(clumpProfileScale(0.0f, 3.0f), 0.5f);
  EXPECT_NEAR(clumpProfileScale(1e-4f, 3.0f), 0.5f, 1e-6f);
  EXPECT_FLOAT_EQ(clumpProfileScale(1.0f, 3.0f), 1.0f);
  EXPECT_NEAR(clumpProfileScale(0.6f, 0.0f), 1.0f, 1e-7f);
}

TEST(DenseStrands, WeightsSumToOneForEveryStrand) {
  const Strands guides = nalu();
  for (GuideBlend blend : {GuideBlend::kSingle, GuideBlend::kBarycentric}) {
    DenseGroomSettings settings;
    settings.blend = blend;
    const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
    ASSERT_EQ(layout.strands.size(), 4095u);
    std::size_t threeGuide = 0;
    for (std::size_t s = 0; s < layout.strands.size(); ++s) {
      const DenseStrand& strand = layout.strands[s];
      double sum = 0.0;
      for (std::uint32_t k = 0; k < strand.guideCount; ++k) {
        EXPECT_GE(strand.weights[k], 0.0f);
        EXPECT_LT(strand.guides[k], 762u);
        sum += strand.weights[k];
      }
      EXPECT_NEAR(sum, 1.0, 1e-6) << "strand " << s;
      if (strand.guideCount == 3) {
        ++threeGuide;
        EXPECT_NE(strand.guides[0], strand.guides[1]);
        EXPECT_NE(strand.guides[0], strand.guides[2]);
        EXPECT_NE(strand.guides[1], strand.guides[2]);
      }
    }
    // A scalp groom always has well-shaped triangles among a root's 4 nearest neighbours.
    EXPECT_EQ(threeGuide, blend == GuideBlend::kBarycentric ? layout.strands.size() : 0u);
  }
}

// Three parallel guides (the same wavy shape at three roots): with no offset, no jitter and no
// clumping, every dense vertex is Σ w_k·guide_k(i), evaluated here in double.
TEST(DenseStrands, ThreeParallelGuidesGiveTheBarycentricCombination) {
  Strands guides(3);
  const glm::vec3 roots[3] = {{0.0f, 0.0f, 0.0f}, {0.02f, 0.0f, 0.001f}, {0.004f, 0.003f, 0.018f}};
  for (int g = 0; g < 3; ++g)
    for (int i = 0; i < 16; ++i) {
      const float y = 0.02f * static_cast<float>(i);
      guides[g].push_back(roots[g] + glm::vec3(0.01f * y * y, y, -0.005f * y));
    }
  DenseGroomSettings settings;
  settings.strandCount = 500;
  settings.blend = GuideBlend::kBarycentric;
  settings.tipJitter = 0.0f;
  settings.clump = 0.0f;
  settings.clumpVariation = 0.0f;
  settings.lengthVariation = 0.0f;
  const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
  const std::vector<glm::vec3> dense = interpolate(guides, layout);
  double worst = 0.0;
  for (std::size_t s = 0; s < layout.strands.size(); ++s) {
    const DenseStrand& strand = layout.strands[s];
    ASSERT_EQ(strand.guideCount, 3u);
    for (std::size_t i = 0; i < 16; ++i) {
      glm::dvec3 expected(0.0);
      for (int k = 0; k < 3; ++k)
        expected += static_cast<double>(strand.weights[k]) * glm::dvec3(guides[strand.guides[k]][i]);
      worst = std::max(worst, distance(expected, dense[s * 16 + i]));
    }
  }
  EXPECT_LT(worst, kRounding);
}

TEST(DenseStrands, FullClumpingPutsTheTipOnTheGuideTip) {
  const Strands guides = nalu(200);
  for (GuideBlend blend : {GuideBlend::kSingle, GuideBlend::kBarycentric}) {
    DenseGroomSettings settings;
    settings.strandCount = 1000;
    settings.blend = blend;
    settings.clump = 1.0f;
    settings.clumpVariation = 0.0f;
    settings.lengthVariation = 0.0f;
    settings.tipJitter = 0.01f;
    const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
    const std::vector<glm::vec3> dense = interpolate(guides, layout);
    double worstTip = 0.0;
    double meanRoot = 0.0;
    for (std::size_t s = 0; s < layout.strands.size(); ++s) {
      const std::vector<glm::vec3>& guide = guides[layout.strands[s].guides[0]];
      worstTip = std::max(worstTip, distance(glm::dvec3(guide[15]), dense[s * 16 + 15]));
      meanRoot += distance(glm::dvec3(guide[0]), dense[s * 16]) / static_cast<double>(layout.strands.size());
    }
    EXPECT_LT(worstTip, kRounding);
    EXPECT_GT(meanRoot, 1e-3);  // the roots are spread: clumping, not a copy, closes the tips
  }
}

// Straight guides of length L: a dense strand of length scale λ and Nd vertices is the first
// λ·L of its guide, sampled evenly (vertex i at distance λ·L·i/(Nd − 1) from the root).
TEST(DenseStrands, LengthScaleShortensAlongTheGuideWithAnyVertexCount) {
  Strands guides;
  for (int g = 0; g < 40; ++g) {
    std::vector<glm::vec3> guide;
    for (int i = 0; i < 16; ++i)
      guide.push_back(
          {0.01f * static_cast<float>(g % 8), -0.02f * static_cast<float>(i), 0.01f * static_cast<float>(g / 8)});
    guides.push_back(guide);
  }
  DenseGroomSettings settings;
  settings.strandCount = 400;
  settings.verticesPerStrand = 31;
  settings.lengthVariation = 0.5f;
  settings.rootSpread = 0.0f;
  settings.tipJitter = 0.0f;
  const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
  const std::vector<glm::vec3> dense = interpolate(guides, layout);
  double worst = 0.0;
  for (std::size_t s = 0; s < layout.strands.size(); ++s) {
    const DenseStrand& strand = layout.strands[s];
    EXPECT_GE(strand.lengthScale, 0.5f);
    EXPECT_LE(strand.lengthScale, 1.0f);
    const glm::dvec3 root(guides[strand.guides[0]][0]);
    for (std::size_t i = 0; i < 31; ++i) {
      const double along = static_cast<double>(strand.lengthScale) * 0.3 * static_cast<double>(i) / 30.0;
      worst = std::max(worst, distance(root + glm::dvec3(0.0, -along, 0.0), dense[s * 31 + i]));
    }
  }
  EXPECT_LT(worst, kRounding);
}

// A guide of 16 vertices on a circle of radius 0.1 m, 12° apart, drawn with 3 dense vertices
// per guide segment. Straight segments keep the whole 12° turn at every guide vertex and cut
// inside the circle: the dense vertex a third along a chord lies r·(1 − cos 6° / cos 2°) ≈
// 0.49 mm inside. The Catmull-Rom spline spreads the turn evenly (12°/3 = 4° per dense vertex,
// end segments included) and stays within a tenth of that of the circle.
TEST(DenseStrands, CatmullRomSpreadsTheGuidesTurnsAlongACircle) {
  constexpr double kRadius = 0.1;
  constexpr double kStep = 12.0 * std::numbers::pi / 180.0;
  std::vector<glm::vec3> arc;
  for (int v = 0; v < 16; ++v)
    arc.push_back(glm::vec3(glm::dvec3(kRadius * std::sin(v * kStep), kRadius * std::cos(v * kStep), 0.0)));
  const Strands guides{arc};
  const double inside = kRadius * (1.0 - std::cos(kStep / 2.0) / std::cos(kStep / 6.0));
  for (const StrandCurve curve : {StrandCurve::kLinear, StrandCurve::kCatmullRom}) {
    DenseGroomSettings settings;
    settings.strandCount = 1;
    settings.verticesPerStrand = 46;
    settings.curve = curve;
    settings.lengthVariation = 0.0f;
    settings.clump = 0.0f;
    settings.clumpVariation = 0.0f;
    settings.rootSpread = 0.0f;
    settings.tipJitter = 0.0f;
    const std::vector<glm::vec3> dense = interpolate(guides, *buildDenseStrandLayout(guides, settings));
    double sharpest = 0.0, gentlest = 180.0, farthest = 0.0;
    for (std::size_t i = 1; i + 1 < dense.size(); ++i) {
      const glm::dvec3 in = glm::normalize(glm::dvec3(dense[i] - dense[i - 1]));
      const glm::dvec3 out = glm::normalize(glm::dvec3(dense[i + 1] - dense[i]));
      const double turn = std::acos(std::clamp(glm::dot(in, out), -1.0, 1.0)) * 180.0 / std::numbers::pi;
      sharpest = std::max(sharpest, turn);
      gentlest = std::min(gentlest, turn);
    }
    for (std::size_t i = 0; i < dense.size(); ++i)
      farthest = std::max(farthest, std::abs(glm::length(glm::dvec3(dense[i])) - kRadius));
    if (curve == StrandCurve::kLinear) {
      EXPECT_NEAR(sharpest, 12.0, 1e-3);
      EXPECT_NEAR(farthest, inside, 1e-6);
    } else {
      EXPECT_LT(sharpest, 4.5);
      EXPECT_GT(gentlest, 3.5);
      EXPECT_LT(farthest, inside / 10.0);
    }
  }
}

// The layout is built once at rest; when the head (and so every guide) moves rigidly, the dense
// strands must move with it, offsets included: interpolate(R·G + T) = R·interpolate(G) + T.
TEST(DenseStrands, OffsetsFollowHeadRotation) {
  const Strands guides = nalu(300);
  const glm::mat4 head = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.1f, 0.2f)), 1.1f,
                                     glm::normalize(glm::vec3(0.3f, 1.0f, -0.5f)));
  Strands moved = guides;
  for (auto& strand : moved)
    for (glm::vec3& p : strand) p = glm::vec3(head * glm::vec4(p, 1.0f));
  for (GuideBlend blend : {GuideBlend::kSingle, GuideBlend::kBarycentric}) {
    DenseGroomSettings settings;
    settings.strandCount = 2000;
    settings.blend = blend;
    settings.tipJitter = 0.01f;
    const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
    const std::vector<glm::vec3> rest = interpolate(guides, layout);
    const std::vector<glm::vec3> turned = interpolate(moved, layout);
    double worst = 0.0;
    for (std::size_t v = 0; v < rest.size(); ++v)
      worst = std::max(worst, distance(glm::dmat4(head) * glm::dvec4(glm::dvec3(rest[v]), 1.0), turned[v]));
    // The transformed guides are themselves rounded (≈ 1 ulp), and the frame's normalisations
    // amplify that by about |offset| / |root − partner| ≲ 1: a few ulps at 0.5 m.
    EXPECT_LT(worst, 2e-6);
  }
}

TEST(DenseStrands, TangentsAreUnitCentralDifferences) {
  const Strands guides = nalu(100);
  DenseGroomSettings settings;
  settings.strandCount = 500;
  const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
  std::vector<glm::vec3> tangents;
  const std::vector<glm::vec3> dense = interpolate(guides, layout, 1, &tangents);
  for (std::size_t s = 0; s < layout.strands.size(); ++s)
    for (std::size_t i = 0; i < 16; ++i) {
      const glm::dvec3 a(dense[s * 16 + (i > 0 ? i - 1 : 0)]);
      const glm::dvec3 b(dense[s * 16 + (i < 15 ? i + 1 : 15)]);
      const glm::dvec3 expected = glm::normalize(b - a);
      ASSERT_LT(distance(expected, tangents[s * 16 + i]), 1e-5) << "strand " << s << " vertex " << i;
    }
}

TEST(DenseStrands, LayoutIsDeterministicForASeed) {
  const Strands guides = nalu();
  for (GuideBlend blend : {GuideBlend::kSingle, GuideBlend::kBarycentric}) {
    DenseGroomSettings settings;
    settings.blend = blend;
    settings.seed = 42;
    const DenseStrandLayout a = *buildDenseStrandLayout(guides, settings);
    const DenseStrandLayout b = *buildDenseStrandLayout(guides, settings);
    ASSERT_EQ(a.strands.size(), b.strands.size());
    EXPECT_EQ(0, std::memcmp(a.strands.data(), b.strands.data(), a.strands.size() * sizeof(DenseStrand)));
    EXPECT_EQ(0, std::memcmp(a.guideFrames.data(), b.guideFrames.data(), a.guideFrames.size() * sizeof(GuideFrameRef)));
    settings.seed = 43;
    const DenseStrandLayout c = *buildDenseStrandLayout(guides, settings);
    EXPECT_NE(0, std::memcmp(a.strands.data(), c.strands.data(), a.strands.size() * sizeof(DenseStrand)));
  }
}

TEST(DenseStrands, OutputIsIdenticalFor1And2And4Threads) {
  const Strands guides = nalu();
  for (GuideBlend blend : {GuideBlend::kSingle, GuideBlend::kBarycentric}) {
    DenseGroomSettings settings;
    settings.blend = blend;
    const DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
    std::vector<glm::vec3> tangents1;
    const std::vector<glm::vec3> one = interpolate(guides, layout, 1, &tangents1);
    for (unsigned threads : {2u, 4u}) {
      std::vector<glm::vec3> tangents;
      const std::vector<glm::vec3> many = interpolate(guides, layout, threads, &tangents);
      EXPECT_EQ(0, std::memcmp(one.data(), many.data(), one.size() * sizeof(glm::vec3))) << threads << " threads";
      EXPECT_EQ(0, std::memcmp(tangents1.data(), tangents.data(), one.size() * sizeof(glm::vec3)))
          << threads << " threads";
    }
  }
}

// Nalu (762 guides → 4,095 strands) and 100,000 strands build and interpolate. Oracle for
// placement: the generated scalp is a sphere of radius 0.1 m, so every dense root stays near it
// (barycentric roots lie on chords between guide roots, single-guide roots in a tangent disc).
TEST(DenseStrands, NaluAndHundredThousandStrandsBuildAndInterpolate) {
  const Strands guides = nalu();
  for (std::size_t count : {std::size_t{4095}, std::size_t{100000}})
    for (GuideBlend blend : {GuideBlend::kSingle, GuideBlend::kBarycentric}) {
      DenseGroomSettings settings;
      settings.strandCount = count;
      settings.blend = blend;
      const auto layout = buildDenseStrandLayout(guides, settings);
      ASSERT_TRUE(layout) << layout.error().message;
      ASSERT_EQ(layout->vertexTotal(), count * 16);
      const std::vector<glm::vec3> dense = interpolate(guides, *layout, 2);
      std::size_t rootsOffScalp = 0;
      std::size_t nonFinite = 0;
      for (std::size_t s = 0; s < count; ++s) {
        const glm::vec3 root = dense[s * 16];
        const float radius = std::sqrt(root.x * root.x + root.y * root.y + root.z * root.z);
        rootsOffScalp += radius < 0.09f || radius > 0.11f;
      }
      for (const glm::vec3& p : dense) nonFinite += !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
      EXPECT_EQ(rootsOffScalp, 0u) << count << " strands, blend " << static_cast<int>(blend);
      EXPECT_EQ(nonFinite, 0u) << count << " strands, blend " << static_cast<int>(blend);
    }
}

// --- bad input ------------------------------------------------------------------------------

std::string buildError(const Strands& guides, const DenseGroomSettings& settings = {}) {
  const auto layout = buildDenseStrandLayout(guides, settings);
  EXPECT_FALSE(layout);
  return layout ? std::string() : layout.error().message;
}

// Interpolates with a modified layout or guide array; the output must stay untouched on error.
std::string interpolateError(std::span<const glm::vec3> guides, const DenseStrandLayout& layout) {
  const glm::vec3 sentinel(123.0f);
  std::vector<glm::vec3> out(layout.vertexTotal(), sentinel);
  const auto done = interpolateDenseStrands(guides, layout, out);
  EXPECT_FALSE(done);
  for (const glm::vec3& p : out) EXPECT_EQ(p, sentinel);
  return done ? std::string() : done.error().message;
}

TEST(DenseStrandsInput, EmptyGroomOrLayoutIsRejected) {
  EXPECT_THAT(buildError({}), HasSubstr("empty"));
  std::vector<glm::vec3> none;
  EXPECT_THAT(interpolateError(none, DenseStrandLayout{}), HasSubstr("empty"));
}

TEST(DenseStrandsInput, MismatchedParticleCountsAreRejected) {
  Strands guides = nalu(20);
  guides[5].pop_back();
  const std::string message = buildError(guides);
  EXPECT_THAT(message, HasSubstr("guide 5 has 15 points"));
  EXPECT_THAT(message, HasSubstr("resample"));

  guides = nalu(20);
  const DenseStrandLayout layout = *buildDenseStrandLayout(guides, {});
  std::vector<glm::vec3> flat = flatten(guides);
  flat.pop_back();
  EXPECT_THAT(interpolateError(flat, layout), HasSubstr("mismatched"));
}

TEST(DenseStrandsInput, GuideIndexOutOfRangeIsRejectedByStrand) {
  const Strands guides = nalu(20);
  DenseGroomSettings settings;
  settings.blend = GuideBlend::kBarycentric;
  DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
  layout.strands[17].guides[2] = 20;
  const std::string message = interpolateError(flatten(guides), layout);
  EXPECT_THAT(message, HasSubstr("strand 17"));
  EXPECT_THAT(message, HasSubstr("out of range"));
}

TEST(DenseStrandsInput, WeightsNotSummingToOneAreRejected) {
  const Strands guides = nalu(20);
  DenseGroomSettings settings;
  settings.blend = GuideBlend::kBarycentric;
  DenseStrandLayout layout = *buildDenseStrandLayout(guides, settings);
  layout.strands[3].weights[0] = 0.5f;
  layout.strands[3].weights[1] = 0.3f;
  layout.strands[3].weights[2] = 0.1f;
  EXPECT_THAT(interpolateError(flatten(guides), layout), HasSubstr("strand 3: weights sum to 0.9"));

  // 1e-5 is the tolerance: 2e-5 off is refused, 5e-6 off is accepted.
  layout = *buildDenseStrandLayout(guides, settings);
  layout.strands[3].weights[0] += 2e-5f;
  EXPECT_THAT(interpolateError(flatten(guides), layout), HasSubstr("not 1"));
  layout.strands[3].weights[0] -= 1.5e-5f;
  EXPECT_TRUE(validateStrandLayout(layout));

  layout.strands[4].weights[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(interpolateError(flatten(guides), layout), HasSubstr("strand 4: weight 1 is not finite"));
}

TEST(DenseStrandsInput, NaNGuidesAreRejectedWithGuideAndVertex) {
  Strands guides = nalu(20);
  guides[7][4].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(buildError(guides), HasSubstr("guide 7, vertex 4 is not finite"));

  guides = nalu(20);
  const DenseStrandLayout layout = *buildDenseStrandLayout(guides, {});
  std::vector<glm::vec3> flat = flatten(guides);
  flat[9 * 16 + 11].z = std::numeric_limits<float>::infinity();
  EXPECT_THAT(interpolateError(flat, layout), HasSubstr("guide 9, vertex 11 is not finite"));
}

TEST(DenseStrandsInput, SettingsOutOfRangeAreRejectedByName) {
  const Strands guides = nalu(20);
  DenseGroomSettings settings;
  settings.strandCount = 0;
  EXPECT_THAT(buildError(guides, settings), HasSubstr("strandCount"));
  settings = {};
  settings.clump = 1.5f;
  EXPECT_THAT(buildError(guides, settings), HasSubstr("clump"));
  settings = {};
  settings.verticesPerStrand = 1;
  EXPECT_THAT(buildError(guides, settings), HasSubstr("verticesPerStrand"));
}

TEST(DenseStrandsInput, OutputOfTheWrongSizeIsRejected) {
  const Strands guides = nalu(20);
  const DenseStrandLayout layout = *buildDenseStrandLayout(guides, {});
  std::vector<glm::vec3> out(layout.vertexTotal() - 1);
  const auto done = interpolateDenseStrands(flatten(guides), layout, out);
  ASSERT_FALSE(done);
  EXPECT_THAT(done.error().message, HasSubstr("output holds"));
}

}  // namespace
}  // namespace mane::physics
