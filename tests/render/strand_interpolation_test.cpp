// The strand interpolation compute pass (render/passes/strand_interpolation_pass.hpp) against its
// references:
// - the CPU reference physics::interpolateDenseStrands on the real TressFX ponytail (4,933 guides
//   × 16 vertices) after the guides moved (a rigid head turn plus a few simulated steps), for the
//   single-guide and the barycentric layouts, positions and tangents;
// - closed forms on synthetic layouts: guides that are all equal give the guide plus the offset
//   (o + t·j)·(1 − c·t) in the fixed axes; tangents are the unit central differences; coincident
//   points give zero tangents;
// - the compiled shader itself: every floating-point add, subtract, multiply and divide is
//   decorated NoContraction, which is what makes the CPU and GPU round the same way.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/hair.hpp"
#include "physics/interpolation.hpp"
#include "render/passes/strand_interpolation_pass.hpp"
#include "scenes/groom_loader.hpp"
#include "shaders/embedded.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

using ::testing::HasSubstr;

// The GPU must match the CPU reference within 1e-5 relative (physics/interpolation.hpp).
constexpr double kRelativeTolerance = 1e-5;

struct GpuResult {
  std::vector<glm::vec4> positions;
  std::vector<glm::vec4> tangents;
};

class StrandInterpolation : public testing::VulkanTest {
public:
  // One frame of the pass: upload the guides, dispatch, wait, read the mapped outputs.
  GpuResult interpolate(const DenseStrandLayout& layout, std::span<const glm::vec3> guides) {
    auto pass = StrandInterpolationPass::create(device(), layout, {.hostReadable = true});
    EXPECT_TRUE(pass.has_value()) << pass.error().message;
    if (!pass) return {};
    auto updated = (*pass)->updateGuides(guides);
    EXPECT_TRUE(updated.has_value()) << updated.error().message;
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });
    const auto positions = (*pass)->mappedPositions();
    const auto tangents = (*pass)->mappedTangents();
    EXPECT_EQ(positions.size(), layout.strands.size() * layout.vertexCount);
    return {{positions.begin(), positions.end()}, {tangents.begin(), tangents.end()}};
  }

  void expectGuidePlusOffset(StrandCurve curve);
};

// ---- The real groom against the CPU reference ------------------------------------------------

struct Comparison {
  double positionError = 0.0;  // max |gpu − cpu| over coordinates, metres
  double tangentError = 0.0;   // max |gpu − cpu| over coordinates (unit vectors)
  std::size_t differingBits = 0;
};

Comparison compare(const GpuResult& gpu, std::span<const glm::vec3> positions, std::span<const glm::vec3> tangents) {
  Comparison result;
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double dp = std::abs(double(gpu.positions[i][c]) - positions[i][c]);
      const double dt = std::abs(double(gpu.tangents[i][c]) - tangents[i][c]);
      result.positionError = std::max(result.positionError, dp);
      result.tangentError = std::max(result.tangentError, dt);
      result.differingBits += (gpu.positions[i][c] != positions[i][c]) + (gpu.tangents[i][c] != tangents[i][c]);
    }
  return result;
}

// The bounding-box diagonal of `points`, metres: the scale position errors are relative to.
double boundingSize(std::span<const glm::vec3> points) {
  glm::vec3 low(points[0]), high(points[0]);
  for (const glm::vec3& p : points) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  return glm::length(glm::dvec3(high - low));
}

