// The hair's density grid and the environment's visibility through it
// (render/passes/hair_density_pass.hpp), against closed forms: the fibre length the splat must
// conserve, and a hemispherical cap of hair over a point, whose transmittance along every
// direction under it is exp(−τ) with τ the cap's optical depth and 1 along every other.

#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/passes/hair_density_pass.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr double kPi = std::numbers::pi;

struct Cap {
  std::vector<glm::vec4> positions;  // two vertices per strand
  double length = 0.0;               // metres of fibre
};

// Segments of length `segment` tangent to spheres about `centre`, between radii `inner` and
// `outer` above the plane through it facing y, spread evenly through that half shell's volume and turned every
// way round their radius.
Cap hairCap(glm::dvec3 centre, double inner, double outer, double segment, std::size_t count) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Cap cap;
  while (cap.positions.size() < 2 * count) {
    const glm::dvec3 p(2 * uniform(random) - 1, uniform(random), 2 * uniform(random) - 1);
    const double r = glm::length(p) * outer;
    if (glm::length(p) > 1.0 || r < inner) continue;
    const glm::dvec3 radial = glm::normalize(p);
    const glm::dvec3 helper = std::abs(radial.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(radial, helper)), v = glm::cross(radial, u);
    const double turn = 2.0 * kPi * uniform(random);
    const glm::dvec3 along = std::cos(turn) * u + std::sin(turn) * v;
    const glm::dvec3 middle = centre + radial * r;
    cap.positions.emplace_back(glm::vec3(middle - 0.5 * segment * along), 0.0f);
    cap.positions.emplace_back(glm::vec3(middle + 0.5 * segment * along), 1.0f);
    cap.length += segment;
  }
  return cap;
}

class HairDensityTest : public testing::VulkanTest {
protected:
  // The occlusion of every voxel, x fastest (RGBA, from fp16).
  std::vector<glm::vec4> readOcclusion(const HairDensityPass& pass) {
    constexpr std::uint32_t side = HairDensityPass::kResolution;
    const Buffer host(device(), vk::DeviceSize(side) * side * side * 8, vk::BufferUsageFlagBits::eTransferDst,
                      vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      using Stage = vk::PipelineStageFlagBits2;
      using Access = vk::AccessFlagBits2;
      using Layout = vk::ImageLayout;
      transition(commands, pass.occlusion(), Layout::eShaderReadOnlyOptimal, Layout::eTransferSrcOptimal,
                 Stage::eAllCommands, Access::eMemoryWrite, Stage::eCopy, Access::eTransferRead);
      commands.copyImageToBuffer(*pass.occlusion().image(), Layout::eTransferSrcOptimal, *host.buffer(),
                                 vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                                     .imageExtent = {side, side, side}});
      transition(commands, pass.occlusion(), Layout::eTransferSrcOptimal, Layout::eShaderReadOnlyOptimal, Stage::eCopy,
                 Access::eTransferRead, Stage::eAllCommands, Access::eShaderSampledRead);
    });
    std::vector<std::uint16_t> halves(std::size_t(side) * side * side * 4);
    std::memcpy(halves.data(), host.mapped().data(), halves.size() * 2);
    std::vector<glm::vec4> voxels(halves.size() / 4);
    for (std::size_t i = 0; i < voxels.size(); ++i)
      for (int c = 0; c < 4; ++c) voxels[i][c] = glm::unpackHalf1x16(halves[4 * i + std::size_t(c)]);
    return voxels;
  }

  std::vector<std::uint32_t> readDensity(const HairDensityPass& pass) {
    const Buffer host(device(), pass.density().size(), vk::BufferUsageFlagBits::eTransferDst,
                      vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      commands.copyBuffer(*pass.density().buffer(), *host.buffer(), vk::BufferCopy{.size = pass.density().size()});
    });
    std::vector<std::uint32_t> values(pass.density().size() / 4);
    std::memcpy(values.data(), host.mapped().data(), pass.density().size());
    return values;
  }
};

