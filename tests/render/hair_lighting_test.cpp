// The per-vertex hair shading pass (render/passes/hair_lighting_pass.hpp) against independent
// references:
//  - radiance: at every vertex of straight strands in many orientations, the Marschner radiance
//    of the CPU model (render/luts/marschner.hpp, double precision) for that vertex's tangent,
//    light and eye directions, plus the ambient term;
//  - shadows: behind a sheet of hair, the first light's transmittance at each vertex matches a
//    ray cast through the sheet's strands (render/passes/opacity_shadow_map_reference.hpp), in both shadow modes,
//    with the sheet and the shaded strands in two grooms (two maps, multiplied); the other
//    lights stay unshadowed.
// Validation layers on; any message fails a test (VulkanTest).

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "render/luts/hair_environment.hpp"
#include "render/luts/marschner.hpp"
#include "render/luts/marschner_lut.hpp"
#include "render/passes/opacity_shadow_map_reference.hpp"
#include "render/environment/spherical_harmonics.hpp"
#include "render/passes/hair_density_pass.hpp"
#include "render/passes/hair_lighting_pass.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/strand_looks.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

// xorshift64*: a fixed sequence, so every run tests the same strands.
class Random {
public:
  explicit Random(std::uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 1) {}
  double uniform() {  // [0, 1)
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return double((state_ * 0x2545F4914F6CDD1Dull) >> 11) * 0x1.0p-53;
  }
  glm::dvec3 direction() {
    for (;;) {
      const glm::dvec3 p(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1);
      const double length = glm::length(p);
      if (length > 0.1 && length <= 1.0) return p / length;
    }
  }

private:
  std::uint64_t state_;
};

/// Strands as the pass reads them: positions (w = t) and tangents, strand-major.
struct Strands {
  std::vector<glm::vec4> positions;
  std::vector<glm::vec4> tangents;
  std::uint32_t vertices = 0;
  std::uint32_t count() const { return std::uint32_t(positions.size() / vertices); }

  void addStraight(glm::vec3 root, glm::vec3 tip) {
    const glm::vec3 tangent = glm::normalize(tip - root);
    for (std::uint32_t i = 0; i < vertices; ++i) {
      const float t = float(i) / float(vertices - 1);
      positions.emplace_back(glm::mix(root, tip, t), t);
      tangents.emplace_back(tangent, 0.0f);
    }
  }
};

class HairLightingTest : public testing::VulkanTest {
protected:
  Buffer upload(std::span<const glm::vec4> values) {
    return Buffer::withData(device(), std::as_bytes(values),
                            vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer);
  }

  std::vector<glm::vec4> readBack(const Buffer& buffer) {
    const Buffer host(device(), buffer.size(), vk::BufferUsageFlagBits::eTransferDst,
                      vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      commands.copyBuffer(*buffer.buffer(), *host.buffer(), vk::BufferCopy{.size = buffer.size()});
    });
    std::vector<glm::vec4> values(buffer.size() / sizeof(glm::vec4));
    std::memcpy(values.data(), host.mapped().data(), buffer.size());
    return values;
  }

  MarschnerLut& lut(const HairShadingParams& params) {
    auto created = MarschnerLut::create(device(), params);
    if (!created) throw std::runtime_error(created.error().message);
    lut_ = std::make_unique<MarschnerLut>(std::move(*created));
    return *lut_;
  }

private:
  std::unique_ptr<MarschnerLut> lut_;
};

// A camera at (0, 0, 0.5) looking at the origin; the pass takes the eye from the matrix.
const glm::vec3 kEye(0.0f, 0.0f, 0.5f);
glm::mat4 viewProjection() {
  return glm::perspectiveRH_ZO(0.8f, 1.0f, 0.01f, 3.0f) * glm::lookAtRH(kEye, glm::vec3(0), glm::vec3(0, 1, 0));
}