void checkAgainstCpu(StrandInterpolation& test, const std::vector<std::vector<glm::vec3>>& rest,
                     std::span<const glm::vec3> moved, physics::GuideBlend blend, std::size_t verticesPerStrand,
                     StrandCurve curve = StrandCurve::kCatmullRom, bool curled = false) {
  physics::DenseGroomSettings settings;
  settings.curve = curve;
  if (curled) {
    settings.curlRadius = 0.004f;
    settings.curlPeriod = 0.02f;
    settings.frizz = 0.0005f;
  }
  settings.seed = 7;
  settings.strandCount = 10000;
  settings.blend = blend;
  settings.verticesPerStrand = verticesPerStrand;
  const auto layout = physics::buildDenseStrandLayout(rest, settings);
  ASSERT_TRUE(layout.has_value()) << layout.error().message;
  const auto blended = std::count_if(layout->strands.begin(), layout->strands.end(),
                                     [](const DenseStrand& s) { return s.guideCount == 3; });
  if (blend == physics::GuideBlend::kBarycentric) {
    ASSERT_GT(blended, 9000) << "the barycentric layout should blend three guides almost everywhere";
  }

  std::vector<glm::vec3> positions(layout->vertexTotal()), tangents(layout->vertexTotal());
  const auto reference = physics::interpolateDenseStrands(moved, *layout, positions, tangents);
  ASSERT_TRUE(reference.has_value()) << reference.error().message;

  const GpuResult gpu = test.interpolate(*layout, moved);
  ASSERT_EQ(gpu.positions.size(), positions.size());
  ASSERT_EQ(gpu.tangents.size(), tangents.size());
  const Comparison error = compare(gpu, positions, tangents);
  const double size = boundingSize(positions);
  std::printf(
      "  %s, %s%s, %zu dense strands x %u vertices: max position error %.3g m (%.3g of the %.3f m groom), "
      "max tangent error %.3g, %zu of %zu floats differ in any bit\n",
      blend == physics::GuideBlend::kSingle ? "single guide" : "barycentric",
      curve == StrandCurve::kLinear ? "linear" : "Catmull-Rom", curled ? ", curled and frizzed" : "",
      layout->strands.size(), layout->vertexCount, error.positionError, error.positionError / size, size,
      error.tangentError, error.differingBits, positions.size() * 6);
  // Positions: per coordinate, relative to the groom's bounding-box diagonal. Tangents: per
  // coordinate of a unit vector, so relative to its length 1.
  EXPECT_LE(error.positionError, kRelativeTolerance * size);
  EXPECT_LE(error.tangentError, kRelativeTolerance);
  // w is the parameter t along the strand (a division, which Vulkan lets a GPU round loosely).
  for (std::size_t i = 0; i < gpu.positions.size(); ++i)
    ASSERT_NEAR(gpu.positions[i].w, double(i % layout->vertexCount) / (layout->vertexCount - 1), 1e-6)
        << "vertex " << i;
}

TEST_F(StrandInterpolation, MatchesTheCpuReferenceOnTheSimulatedPonytail) {
  // The four groups of the TressFX ponytail as one groom, in metres (scenes/ponytail.json scales
  // the head and its hair by 0.01).
  MANE_RESOLVE_OR_SKIP(frontTop, "hair/tressfx_ponytail/front_top.tfx");
  MANE_RESOLVE_OR_SKIP(side, "hair/tressfx_ponytail/side.tfx");
  MANE_RESOLVE_OR_SKIP(back, "hair/tressfx_ponytail/back.tfx");
  MANE_RESOLVE_OR_SKIP(tail, "hair/tressfx_ponytail/tail.tfx");
  std::vector<std::vector<glm::vec3>> rest;
  for (const auto& file : {frontTop, side, back, tail}) {
    auto loaded = scenes::loadGroomFile(file);
    ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
    for (auto& strand : loaded->strands) {
      for (glm::vec3& point : strand) point *= 0.01f;
      rest.push_back(std::move(strand));
    }
  }
  ASSERT_EQ(rest.size(), 4933u);
  // Move the guides: the head turns 25° about +Y and shifts, and the strands swing for 4 frames.
  auto hair = physics::HairSystem::create(rest, physics::SolverSettings{});
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  const glm::mat4 head = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.05f, 0.02f, -0.03f)),
                                     25.0f * std::numbers::pi_v<float> / 180.0f, glm::vec3(0.0f, 1.0f, 0.0f));
  ASSERT_TRUE(hair->setHeadTransform(head).has_value());
  for (int frame = 0; frame < 4; ++frame) ASSERT_TRUE(hair->advance(1.0 / 60.0).has_value());
  const std::vector<glm::vec3>& moved = hair->particles().positions;
  ASSERT_EQ(moved.size(), rest.size() * 16);
  ASSERT_NE(moved[1], rest[0][1]);

  checkAgainstCpu(*this, rest, moved, physics::GuideBlend::kSingle, 0);
  checkAgainstCpu(*this, rest, moved, physics::GuideBlend::kBarycentric, 24);
  checkAgainstCpu(*this, rest, moved, physics::GuideBlend::kBarycentric, 24, StrandCurve::kLinear);
  checkAgainstCpu(*this, rest, moved, physics::GuideBlend::kBarycentric, 48, StrandCurve::kCatmullRom, true);
}