// A cap 3 cm thick, 8 cm from a point under it, of 1 mm fibres 4 mm long, opacity 0.8, extinction
// 1.2. Optical depth along a radius through it, taking the fibres as turned every way (the model's
// mean shadow ℓw·π/4): τ = κα·w·(π/4)·(length per volume)·thickness.
TEST_F(HairDensityTest, ACapOfHairHidesTheSkyAboveAPointAndNotTheGroundBelow) {
  constexpr double inner = 0.08, outer = 0.11, segment = 0.004, width = 1e-3, opacity = 0.8, extinction = 1.2;
  // The grid round a cube 24 cm a side about the origin: 22 voxels across and one spare each side.
  const HairBounds bounds{.low = glm::vec3(-0.12f), .high = glm::vec3(0.12f)};
  constexpr int side = HairDensityPass::kResolution;
  // The cap is centred on the middle of a voxel, whose occlusion is read back below.
  const glm::ivec3 centre(side / 2);
  const double voxel = 0.24 / (side - 2);
  const glm::dvec3 middle = glm::dvec3(-0.5 * side * voxel) + (glm::dvec3(centre) + 0.5) * voxel;
  const Cap cap = hairCap(middle, inner, outer, segment, 24000);
  const double halfShell = 2.0 * kPi / 3.0 * (outer * outer * outer - inner * inner * inner);
  const double tau = extinction * opacity * width * kPi / 4.0 * cap.length / halfShell * (outer - inner);
  const double hidden = std::exp(-tau);

  const Buffer positions =
      Buffer::withData(device(), std::as_bytes(std::span(cap.positions)),
                       vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer);
  const HairShadowPass::Groom groom{.strands = {.positions = &positions,
                                                .strandCount = std::uint32_t(cap.positions.size() / 2),
                                                .verticesPerStrand = 2},
                                    .width = float(width),
                                    .opacity = float(opacity),
                                    .extinction = float(extinction)};
  auto pass = HairDensityPass::create(device(), std::span(&groom, 1));
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  (*pass)->place(std::span(&bounds, 1));
  ASSERT_EQ((*pass)->voxels(), glm::uvec3(side));
  ASSERT_NEAR((*pass)->voxelSide(), voxel, 1e-7);
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });

  // The splat conserves the fibre: Σ density = 2²⁰·κα·w·(π/4)·ℓ/s², less than half a unit per piece.
  double units = 0.0;
  for (const std::uint32_t value : readDensity(**pass)) units += value;
  const double expectedUnits = 1048576.0 * extinction * opacity * width * kPi / 4.0 * cap.length / (voxel * voxel);
  EXPECT_NEAR(units, expectedUnits, 0.5 * double(cap.positions.size() / 2));

  // The voxel holding the cap's centre: a surface facing up sees the sky through the cap, one
  // facing down the open ground, one facing sideways half of each; V(ω) ≈ a + b·ω.
  const std::vector<glm::vec4> occlusion = readOcclusion(**pass);
  const glm::vec4 o = occlusion[std::size_t((centre.z * side + centre.y) * side + centre.x)];
  const auto facing = [&](glm::vec3 n) { return 1.0 - o.w - 2.0 / 3.0 * glm::dot(glm::vec3(o), n); };
  std::printf("cap τ %.3f: facing up %.4f (e^-τ %.4f), down %.4f, sideways %.4f\n", tau, facing({0, 1, 0}), hidden,
              facing({0, -1, 0}), facing({1, 0, 0}));
  EXPECT_GT(tau, 1.0);
  EXPECT_NEAR(facing({0, 1, 0}), hidden, 0.03);
  EXPECT_NEAR(facing({0, -1, 0}), 1.0, 0.03);
  EXPECT_NEAR(facing({1, 0, 0}), 0.5 * (1.0 + hidden), 0.03);
  // Far outside the cap, nothing is hidden.
  EXPECT_NEAR(occlusion[0].w, 0.0, 1e-3);
}

TEST_F(HairDensityTest, RefusesGroomsWithoutStrands) {
  const HairShadowPass::Groom empty{};
  EXPECT_FALSE(HairDensityPass::create(device(), {}).has_value());
  const auto pass = HairDensityPass::create(device(), std::span(&empty, 1));
  ASSERT_FALSE(pass.has_value());
  EXPECT_NE(pass.error().message.find("groom 0"), std::string::npos) << pass.error().message;
}

}  // namespace
}  // namespace mane::render