glm::dvec3 ambientAlbedo(const HairShadingParams& params) {
  const AzimuthalLobes albedo = azimuthalAlbedo(params, 1.0);
  return albedo.tt + albedo.trt + glm::dvec3(albedo.r);
}

// Straight strands (no tangent turns, so the lookups read mip level 0) in 200 random
// orientations: the GPU radiance equals the CPU model within 2 % per channel where the value
// is above 1 % of the largest (the LUTs reproduce the model within 1 %, marschner_lut.hpp;
// lavapipe's asin/acos move a lookup by < 0.05 texel).
TEST_F(HairLightingTest, VertexRadianceMatchesTheCpuModel) {
  const HairShadingParams params = blondeHairParams();
  const MarschnerLut& table = lut(params);
  Random random(3);
  Strands strands{.vertices = 4};
  for (int s = 0; s < 200; ++s) {
    const glm::vec3 centre = glm::vec3(0.1 * random.direction());
    const glm::vec3 half = glm::vec3(0.02 * random.direction());
    strands.addStraight(centre - half, centre + half);
  }
  const Buffer positions = upload(strands.positions);
  const Buffer tangents = upload(strands.tangents);
  auto shadows = HairShadowPass::create(device());
  ASSERT_TRUE(shadows.has_value()) << shadows.error().message;
  auto pass =
      HairLightingPass::create(device(), table, **shadows, positions, tangents, strands.count(), strands.vertices);
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const std::vector<DirectionalLight> lights{
      {.direction = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)), .color = {1.0f, 0.9f, 0.8f}, .intensity = 2.0f},
      {.direction = glm::normalize(glm::vec3(-0.2f, 0.3f, -0.9f)), .intensity = 3.0f}};
  const glm::vec3 ambient(0.02f, 0.025f, 0.03f);
  ASSERT_TRUE((*pass)->update(viewProjection(), lights, ambient, (*shadows)->uniforms()).has_value());
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });
  const std::vector<glm::vec4> radiance = readBack((*pass)->radiance());

  std::vector<glm::dvec3> expected;
  double largest = 0.0;
  for (std::size_t v = 0; v < strands.positions.size(); ++v) {
    const glm::dvec3 p(strands.positions[v]);
    const glm::dvec3 toEye = glm::normalize(glm::dvec3(kEye) - p);
    glm::dvec3 sum = glm::dvec3(ambient) * ambientAlbedo(params);
    for (const DirectionalLight& light : lights)
      sum += hairScattering(params, glm::dvec3(light.direction), toEye, glm::dvec3(strands.tangents[v])) *
             glm::dvec3(light.color * light.intensity);
    expected.push_back(sum);
    largest = std::max({largest, sum.r, sum.g, sum.b});
  }
  double worst = 0.0;
  for (std::size_t v = 0; v < expected.size(); ++v) {
    EXPECT_EQ(radiance[v].a, 1.0f) << "vertex " << v << ": no shadow maps, full transmittance";
    for (int c = 0; c < 3; ++c) {
      if (expected[v][c] < 0.01 * largest) continue;
      const double error = std::abs(radiance[v][c] - expected[v][c]) / expected[v][c];
      worst = std::max(worst, error);
      EXPECT_LT(error, 0.02) << "vertex " << v << " channel " << c << ": GPU " << radiance[v][c] << " CPU "
                             << expected[v][c];
    }
  }
  std::printf("per-vertex radiance: worst relative error %.4f over %zu vertices\n", worst, expected.size());
}

