// The environment's pre-filtering on the GPU against CPU references. The specular chain
// (render/environment/specular_reference.hpp): a constant environment stays constant at every
// level, the mirror level is the source, and the glossy levels follow the GGX-weighted integral.
// The spherical harmonics (render/environment/harmonics_projection.hpp): a constant environment
// projects on Y00 alone, √(4π)·L, and a sky with a sun's glow as projectRadiance projects it.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/environment/harmonics_projection.hpp"
#include "render/environment/specular_chain.hpp"
#include "render/environment/specular_reference.hpp"
#include "tests/render/environment_cubes.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

std::vector<glm::vec3> testDirections() {
  std::vector<glm::vec3> directions;
  for (int i = 0; i < 24; ++i) {
    // A spiral over the sphere (Fibonacci): no face or axis favoured.
    const float y = 1.0f - (float(i) + 0.5f) / 12.0f;
    const float phi = 2.39996323f * float(i);
    const float r = std::sqrt(1.0f - y * y);
    directions.push_back({r * std::cos(phi), y, r * std::sin(phi)});
  }
  return directions;
}

class SpecularChainTest : public testing::VulkanTest {
public:
  SpecularChain bake(const CubeMap& source) {
    const Image cube = uploadCubeWithMips(device(), source);
    const vk::raii::Sampler sampler = makeLinearSampler(device(), vk::SamplerAddressMode::eClampToEdge, 1.0f);
    auto chain = SpecularChain::bake(device(), cube, sampler, 128);
    EXPECT_TRUE(chain.has_value()) << chain.error().message;
    return std::move(*chain);
  }
};

TEST_F(SpecularChainTest, AConstantEnvironmentIsConstantAtEveryLevel) {
  const glm::vec3 radiance(0.25f, 1.5f, 3.0f);
  const SpecularChain chain = bake(cubeOf(64, [&](glm::vec3) { return radiance; }));
  for (std::uint32_t level = 0; level < SpecularChain::kLevels; ++level) {
    const CubeMap texels = chain.readLevel(device(), level);
    EXPECT_EQ(texels.size, int(128u >> level));
    for (const auto& face : texels.faces)
      for (const glm::vec3& texel : face)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(texel[c], radiance[c], 1e-3f * radiance[c]) << "level " << level;
  }
}

TEST_F(SpecularChainTest, GlossyLevelsFollowTheBruteForceIntegral) {
  // A sky with a bright glow round a sun and a darker ground: detail at every scale.
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.6f, -0.7f));
  const CubeMap source = cubeOf(32, [&](glm::vec3 d) {
    const float glow = std::pow(std::max(glm::dot(d, sun), 0.0f), 6.0f);
    return glm::vec3(0.1f + 0.3f * std::max(d.y, 0.0f)) + glm::vec3(3.0f, 2.5f, 2.0f) * glow;
  });
  const SpecularChain chain = bake(source);
  for (std::uint32_t level : {0u, 1u, 2u, 4u, 7u}) {
    const CubeMap texels = chain.readLevel(device(), level);
    double worst = 0.0;
    for (const glm::vec3& near : testDirections()) {
      // The centre of the level's texel that `near` falls in: coarse levels have few.
      const CubeCoordinates at = cubeCoordinates(near);
      const glm::ivec2 texel = glm::min(glm::ivec2(at.st * float(texels.size)), glm::ivec2(texels.size - 1));
      const glm::vec3 direction = cubeDirection(at.face, (glm::vec2(texel) + 0.5f) / float(texels.size));
      const glm::vec3 expected =
          level == 0 ? sampleCube(source, direction)
                     : prefilteredRadianceReference(source, direction, SpecularChain::roughnessOf(level));
      const glm::vec3 got = texels.at(at.face, texel.x, texel.y);
      worst = std::max(worst, double(glm::length(got - expected) / glm::length(expected)));
    }
    RecordProperty("worst_relative_error_level_" + std::to_string(level), std::to_string(worst));
    EXPECT_LT(worst, level == 0 ? 0.01 : 0.05) << "level " << level;
    std::printf("level %u: worst relative error %.4f\n", level, worst);
  }
}

class HarmonicsProjection : public testing::VulkanTest {
public:
  SphericalHarmonics9 project(const CubeMap& source) {
    const Image cube = uploadCubeWithMips(device(), source);
    auto projected = projectRadianceOnGpu(device(), cube);
    EXPECT_TRUE(projected.has_value()) << projected.error().message;
    return projected ? *projected : SphericalHarmonics9{};
  }
};

TEST_F(HarmonicsProjection, AConstantEnvironmentProjectsOnTheFirstHarmonicAlone) {
  const glm::vec3 radiance(0.25f, 1.5f, 3.0f);
  const SphericalHarmonics9 sh = project(cubeOf(64, [&](glm::vec3) { return radiance; }));
  const float y00 = std::sqrt(4.0f * 3.14159265f);  // ∫ Y00 dω
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(sh[0][c], y00 * radiance[c], 1e-5f * y00 * radiance[c]);
    for (std::size_t i = 1; i < 9; ++i) EXPECT_NEAR(sh[i][c], 0.0f, 1e-5f * y00 * radiance[c]) << "harmonic " << i;
  }
}

TEST_F(HarmonicsProjection, ASkyProjectsAsOnTheCpu) {
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.6f, -0.7f));
  const auto sky = [&](glm::vec3 d) {
    const float glow = std::pow(std::max(glm::dot(d, sun), 0.0f), 6.0f);
    return glm::vec3(0.1f + 0.3f * std::max(d.y, 0.0f)) + glm::vec3(3.0f, 2.5f, 2.0f) * glow;
  };
  for (const int size : {64, 256}) {
    SCOPED_TRACE(size);
    // The GPU reads the fp16 cube: the reference projects the same rounded texels.
    CubeMap source = cubeOf(size, sky);
    for (auto& face : source.faces)
      for (glm::vec3& texel : face)
        for (int c = 0; c < 3; ++c) texel[c] = glm::unpackHalf1x16(glm::packHalf1x16(texel[c]));
    const SphericalHarmonics9 gpu = project(source), cpu = projectRadiance(source);
    for (std::size_t i = 0; i < 9; ++i)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[i][c], cpu[i][c], 1e-5f * cpu[0][c]) << "harmonic " << i;
  }
}

}  // namespace
}  // namespace mane::render
