// The sea on the GPU.
//
// Oracles: the CPU's sum of the same waves (physics/ocean_waves.hpp), in double precision; the
// foam's exponential fade, 2^(−t/T½), over frames in which nothing breaks; the crests the CPU's
// Jacobian finds breaking, laid into the foam map; a foam source's
// Gaussian and its integral π r²; the horizon line computed from the camera alone, below which
// every pixel must show water; and a flat sea's mirror image of an ellipsoid, traced on the CPU.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "physics/ocean_waves.hpp"
#include "render/passes/ocean_pass.hpp"
#include "render/renderer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

OceanData oceanData(const physics::OceanWaves& waves) {
  OceanData data;
  for (const physics::GerstnerWave& w : waves.waves())
    data.waves.emplace_back(w.direction.x, w.direction.y, w.wavenumber, w.amplitude);
  data.choppiness = waves.choppiness();
  return data;
}

FrameInput frameAt(const physics::OceanWaves& waves, double time, float seconds) {
  FrameInput frame;
  frame.ocean = OceanFrame{.phases = std::vector<float>(waves.waves().size()), .seconds = seconds};
  waves.phasesAt(time, frame.ocean->phases);
  return frame;
}

// The foam step alone, waited for (it leaves the map in GENERAL, where it rests).
struct FoamStep {
  const OceanPass* pass;
  void declare(FrameGraph::Builder& builder) const { pass->declareFoam(builder); }
  void execute(const vk::raii::CommandBuffer& commands) const { pass->recordFoam(commands); }
};
void recordFoamAlone(const Device& device, const OceanPass& pass) {
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    FrameGraph::recordAlone(commands, PassName::kOcean, FoamStep{&pass});
  });
}

class OceanTest : public testing::VulkanTest {};

TEST_F(OceanTest, TheGpuSumsTheWavesAsTheCpuDoesWithinATenthOfAMillimetre) {
  const auto waves = physics::OceanWaves::create({.windSpeed = 12.0f, .choppiness = 0.9f, .shortestWavelength = 0.5f});
  ASSERT_TRUE(waves) << waves.error().message;
  auto pass = OceanPass::create(device(), oceanData(*waves));
  ASSERT_TRUE(pass) << pass.error().message;
  std::vector<glm::vec2> rests;
  for (float x = -150.0f; x <= 150.0f; x += 7.7f)
    for (float z = -150.0f; z <= 150.0f; z += 9.1f) rests.emplace_back(x, z);
  float worstPosition = 0.0f;
  float worstNormal = 0.0f;
  float worstJacobian = 0.0f;
  for (double time : {0.0, 12.5, 3600.25}) {
    ASSERT_TRUE((*pass)->prepare(frameAt(*waves, time, 0.0f), 1.0f));
    const std::vector<OceanProbeSample> gpu = (*pass)->probe(rests);
    ASSERT_EQ(gpu.size(), rests.size());
    for (std::size_t i = 0; i < rests.size(); ++i) {
      const physics::OceanSample cpu = waves->sample(rests[i], time);
      const glm::vec3 displacement = cpu.position - glm::vec3(rests[i].x, 0.0f, rests[i].y);
      worstPosition = std::max(worstPosition, glm::length(gpu[i].displacement - displacement));
      worstNormal = std::max(worstNormal, glm::length(gpu[i].normal - cpu.normal));
      worstJacobian = std::max(worstJacobian, std::abs(gpu[i].jacobian - cpu.jacobian));
    }
  }
  RecordProperty("worst_position_m", std::to_string(worstPosition));
  EXPECT_LT(worstPosition, 1e-4f);
  EXPECT_LT(worstNormal, 1e-4f);
  EXPECT_LT(worstJacobian, 1e-4f);
}