// Under an environment and no lights, each vertex shows the environment scattered by the lobes
// (render/luts/hair_environment.hpp, whose own test holds its weights to the full model): each band
// of the sky's radiance at the tangent times the band's weights at the vertex's θr, computed here
// at the exact θr, where the pass interpolates its table linearly between samples 2.8° apart
// (within 1 %). The sky is of bands 0 to 2 only, so its nine harmonics hold it whole; the
// strands' colours multiply the TT and TRT lobes alone.
TEST_F(HairLightingTest, TheEnvironmentLightsEachFibreThroughItsLobes) {
  const HairShadingParams params = blondeHairParams();
  const MarschnerLut& table = lut(params);
  Random random(5);
  Strands strands{.vertices = 2};
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    strands.addStraight(-0.02f * axis, 0.02f * axis);
  for (int s = 0; s < 40; ++s) {
    const glm::vec3 root(0.3 * random.direction());
    strands.addStraight(root, root + glm::vec3(0.02 * random.direction()));
  }
  CubeMap sky{.size = 32};
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < sky.size; ++row)
      for (int column = 0; column < sky.size; ++column) {
        const glm::vec3 d = cubeDirection(face, {(column + 0.5f) / 32.0f, (row + 0.5f) / 32.0f});
        sky.faces[face].push_back(glm::vec3(0.5f + 0.3f * d.y + 0.4f * d.y * d.y + 0.2f * d.x * d.z, 0.6f, 0.3f));
      }
  const SphericalHarmonics9 radiance = projectRadiance(sky);
  SphericalHarmonics9 irradianceOverPi = irradianceFromRadiance(radiance);
  for (glm::vec3& coefficient : irradianceOverPi) coefficient /= float(std::numbers::pi);
  std::vector<HairStrandLook> looks(strands.count());
  for (HairStrandLook& look : looks) look.colour = glm::vec3(random.uniform(), random.uniform(), random.uniform());

  const Buffer positions = upload(strands.positions);
  const Buffer tangents = upload(strands.tangents);
  auto shadows = HairShadowPass::create(device());
  ASSERT_TRUE(shadows.has_value()) << shadows.error().message;
  auto pass =
      HairLightingPass::create(device(), table, **shadows, positions, tangents, strands.count(), strands.vertices);
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const Buffer looksBuffer = uploadStrandLooks(device(), looks, strands.count());
  ASSERT_TRUE((*pass)->setStrandLooks(looksBuffer).has_value());
  (*pass)->setEnvironment(irradianceOverPi);
  ASSERT_TRUE((*pass)->update(viewProjection(), {}, glm::vec3(0.0f), (*shadows)->uniforms()).has_value());
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });
  const std::vector<glm::vec4> shaded = readBack((*pass)->radiance());
  double worst = 0.0, lowest = 1e9, highest = 0.0;
  for (std::size_t v = 0; v < strands.positions.size(); ++v) {
    const glm::dvec3 tangent(strands.tangents[v]);
    const glm::dvec3 toEye = glm::normalize(glm::dvec3(kEye) - glm::dvec3(strands.positions[v]));
    const HairEnvironmentBands bands =
        hairEnvironmentBands(params, std::asin(std::clamp(glm::dot(toEye, tangent), -1.0, 1.0)));
    const std::array<float, 9> y = harmonicsAt(glm::vec3(tangent));
    const std::array<glm::dvec3, 3> atTangent{glm::dvec3(radiance[0] * y[0]),
                                              glm::dvec3(radiance[1] * y[1] + radiance[2] * y[2] + radiance[3] * y[3]),
                                              glm::dvec3(radiance[4] * y[4] + radiance[5] * y[5] + radiance[6] * y[6] +
                                                         radiance[7] * y[7] + radiance[8] * y[8])};
    const glm::dvec3 colour(looks[v / strands.vertices].colour);
    glm::dvec3 expected(0.0);
    for (int l = 0; l < 3; ++l) expected += (bands.crossed[l] * colour + bands.reflected[l]) * atTangent[l];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(shaded[v][c], expected[c], 1e-2 * expected[c]) << "vertex " << v << " channel " << c;
      worst = std::max(worst, std::abs(shaded[v][c] - expected[c]) / expected[c]);
    }
    lowest = std::min(lowest, expected.r);
    highest = std::max(highest, expected.r);
  }
  std::printf("environment through the lobes: worst relative error %.5f\n", worst);
  EXPECT_GT(highest - lowest, 0.05 * highest);  // fibres along y see the sky's gradient differently
}