// ---- Synthetic layouts with closed-form answers ---------------------------------------------

constexpr std::uint32_t kGuideVertices = 9;

// A curled polyline about 0.4 m long, metres.
std::vector<glm::vec3> curledGuide() {
  std::vector<glm::vec3> points;
  for (std::uint32_t v = 0; v < kGuideVertices; ++v) {
    const float a = 0.7f * float(v);
    points.push_back({0.1f + 0.03f * std::cos(a), 0.5f - 0.05f * float(v), -0.2f + 0.03f * std::sin(a)});
  }
  return points;
}

// The point at u along a guide, in double. Catmull-Rom in its Hermite form: the cubic between
// vertices v and v + 1 whose end tangents are half the differences of their neighbours, the
// guide extended at its ends by the parabola through its last three vertices.
glm::dvec3 onGuide(const std::vector<glm::vec3>& guide, double u, StrandCurve curve) {
  const auto last = static_cast<std::uint32_t>(guide.size() - 1);
  const std::uint32_t v = std::min<std::uint32_t>(std::uint32_t(u), last - 1);
  const double f = u - v;
  const glm::dvec3 p1(guide[v]), p2(guide[v + 1]);
  if (curve == StrandCurve::kLinear) return (1.0 - f) * p1 + f * p2;
  const auto parabola = [&](std::uint32_t end, int inwards) {
    const glm::dvec3 p(guide[end]), q(guide[end + inwards]), r(guide[end + 2 * inwards]);
    return 3.0 * p - 3.0 * q + r;
  };
  const glm::dvec3 p0 = v > 0 ? glm::dvec3(guide[v - 1]) : parabola(0, 1);
  const glm::dvec3 p3 = v + 1 < last ? glm::dvec3(guide[v + 2]) : parabola(last, -1);
  const glm::dvec3 m1 = 0.5 * (p2 - p0), m2 = 0.5 * (p3 - p1);
  const double f2 = f * f, f3 = f2 * f;
  return (2 * f3 - 3 * f2 + 1) * p1 + (f3 - 2 * f2 + f) * m1 + (3 * f2 - 2 * f3) * p2 + (f3 - f2) * m2;
}

TEST_F(StrandInterpolation, EqualGuidesGiveTheGuidePlusTheOffsetInTheFixedAxes) {
  for (const StrandCurve curve : {StrandCurve::kLinear, StrandCurve::kCatmullRom}) expectGuidePlusOffset(curve);
}