TEST_F(OceanTest, FoamFadesWithItsHalfLifeWhereNothingBreaks) {
  // One wave of λ k A = 1.5, so J = 1 − 1.5 cos θ: where cos θ > 0.43 the crest breaks.
  const float k = 0.2f;
  const float a = 1.0f;
  const auto waves = physics::OceanWaves::fromWaves(
      {physics::GerstnerWave{
          .direction = {1.0f, 0.0f}, .wavenumber = k, .angularFrequency = std::sqrt(9.81f * k), .amplitude = a}},
      1.5f / (k * a));
  ASSERT_TRUE(waves);
  OceanData data = oceanData(*waves);
  data.foamHalfLife = 2.0f;
  data.foamGrowth = 1000.0f;  // a breaking crest covers its texel at once
  data.foamExtent = 64.0f;
  data.foamResolution = 64;
  auto pass = OceanPass::create(device(), data);
  ASSERT_TRUE(pass) << pass.error().message;
  const auto runFoam = [&](const FrameInput& frame) {
    ASSERT_TRUE((*pass)->prepare(frame, 1.0f));
    recordFoamAlone(device(), **pass);
  };
  // Breaking where J < threshold − 0.2 at the first phases, fully; then half a period later
  // J = 1 + 1.5 cos θ there, and nothing breaks where it did.
  FrameInput frame = frameAt(*waves, 0.0, 0.1f);
  runFoam(frame);
  const float phase = frame.ocean->phases[0];
  frame.ocean->phases[0] = phase + std::numbers::pi_v<float>;
  frame.ocean->seconds = 0.25f;
  for (int i = 0; i < 16; ++i) runFoam(frame);
  const std::vector<float> foam = (*pass)->readFoam();
  ASSERT_EQ(foam.size(), 64u * 64u);
  const double expected = std::exp2(-16 * 0.25 / 2.0);
  int checked = 0;
  for (int texel = 0; texel < 64; ++texel) {
    const float x = -32.0f + (float(texel) + 0.5f);
    const float j = 1.0f - 1.5f * std::cos(k * x + phase);
    if (j > data.foamThreshold - 0.21f) continue;
    for (int row = 0; row < 64; ++row) ASSERT_NEAR(foam[std::size_t(row) * 64 + texel] / expected, 1.0, 0.02) << texel;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST_F(OceanTest, AFoamSourceLaysItsGaussianAtItsRestPoint) {
  // A still sea (one wave of no height), so nothing breaks and only the source lays foam.
  const auto waves = physics::OceanWaves::fromWaves(
      {physics::GerstnerWave{.direction = {1.0f, 0.0f}, .wavenumber = 0.1f, .angularFrequency = 1.0f}}, 0.0f);
  ASSERT_TRUE(waves);
  OceanData data = oceanData(*waves);
  data.foamExtent = 64.0f;
  data.foamResolution = 128;  // half a metre a texel
  auto pass = OceanPass::create(device(), data);
  ASSERT_TRUE(pass) << pass.error().message;
  // 2 per second at (10, −5) with r = 3 m, over 0.1 s: 0.2 at its centre.
  FrameInput frame = frameAt(*waves, 0.0, 0.1f);
  frame.ocean->foamSources = {{10.0f, -5.0f, 3.0f, 2.0f}};
  ASSERT_TRUE((*pass)->prepare(frame, 1.0f));
  recordFoamAlone(device(), **pass);
  const std::vector<float> foam = (*pass)->readFoam();
  ASSERT_EQ(foam.size(), 128u * 128u);
  double sum = 0.0;
  float worst = 0.0f;
  for (int row = 0; row < 128; ++row) {
    for (int column = 0; column < 128; ++column) {
      const glm::vec2 rest(-32.0f + 0.5f * (float(column) + 0.5f), -32.0f + 0.5f * (float(row) + 0.5f));
      const glm::vec2 d = rest - glm::vec2(10.0f, -5.0f);
      const float expected = 0.2f * std::exp(-glm::dot(d, d) / 9.0f);
      const float laid = foam[std::size_t(row) * 128 + std::size_t(column)];
      worst = std::max(worst, std::abs(laid - expected));
      sum += laid * 0.25;
    }
  }
  EXPECT_LT(worst, 0.2f * 2e-3f);
  // Its integral, 0.2 π r², within the share beyond 3 r that is left out (e⁻⁹).
  EXPECT_NEAR(sum / (0.2 * std::numbers::pi * 9.0), 1.0, 1e-3);
  // More sources than the pass holds, or a bad one, are refused by name.
  frame.ocean->foamSources.assign(kMaxFoamSources + 1, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  EXPECT_FALSE((*pass)->prepare(frame, 1.0f));
  frame.ocean->foamSources = {{0.0f, 0.0f, 0.0f, 1.0f}};
  const auto refused = (*pass)->prepare(frame, 1.0f);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("foam source 0"), std::string::npos) << refused.error().message;
}

TEST_F(OceanTest, CrestsBreakIntoTheFoamMapWhereTheCpusJacobianFallsUnderTheThreshold) {
  // A rough sea whose shortest wave spans 8 texels, so that no wave is faded for the map's spacing;
  // 100 texels a side, which the runs of texels the shader updates together do not divide.
  const auto waves = physics::OceanWaves::create({.windSpeed = 14.0f, .choppiness = 1.0f, .shortestWavelength = 0.8f});
  ASSERT_TRUE(waves) << waves.error().message;
  OceanData data = oceanData(*waves);
  data.foamThreshold = 0.9f;
  data.foamGrowth = 10.0f;  // over 0.1 s a crest adds its whole breaking share
  data.foamCenter = {3.0f, -7.0f};
  data.foamExtent = 10.0f;
  data.foamResolution = 100;
  auto pass = OceanPass::create(device(), data);
  ASSERT_TRUE(pass) << pass.error().message;
  const double time = 41.3;
  ASSERT_TRUE((*pass)->prepare(frameAt(*waves, time, 0.1f), 1.0f));
  recordFoamAlone(device(), **pass);
  const std::vector<float> foam = (*pass)->readFoam();
  ASSERT_EQ(foam.size(), 100u * 100u);
  float worst = 0.0f;
  int breaking = 0;
  for (int row = 0; row < 100; ++row) {
    for (int column = 0; column < 100; ++column) {
      const glm::vec2 rest = data.foamCenter - 5.0f + 0.1f * glm::vec2(float(column) + 0.5f, float(row) + 0.5f);
      const float jacobian = waves->sample(rest, time).jacobian;
      const float expected = std::clamp((data.foamThreshold - jacobian) / 0.2f, 0.0f, 1.0f);
      worst = std::max(worst, std::abs(foam[std::size_t(row) * 100 + std::size_t(column)] - expected));
      breaking += expected > 0.0f;
    }
  }
  RecordProperty("breaking_texels", breaking);
  RecordProperty("worst_difference", std::to_string(worst));
  EXPECT_GT(breaking, 500);
  EXPECT_LT(breaking, 9500);
  // The GPU's Jacobian within 1e-4 of the CPU's, as the probe finds it, is 5e-4 of breaking.
  EXPECT_LT(worst, 1e-3f);
}

class OceanRender : public testing::VulkanTest {};

// The direction of the eye's ray through the centre of pixel (x, y).
glm::vec3 eyeRay(const glm::mat4& clipToWorld, vk::Extent2D extent, int x, int y) {
  const glm::vec2 ndc((float(x) + 0.5f) / float(extent.width) * 2.0f - 1.0f,
                      (float(y) + 0.5f) / float(extent.height) * 2.0f - 1.0f);
  const glm::vec4 near = clipToWorld * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 far = clipToWorld * glm::vec4(ndc, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(far) / far.w - glm::vec3(near) / near.w);
}

// The background's colour, which no water shows.
constexpr glm::vec3 kBackground{1.0f, 0.0f, 1.0f};

TEST_F(OceanRender, TheProjectedGridLeavesNoBackgroundBelowTheHorizon) {
  const auto waves = physics::OceanWaves::create({.windSpeed = 14.0f, .choppiness = 0.9f});
  ASSERT_TRUE(waves);
  constexpr vk::Extent2D extent{160, 96};
  auto renderer = Renderer::create(device(), {.extent = extent});
  ASSERT_TRUE(renderer) << renderer.error().message;
  StaticScene scene;
  scene.ocean = oceanData(*waves);
  ASSERT_TRUE((*renderer)->setScene(scene));
  // Low over the water and looking up past the horizon, high and looking down, turned and tilted.
  const Camera cameras[] = {
      {.position = {0.0f, 3.0f, 0.0f},
       .target = {100.0f, 8.0f, 30.0f},
       .verticalFovRadians = 0.8f,
       .nearPlane = 0.1f,
       .farPlane = 30000.0f},
      {.position = {5.0f, 40.0f, -3.0f},
       .target = {-60.0f, 0.0f, 40.0f},
       .verticalFovRadians = 0.9f,
       .nearPlane = 0.1f,
       .farPlane = 30000.0f},
      {.position = {0.0f, 12.0f, 0.0f},
       .target = {0.0f, 11.0f, -100.0f},
       .up = {0.3f, 1.0f, 0.0f},
       .verticalFovRadians = 0.6f,
       .nearPlane = 0.1f,
       .farPlane = 30000.0f},
  };
  for (const Camera& camera : cameras) {
    FrameInput frame = frameAt(*waves, 7.0, 1.0f / 30.0f);
    frame.camera = camera;
    frame.background = kBackground;
    frame.ambient = glm::vec3(0.2f);
    frame.lights = {{.direction = glm::normalize(glm::vec3(0.3f, 0.5f, -0.4f)), .intensity = 2.0f}};
    ASSERT_TRUE((*renderer)->render(frame));
    const auto hdr = (*renderer)->readHdrOutput();
    ASSERT_TRUE(hdr);
    const float aspect = float(extent.width) / float(extent.height);
    const glm::mat4 clipToWorld = glm::inverse(camera.projection(aspect) * camera.view());
    const float pixelAngle = camera.verticalFovRadians / float(extent.height);
    int water = 0;
    int sky = 0;
    for (int y = 0; y < int(extent.height); ++y) {
      for (int x = 0; x < int(extent.width); ++x) {
        const glm::vec3 ray = eyeRay(clipToWorld, extent, x, y);
        const std::size_t i = (std::size_t(y) * extent.width + std::size_t(x)) * 4;
        const glm::vec3 colour(glm::unpackHalf1x16((*hdr)[i]), glm::unpackHalf1x16((*hdr)[i + 1]),
                               glm::unpackHalf1x16((*hdr)[i + 2]));
        const bool background = glm::length(colour - kBackground) < 0.05f;
        // More than a pixel below the horizon: water, whatever the waves do.
        if (ray.y < -std::sin(pixelAngle)) {
          ASSERT_FALSE(background) << "pixel " << x << ", " << y << " below the horizon shows the background";
          ++water;
        } else if (ray.y > std::sin(2.0f * pixelAngle) + 0.1f) {
          // Well above the highest crest seen from here: the sky.
          sky += background;
        }
      }
    }
    EXPECT_GT(water, 1000);
    (void)sky;
  }
}

TEST(OceanGridRows, KeepEveryRowWhoseRaysMeetTheSeaAndFewMore) {
  // Level, looking up, looking down, rolled, and under the sea; against the rays of 1,001 points
  // across each row of the grid: no row left out meets the sea within reach.
  const Camera cameras[] = {
      {.position = {0.0f, 9.0f, 48.0f}, .target = {0.0f, 9.0f, 0.0f}, .verticalFovRadians = 0.8f},
      {.position = {0.0f, 3.0f, 0.0f}, .target = {100.0f, 30.0f, 30.0f}, .verticalFovRadians = 0.8f},
      {.position = {5.0f, 40.0f, -3.0f}, .target = {-60.0f, 0.0f, 40.0f}, .verticalFovRadians = 0.9f},
      {.position = {0.0f, 12.0f, 0.0f}, .target = {0.0f, 11.0f, -100.0f}, .up = {0.6f, 1.0f, 0.0f}},
      {.position = {0.0f, -2.0f, 0.0f}, .target = {10.0f, -2.0f, 0.0f}},
  };
  const glm::uvec2 cells{150, 150};
  const float reach = 20000.0f;
  // Level or looking up, the horizon crosses the screen and the sky's rows are left out; rolled,
  // it spans every row; from under the sea every row is kept.
  const bool fewerThanThreeQuarters[] = {true, true, false, false, false};
  for (std::size_t c = 0; c < std::size(cameras); ++c) {
    const Camera& camera = cameras[c];
    const glm::mat4 clipToWorld = glm::inverse(camera.projection(16.0f / 9.0f) * camera.view());
    const GridRows rows = oceanGridRows(clipToWorld, camera.position, reach, cells);
    ASSERT_LE(rows.first + rows.count, cells.y) << c;
    ASSERT_GE(rows.count, 1u) << c;
    EXPECT_EQ(rows.count < cells.y * 3 / 4, fewerThanThreeQuarters[c]) << c;
    if (camera.position.y <= 0.0f) {
      EXPECT_EQ(rows.count, cells.y);
      continue;
    }
    std::uint32_t wasted = 0;
    for (std::uint32_t row = 0; row <= cells.y; ++row) {
      const float y = -kOceanGridOverhang + 2.0f * kOceanGridOverhang * float(row) / float(cells.y);
      bool sea = false;
      for (int i = 0; i <= 1000; ++i) {
        const glm::vec2 ndc(-kOceanGridOverhang + 2.0f * kOceanGridOverhang * float(i) / 1000.0f, y);
        const glm::vec4 near = clipToWorld * glm::vec4(ndc, 0.0f, 1.0f);
        const glm::vec4 far = clipToWorld * glm::vec4(ndc, 1.0f, 1.0f);
        const glm::vec3 ray = glm::vec3(far) / far.w - glm::vec3(near) / near.w;
        sea = sea || (ray.y < 0.0f && camera.position.y * glm::length(glm::vec2(ray.x, ray.z)) < -ray.y * reach);
      }
      const bool kept = row >= rows.first && row <= rows.first + rows.count;
      EXPECT_TRUE(kept || !sea) << "camera " << c << ": row " << row << " meets the sea but is left out";
      wasted += kept && !sea;
    }
    EXPECT_LE(wasted, 2u) << "camera " << c;
  }
}

TEST_F(OceanRender, TheShipHidesTheSkyInTheWatersReflection) {
  // A flat sea (one wave of no height) mirrors the sky, and a red ellipsoid above it hides the sky
  // along the rays it mirrors: where the eye's ray, mirrored at the water, passes well inside
  // the ellipsoid, the water is red; where it passes well outside, it shows the sky.
  const auto waves = physics::OceanWaves::fromWaves(
      {physics::GerstnerWave{.direction = {1.0f, 0.0f}, .wavenumber = 0.1f, .angularFrequency = 1.0f}}, 0.0f);
  ASSERT_TRUE(waves);
  constexpr vk::Extent2D extent{160, 96};
  auto renderer = Renderer::create(device(), {.extent = extent});
  ASSERT_TRUE(renderer) << renderer.error().message;
  StaticScene scene;
  scene.ocean = oceanData(*waves);
  scene.ocean->fogDensity = 0.0f;
  scene.ocean->fresnelPower = 1.0f;  // a strong reflection at every angle
  ASSERT_TRUE((*renderer)->setScene(scene));
  const Camera camera{.position = {0.0f, 3.0f, 0.0f},
                      .target = {30.0f, -1.0f, 0.0f},
                      .verticalFovRadians = 0.8f,
                      .nearPlane = 0.1f,
                      .farPlane = 30000.0f};
  const glm::vec3 centre(30.0f, 5.0f, 0.0f);
  const glm::vec3 radii(8.0f, 4.0f, 8.0f);
  FrameInput frame = frameAt(*waves, 0.0, 1.0f / 30.0f);
  frame.camera = camera;
  frame.ambient = glm::vec3(1.0f);
  frame.ocean->reflector = OceanReflector{
      .worldFromUnitSphere = glm::translate(glm::mat4(1.0f), centre) * glm::scale(glm::mat4(1.0f), radii),
      .albedo = {1.0f, 0.0f, 0.0f}};
  ASSERT_TRUE((*renderer)->render(frame));
  const auto hdr = (*renderer)->readHdrOutput();
  ASSERT_TRUE(hdr);
  const float aspect = float(extent.width) / float(extent.height);
  const glm::mat4 clipToWorld = glm::inverse(camera.projection(aspect) * camera.view());
  // Whether the ray from `origin` along `direction` meets the ellipsoid grown by `scale`.
  const auto meets = [&](glm::vec3 origin, glm::vec3 direction, float scale) {
    const glm::vec3 o = (origin - centre) / (radii * scale);
    const glm::vec3 d = direction / (radii * scale);
    const float b = glm::dot(o, d);
    const float c = glm::dot(o, o) - 1.0f;
    return b * b - glm::dot(d, d) * c > 0.0f && (c < 0.0f || b < 0.0f);
  };
  int red = 0;
  int sky = 0;
  for (int y = 0; y < int(extent.height); ++y) {
    for (int x = 0; x < int(extent.width); ++x) {
      const glm::vec3 ray = eyeRay(clipToWorld, extent, x, y);
      if (ray.y > -0.02f) continue;  // the sky, or water too far off to tell
      const glm::vec3 water = camera.position + ray * (-camera.position.y / ray.y);
      const glm::vec3 mirrored(ray.x, -ray.y, ray.z);
      const std::size_t i = (std::size_t(y) * extent.width + std::size_t(x)) * 4;
      const float r = glm::unpackHalf1x16((*hdr)[i]);
      const float g = glm::unpackHalf1x16((*hdr)[i + 1]);
      // The ripples tilt the water by a few hundredths: half and twice the ellipsoid leave room.
      if (meets(water, mirrored, 0.5f)) {
        EXPECT_GT(r, 2.0f * g) << "pixel " << x << ", " << y << " mirrors the ship but shows no red";
        ++red;
      } else if (!meets(water, mirrored, 2.0f)) {
        EXPECT_LT(r, g) << "pixel " << x << ", " << y << " mirrors the sky but shows red";
        ++sky;
      }
    }
  }
  EXPECT_GT(red, 20);
  EXPECT_GT(sky, 1000);
}

}  // namespace
}  // namespace mane::render