// Strands at the middle of a shell of hair 3 cm thick receive e^−τ of the environment they would
// receive without it, τ the shell's optical depth along a radius (render/passes/hair_density_pass.hpp,
// whose own test checks the visibility in every direction): the lit radiance with and without the
// occlusion volume, vertex by vertex, within 0.03.
TEST_F(HairLightingTest, TheHairAroundAFibreHidesTheEnvironmentFromIt) {
  const HairShadingParams params = blondeHairParams();
  const MarschnerLut& table = lut(params);
  constexpr double inner = 0.08, outer = 0.11, segment = 0.004, width = 1.5e-3;
  Random random(9);
  std::vector<glm::vec4> shell;
  double length = 0.0;
  while (shell.size() < 2 * 30000) {
    const glm::dvec3 p(2 * random.uniform() - 1, 2 * random.uniform() - 1, 2 * random.uniform() - 1);
    const double r = glm::length(p) * outer;
    if (glm::length(p) > 1.0 || r < inner) continue;
    const glm::dvec3 along = glm::normalize(glm::cross(p, random.direction()));
    shell.emplace_back(glm::vec3(glm::normalize(p) * r - 0.5 * segment * along), 0.0f);
    shell.emplace_back(glm::vec3(glm::normalize(p) * r + 0.5 * segment * along), 1.0f);
    length += segment;
  }
  const double shellVolume = 4.0 * std::numbers::pi / 3.0 * (outer * outer * outer - inner * inner * inner);
  const double tau = width * std::numbers::pi / 4.0 * length / shellVolume * (outer - inner);
  const Buffer shellPositions = upload(shell);
  const HairShadowPass::Groom shellGroom{
      .strands = {.positions = &shellPositions, .strandCount = std::uint32_t(shell.size() / 2), .verticesPerStrand = 2},
      .width = float(width),
      .opacity = 1.0f,
      .extinction = 1.0f};
  auto density = HairDensityPass::create(device(), std::span(&shellGroom, 1));
  ASSERT_TRUE(density.has_value()) << density.error().message;
  const HairBounds bounds{.low = glm::vec3(-0.12f), .high = glm::vec3(0.12f)};
  (*density)->place(std::span(&bounds, 1));
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*density)->record(commands); });

  // Short strands every way through the shell's middle voxel's centre.
  const glm::vec3 middle((0.5f + HairDensityPass::kResolution / 2) * (*density)->voxelSide() -
                         0.5f * HairDensityPass::kResolution * (*density)->voxelSide());
  Strands strands{.vertices = 2};
  for (int s = 0; s < 20; ++s) {
    const glm::vec3 half(0.002 * random.direction());
    strands.addStraight(middle - half, middle + half);
  }
  CubeMap sky{.size = 16};
  for (auto& face : sky.faces) face.assign(16 * 16, glm::vec3(1.0f, 0.8f, 0.6f));
  SphericalHarmonics9 irradianceOverPi = irradianceFromRadiance(projectRadiance(sky));
  for (glm::vec3& coefficient : irradianceOverPi) coefficient /= float(std::numbers::pi);
  const Buffer positions = upload(strands.positions);
  const Buffer tangents = upload(strands.tangents);
  auto shadows = HairShadowPass::create(device());
  ASSERT_TRUE(shadows.has_value()) << shadows.error().message;
  std::vector<std::vector<glm::vec4>> shaded;
  for (const bool hidden : {false, true}) {
    auto pass =
        HairLightingPass::create(device(), table, **shadows, positions, tangents, strands.count(), strands.vertices);
    ASSERT_TRUE(pass.has_value()) << pass.error().message;
    (*pass)->setEnvironment(irradianceOverPi);
    if (hidden) (*pass)->setHairVisibility(density->get());
    ASSERT_TRUE((*pass)->update(viewProjection(), {}, glm::vec3(0.0f), (*shadows)->uniforms()).has_value());
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });
    shaded.push_back(readBack((*pass)->radiance()));
  }
  std::printf("shell τ %.3f: e^-τ %.4f, vertex 0 keeps %.4f\n", tau, std::exp(-tau), shaded[1][0].g / shaded[0][0].g);
  EXPECT_GT(tau, 1.0);
  for (std::size_t v = 0; v < strands.positions.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(shaded[0][v][c], 0.0f);
      EXPECT_NEAR(shaded[1][v][c] / shaded[0][v][c], std::exp(-tau), 0.03) << "vertex " << v << " channel " << c;
    }
}