void StrandInterpolation::expectGuidePlusOffset(StrandCurve curve) {
  SCOPED_TRACE(curve == StrandCurve::kLinear ? "linear" : "Catmull-Rom");
  // Three identical guides with no frame partners: the frame is the fixed axes (x, y, z), and
  // any weights blend the guide with itself, so vertex i of a strand is exactly
  //   G(u) + (1 − c·t)·(o + t·j),  u = i·vertexScale,  t = i/(Nd − 1)
  // (clumping pulls B towards L_0 = B). Evaluated here in double.
  constexpr std::uint32_t kGuides = 3, kDenseVertices = 13;
  const std::vector<glm::vec3> guide = curledGuide();
  std::vector<glm::vec3> guides;
  for (std::uint32_t g = 0; g < kGuides; ++g) guides.insert(guides.end(), guide.begin(), guide.end());
  const std::vector<GuideFrameRef> frames{{0, 0}, {1, 1}, {2, 2}};
  const float span = float(kGuideVertices - 1) / float(kDenseVertices - 1);
  const std::vector<DenseStrand> strands{
      {.guides = {0, 0, 0}, .vertexScale = span},
      {.guides = {1, 0, 0}, .vertexScale = span, .rootOffset = {0.004f, -0.002f, 0.001f}},
      {.guides = {2, 0, 0},
       .vertexScale = 0.8f * span,
       .rootOffset = {-0.003f, 0.001f, 0.0f},
       .clump = 0.6f,
       .tipJitter = {0.001f, 0.002f, -0.0015f}},
      {.guides = {0, 1, 2},
       .guideCount = 3,
       .weights = {0.5f, 0.25f, 0.25f},
       .vertexScale = 0.9f * span,
       .rootOffset = {0.002f, 0.002f, 0.0f},
       .clump = 1.0f,
       .tipJitter = {-0.002f, 0.0f, 0.001f}},
      {.guides = {2, 1, 0},
       .guideCount = 2,
       .weights = {0.7f, 0.3f, 0.0f},
       .vertexScale = span,
       .clump = 0.3f,
       .tipJitter = {0.0f, 0.0f, 0.003f}},
  };
  const DenseStrandLayout layout{.guideCount = kGuides,
                                 .guideVertexCount = kGuideVertices,
                                 .vertexCount = kDenseVertices,
                                 .guideFrames = frames,
                                 .strands = strands,
                                 .curve = curve};
  const GpuResult gpu = interpolate(layout, guides);
  ASSERT_EQ(gpu.positions.size(), strands.size() * kDenseVertices);

  // The guide is about 0.4 m long; 1e-5 relative of that covers float rounding of weights that
  // sum to 1 only to within an ulp.
  const double tolerance = kRelativeTolerance * 0.4;
  for (std::size_t s = 0; s < strands.size(); ++s) {
    const DenseStrand& strand = strands[s];
    for (std::uint32_t i = 0; i < kDenseVertices; ++i) {
      const glm::dvec3 point = onGuide(guide, double(i) * strand.vertexScale, curve);
      const double t = double(i) / (kDenseVertices - 1);
      const double scale = 1.0 - strand.clump * t;
      const glm::vec4 got = gpu.positions[s * kDenseVertices + i];
      for (int c = 0; c < 3; ++c) {
        const double expected = point[c] + scale * (double(strand.rootOffset[c]) + t * strand.tipJitter[c]);
        EXPECT_NEAR(got[c], expected, tolerance) << "strand " << s << ", vertex " << i << ", axis " << c;
      }
    }
  }

  // Tangents: the unit central difference of the strand's own positions, one-sided at the ends.
  for (std::size_t s = 0; s < strands.size(); ++s)
    for (std::uint32_t i = 0; i < kDenseVertices; ++i) {
      const glm::dvec3 next(gpu.positions[s * kDenseVertices + std::min(i + 1, kDenseVertices - 1)]);
      const glm::dvec3 previous(gpu.positions[s * kDenseVertices + (i > 0 ? i - 1 : 0)]);
      const glm::dvec3 expected = glm::normalize(next - previous);
      const glm::dvec3 got(gpu.tangents[s * kDenseVertices + i]);
      EXPECT_NEAR(glm::length(got), 1.0, 1e-6) << "strand " << s << ", vertex " << i;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], expected[c], kRelativeTolerance) << "strand " << s << ", vertex " << i << ", axis " << c;
      EXPECT_EQ(gpu.tangents[s * kDenseVertices + i].w, 0.0f);
    }
}

TEST_F(StrandInterpolation, CoincidentPointsGiveZeroTangents) {
  // A guide collapsed to one point, followed with no offset: every dense point is that point,
  // so P[i + 1] − P[i − 1] = 0 and the tangent is (0, 0, 0), not NaN.
  const std::vector<glm::vec3> guides(kGuideVertices, glm::vec3(0.1f, 0.2f, 0.3f));
  const std::vector<GuideFrameRef> frames{{0, 0}};
  const std::vector<DenseStrand> strands{{.vertexScale = 1.0f, .clump = 0.5f}};
  const GpuResult gpu = interpolate({1, kGuideVertices, kGuideVertices, frames, strands}, guides);
  ASSERT_EQ(gpu.positions.size(), kGuideVertices);
  for (std::size_t i = 0; i < kGuideVertices; ++i) {
    EXPECT_EQ(glm::vec3(gpu.positions[i]), guides[0]) << "vertex " << i;
    EXPECT_EQ(gpu.tangents[i], glm::vec4(0.0f)) << "vertex " << i;
  }
}

TEST_F(StrandInterpolation, DeviceLocalOutputsHoldTheSameVerticesAsHostReadableOnes) {
  // The default (device-local) outputs, copied out after record's barrier, equal the mapped
  // outputs of a host-readable pass on the same input, bit for bit: same shader, same inputs.
  const std::vector<glm::vec3> guide = curledGuide();
  const std::vector<GuideFrameRef> frames{{0, 0}};
  const std::vector<DenseStrand> strands{{.vertexScale = 0.5f, .rootOffset = {0.01f, 0.0f, 0.0f}, .clump = 0.4f},
                                         {.vertexScale = 1.0f, .tipJitter = {0.0f, 0.02f, 0.0f}}};
  const DenseStrandLayout layout{1, kGuideVertices, kGuideVertices, frames, strands};
  const GpuResult expected = interpolate(layout, guide);

  auto pass = StrandInterpolationPass::create(device(), layout);
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  EXPECT_TRUE((*pass)->mappedPositions().empty());
  ASSERT_TRUE((*pass)->updateGuides(guide).has_value());
  const vk::DeviceSize bytes = (*pass)->positions().size();
  const Buffer copy(device(), 2 * bytes, vk::BufferUsageFlagBits::eTransferDst,
                    vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    (*pass)->record(commands);
    commands.copyBuffer(*(*pass)->positions().buffer(), *copy.buffer(), vk::BufferCopy{.size = bytes});
    commands.copyBuffer(*(*pass)->tangents().buffer(), *copy.buffer(),
                        vk::BufferCopy{.dstOffset = bytes, .size = bytes});
    const vk::MemoryBarrier2 toHost{.srcStageMask = vk::PipelineStageFlagBits2::eCopy,
                                    .srcAccessMask = vk::AccessFlagBits2::eTransferWrite,
                                    .dstStageMask = vk::PipelineStageFlagBits2::eHost,
                                    .dstAccessMask = vk::AccessFlagBits2::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
  });
  const auto* words = reinterpret_cast<const glm::vec4*>(copy.mapped().data());
  const std::size_t total = (*pass)->vertexTotal();
  ASSERT_EQ(expected.positions.size(), total);
  for (std::size_t i = 0; i < total; ++i) {
    EXPECT_EQ(words[i], expected.positions[i]) << "vertex " << i;
    EXPECT_EQ(words[total + i], expected.tangents[i]) << "vertex " << i;
  }
}

// ---- Bad input ----------------------------------------------------------------------------