// A sheet of 2,000 horizontal strands along x (r = 20 µm, α = κ = 1, about 6 per map texel row) 2–3 cm above 8 shaded
// strands along z; the key light shines down through the sheet. The shaded strands are a second groom with a negligible
// opacity (their own map multiplies in exp(−1e-6·…)). Tolerance: the brief's 0.05 on the mean |ΔT| against the ray cast
// (filtered with the map's kernel at its texel size, as in opacity_shadow_map_test.cpp); the radiance composes ambient
// + S·E·T for the key light and unshadowed S·E for the fill light within 2 %. All the shaded points lie behind the
// whole sheet, so both modes read the full column of opacity: this checks the wiring and the product of two maps;
// opacity_shadow_map_test.cpp checks the modes' depth interpolation.
TEST_F(HairLightingTest, FirstLightIsShadowedByTheHairInFrontOfIt) {
  const HairShadingParams params = blondeHairParams();
  const MarschnerLut& table = lut(params);
  constexpr float kRadius = 2e-5f;
  const glm::vec3 towardLight = glm::normalize(glm::vec3(0.1f, 1.0f, 0.05f));
  Random random(17);
  Strands sheet{.vertices = 16};
  for (int s = 0; s < 2000; ++s) {
    const float z = float(0.08 * random.uniform() - 0.04);
    const float y = float(0.02 + 0.01 * random.uniform());
    sheet.addStraight({-0.05f, y, z}, {0.05f, y + 0.002f, z + 0.003f});
  }
  Strands shaded{.vertices = 16};
  for (int s = 0; s < 8; ++s) {  // across the sheet's strands, so each crosses the shadows of many
    const float x = -0.035f + 0.01f * float(s);
    shaded.addStraight({x, 0.0f, -0.035f}, {x + 0.001f, 0.0f, 0.035f});
  }
  const Buffer sheetPositions = upload(sheet.positions);
  const Buffer shadedPositions = upload(shaded.positions);
  const Buffer shadedTangents = upload(shaded.tangents);
  auto reference = OpacityReference::create({.positions = sheet.positions,
                                             .strandCount = sheet.count(),
                                             .verticesPerStrand = sheet.vertices,
                                             .strandRadius = kRadius},
                                            towardLight);
  ASSERT_TRUE(reference.has_value()) << reference.error().message;
  const std::vector<DirectionalLight> lights{
      {.direction = towardLight, .intensity = 2.0f},
      {.direction = glm::normalize(glm::vec3(-0.3f, 0.2f, 0.9f)), .color = {0.6f, 0.7f, 1.0f}, .intensity = 1.0f}};
  const glm::vec3 ambient(0.01f);

  for (const HairShadowMode mode : {HairShadowMode::kOpacityShadowMap, HairShadowMode::kDeepOpacityMap}) {
    SCOPED_TRACE(mode == HairShadowMode::kDeepOpacityMap ? "deep opacity map" : "opacity shadow map");
    auto shadows = HairShadowPass::create(device());
    ASSERT_TRUE(shadows.has_value()) << shadows.error().message;
    const std::array grooms{
        HairShadowPass::Groom{.strands = {&sheetPositions, sheet.count(), sheet.vertices}, .width = 2 * kRadius},
        HairShadowPass::Groom{
            .strands = {&shadedPositions, shaded.count(), shaded.vertices}, .width = 2 * kRadius, .opacity = 1e-6f}};
    ASSERT_TRUE((*shadows)->setGrooms(grooms, {.mode = mode, .resolution = 512}).has_value());
    const BoundingSphere sheetSphere = *boundingSphere(sheet.positions);
    ASSERT_TRUE((*shadows)->setBounds(0, sheetSphere).has_value());
    ASSERT_TRUE((*shadows)->setBounds(1, *boundingSphere(shaded.positions)).has_value());
    auto pass = HairLightingPass::create(device(), table, **shadows, shadedPositions, shadedTangents, shaded.count(),
                                         shaded.vertices);
    ASSERT_TRUE(pass.has_value()) << pass.error().message;
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      (*shadows)->record(commands, towardLight);
      ASSERT_TRUE((*pass)->update(viewProjection(), lights, ambient, (*shadows)->uniforms()).has_value());
      (*pass)->record(commands);
    });
    EXPECT_EQ((*shadows)->uniforms().count.x, 2u);
    const std::vector<glm::vec4> radiance = readBack((*pass)->radiance());

    const double texel = 2.0 * sheetSphere.radius / 512.0;
    double meanError = 0.0, meanTransmittance = 0.0;
    for (std::size_t v = 0; v < shaded.positions.size(); ++v) {
      const glm::dvec3 p(shaded.positions[v]);
      const double expectedT =
          reference->transmittance(reference->filteredOpacity(p, texel, int(std::ceil(texel / kRadius / 2.0))));
      meanError += std::abs(radiance[v].a - expectedT) / double(shaded.positions.size());

      meanTransmittance += expectedT / double(shaded.positions.size());
      const glm::dvec3 toEye = glm::normalize(glm::dvec3(kEye) - p);
      const glm::dvec3 tangent(shaded.tangents[v]);
      const glm::dvec3 expected =
          glm::dvec3(ambient) * ambientAlbedo(params) +
          hairScattering(params, glm::dvec3(lights[0].direction), toEye, tangent) * 2.0 * double(radiance[v].a) +
          hairScattering(params, glm::dvec3(lights[1].direction), toEye, tangent) * glm::dvec3(lights[1].color);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(radiance[v][c], expected[c], 0.02 * expected[c]) << "vertex " << v << " channel " << c;
    }
    std::printf("shadowed strands: mean reference transmittance %.3f, mean |ΔT| %.4f\n", meanTransmittance, meanError);
    EXPECT_LT(meanTransmittance, 0.8) << "the sheet must actually shadow the strands";
    EXPECT_LT(meanError, 0.05);
  }
}