TEST_F(StrandInterpolation, RejectsLayoutsAndGuidesThatDoNotFit) {
  const std::vector<GuideFrameRef> frames{{0, 0}, {1, 1}};
  std::vector<DenseStrand> strands(2);
  strands[1].guides[0] = 2;  // only guides 0 and 1 exist
  auto outOfRange = StrandInterpolationPass::create(device(), {2, 4, 4, frames, strands});
  ASSERT_FALSE(outOfRange.has_value());
  EXPECT_THAT(outOfRange.error().message, HasSubstr("dense strand 1: guide index 2 is out of range"));

  strands[1] = {.guides = {0, 1, 0}, .guideCount = 2, .weights = {0.5f, 0.4f, 0.0f}};
  auto badWeights = StrandInterpolationPass::create(device(), {2, 4, 4, frames, strands});
  ASSERT_FALSE(badWeights.has_value());
  EXPECT_THAT(badWeights.error().message, HasSubstr("weights sum to"));

  EXPECT_FALSE(StrandInterpolationPass::create(device(), {2, 4, 4, frames, {}}).has_value());
  EXPECT_FALSE(StrandInterpolationPass::create(device(), {2, 4, 4, {frames.front()}, strands}).has_value());

  strands[1] = {.guides = {1, 0, 0}};
  auto pass = StrandInterpolationPass::create(device(), {2, 4, 4, frames, strands});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  std::vector<glm::vec3> guides(7, glm::vec3(0.0f));
  auto wrongCount = (*pass)->updateGuides(guides);
  ASSERT_FALSE(wrongCount.has_value());
  EXPECT_THAT(wrongCount.error().message, HasSubstr("expected 2 guides × 4 vertices = 8 guide positions, got 7"));
  guides.resize(8);
  guides[6].y = std::numeric_limits<float>::quiet_NaN();
  auto notFinite = (*pass)->updateGuides(guides);
  ASSERT_FALSE(notFinite.has_value());
  EXPECT_THAT(notFinite.error().message, HasSubstr("guide 1, vertex 2 is not finite"));
}

TEST_F(StrandInterpolation, RejectsGuidesWhoseFrameCollapsed) {
  // Guide 0's frame is spanned by the roots of guides 1 and 2; all three roots on one line.
  const std::vector<GuideFrameRef> frames{{1, 2}, {1, 1}, {2, 2}};
  const std::vector<DenseStrand> strands(1);
  auto pass = StrandInterpolationPass::create(device(), {3, 2, 2, frames, strands});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const std::vector<glm::vec3> guides{{0, 0, 0}, {0, -1, 0}, {1, 0, 0}, {1, -1, 0}, {2, 0, 0}, {2, -1, 0}};
  auto collapsed = (*pass)->updateGuides(guides);
  ASSERT_FALSE(collapsed.has_value());
  EXPECT_THAT(collapsed.error().message, HasSubstr("guide 0's root is collinear"));
}

// ---- The compiled shader ------------------------------------------------------------------

TEST(StrandInterpolationShader, EveryFloatAddMultiplyAndDivideIsNoContraction) {
  // SPIR-V: OpDecorate (71) <id> NoContraction (42); the arithmetic opcodes whose rounding the
  // CPU reference fixes: OpFAdd 129, OpFSub 131, OpFMul 133, OpFDiv 136, OpVectorTimesScalar 142.
  const auto words = shaders::findSpirv("strand_interpolation.comp");
  ASSERT_TRUE(words.has_value());
  std::set<std::uint32_t> noContraction;
  std::vector<std::uint32_t> arithmetic;
  for (std::size_t at = 5; at < words->size();) {
    const std::uint32_t opcode = (*words)[at] & 0xffffu;
    const std::uint32_t count = (*words)[at] >> 16;
    ASSERT_GT(count, 0u);
    if (opcode == 71 && count >= 3 && (*words)[at + 2] == 42) noContraction.insert((*words)[at + 1]);
    if (opcode == 129 || opcode == 131 || opcode == 133 || opcode == 136 || opcode == 142)
      arithmetic.push_back((*words)[at + 2]);  // result id
    at += count;
  }
  ASSERT_GT(arithmetic.size(), 40u);
  for (std::uint32_t id : arithmetic) EXPECT_TRUE(noContraction.count(id)) << "%" << id << " may be contracted";
}

}  // namespace
}  // namespace mane::render