TEST_F(HairLightingTest, RejectsStrandsItCannotShade) {
  const MarschnerLut& table = lut(darkHairParams());
  auto shadows = HairShadowPass::create(device());
  ASSERT_TRUE(shadows.has_value());
  const Buffer small(device(), 64,
                     vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer,
                     vk::MemoryPropertyFlagBits::eDeviceLocal);
  EXPECT_FALSE(HairLightingPass::create(device(), table, **shadows, small, small, 0, 4).has_value()) << "no strands";
  EXPECT_FALSE(HairLightingPass::create(device(), table, **shadows, small, small, 1, 1).has_value()) << "1 vertex";
  const auto tooFew = HairLightingPass::create(device(), table, **shadows, small, small, 2, 4);
  ASSERT_FALSE(tooFew.has_value()) << "8 vertices in a 4-vertex buffer";
  EXPECT_NE(tooFew.error().message.find("bytes"), std::string::npos) << tooFew.error().message;
  auto pass = HairLightingPass::create(device(), table, **shadows, small, small, 1, 4);
  ASSERT_TRUE(pass.has_value());
  const std::array bad{DirectionalLight{.direction = glm::vec3(0.0f)}};
  EXPECT_FALSE((*pass)->update(viewProjection(), bad, glm::vec3(0), (*shadows)->uniforms()).has_value());
}

}  // namespace
}  // namespace mane::render
