// Texture-space diffusion's inputs (render/passes/skin_diffusion_pass.hpp): the irradiance and
// stretch maps drawn from a mesh at its uvs, and the errors for bad settings and meshes. The
// references are closed forms for a flat quad: E = ambient + Σ max(N·L, 0)·radiance with the
// quad's one normal, and the stretch = its world size / the texels its uvs span.

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "render/passes/skin_diffusion_pass.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

using SkinIrradianceTest = testing::VulkanTest;

// A width × height quad in the xy plane facing +z, drawn at uv [u0, u1] × [v0, v1]; v grows
// down the image as y falls (glTF's convention).
struct Quad {
  float width, height;  // metres
  glm::vec2 uvMin{0.25f, 0.25f}, uvMax{0.75f, 0.5f};
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices{0, 1, 2, 0, 2, 3};

  explicit Quad(float width_ = 0.1f, float height_ = 0.02f) : width(width_), height(height_) {
    positions = {{0, 0, 0}, {width, 0, 0}, {width, height, 0}, {0, height, 0}};
    normals.assign(4, glm::vec3(0, 0, 1));
    uvs = {{uvMin.x, uvMax.y}, {uvMax.x, uvMax.y}, {uvMax.x, uvMin.y}, {uvMin.x, uvMin.y}};
  }
  MeshData mesh() const { return {.positions = positions, .normals = normals, .uvs = uvs, .indices = indices}; }
  // Whether texel (x, y)'s centre lies inside the quad's uvs by at least `margin` texels.
  bool inside(std::uint32_t size, std::uint32_t x, std::uint32_t y, float margin) const {
    const glm::vec2 centre = (glm::vec2(x, y) + 0.5f) / float(size);
    const glm::vec2 pad(margin / float(size));
    return glm::all(glm::greaterThan(centre, uvMin + pad)) && glm::all(glm::lessThan(centre, uvMax - pad));
  }
  bool outside(std::uint32_t size, std::uint32_t x, std::uint32_t y, float margin) const {
    const glm::vec2 centre = (glm::vec2(x, y) + 0.5f) / float(size);
    const glm::vec2 pad(margin / float(size));
    return glm::any(glm::lessThan(centre, uvMin - pad)) || glm::any(glm::greaterThan(centre, uvMax + pad));
  }
};

struct Drawn {
  std::vector<glm::vec4> irradiance;
  std::vector<glm::vec2> stretch;
};

Drawn draw(const Device& device, SkinDiffusionPass& pass, const Quad& quad, const SkinIrradianceInput& input) {
  auto mesh = SkinDiffusionMesh::create(device, quad.mesh());
  EXPECT_TRUE(mesh.has_value()) << mesh.error().message;
  if (!mesh) return {};
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) { pass.recordIrradiance(commands, *mesh, input); });
  auto irradiance = pass.readIrradiance();
  auto stretch = pass.readStretch();
  EXPECT_TRUE(irradiance && stretch);
  if (!irradiance || !stretch) return {};
  return {*irradiance, *stretch};
}

TEST_F(SkinIrradianceTest, AFlatQuadReceivesAmbientPlusNDotLTimesRadiance) {
  // The quad turned 90° about x (its normal, +z, becomes −y: the normal matrix is used) under a
  // light at N·L = 0.6 and one behind it (N·L = −1, adds nothing), with ambient:
  // E = ambient + 0.6·colour·intensity. Texels inside the quad: E with coverage 1, within 1e-3
  // relative (half floats: 2^-11); texels off it: 0.
  constexpr std::uint32_t kSize = 128;
  auto pass = SkinDiffusionPass::create(device(), {.size = kSize});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const Quad quad;
  const glm::mat4 model = glm::rotate(glm::mat4(1.0f), std::numbers::pi_v<float> / 2, glm::vec3(1, 0, 0));
  const std::vector<DirectionalLight> lights{
      {.direction = {0.0f, -0.6f, 0.8f}, .color = {1.0f, 0.5f, 0.25f}, .intensity = 2.0f},
      {.direction = {0.0f, 1.0f, 0.0f}, .color = {5.0f, 5.0f, 5.0f}, .intensity = 1.0f}};
  const glm::vec3 ambient(0.05f, 0.1f, 0.15f);
  const Drawn drawn = draw(device(), *pass, quad, {.model = model, .lights = lights, .ambient = ambient});
  ASSERT_EQ(drawn.irradiance.size(), kSize * kSize);
  const glm::vec3 expected = ambient + 0.6f * glm::vec3(1.0f, 0.5f, 0.25f) * 2.0f;
  int inside = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const glm::vec4 texel = drawn.irradiance[y * kSize + x];
      if (quad.inside(kSize, x, y, 0.5f)) {
        ++inside;
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(texel[c], expected[c], 1e-3 * expected[c]) << "texel (" << x << ", " << y << ") channel " << c;
        ASSERT_EQ(texel.a, 1.0f) << "coverage at (" << x << ", " << y << ")";
      } else if (quad.outside(kSize, x, y, 0.5f)) {
        ASSERT_EQ(texel, glm::vec4(0.0f)) << "texel (" << x << ", " << y << ") is off the quad";
      }
    }
  // uv [0.25, 0.75] × [0.25, 0.5] of 128²: 64 × 32 texels, less the border rows and columns.
  EXPECT_GE(inside, 62 * 30);
}

TEST_F(SkinIrradianceTest, TheNormalMapTiltsTheNormal) {
  // A constant normal map (204, 128, 230): tangent-space n = normalize(0.6, 0.004, 0.804). On
  // the unrotated quad, +u is +x and the map's +Y (−v) is +y, so the world normal is n itself;
  // a light along +x gives E = n.x·radiance. The quad is 100 × 50 mm on 0.5 × 0.25 of uv, the
  // same stretch along u and v: the derivative frame (shaders/cotangent_frame.glsl, as the
  // surface pass uses it) is orthonormal only then — under anisotropic stretch it scales the
  // map's x and y by the uv gradients. 8-bit texels decode exactly as the shader does; tolerance
  // 2e-3 relative (half floats and the sampler's filtering of a constant).
  constexpr std::uint32_t kSize = 64;
  auto pass = SkinDiffusionPass::create(device(), {.size = kSize});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const std::vector<std::uint8_t> texels = [] {
    std::vector<std::uint8_t> rgba;
    for (int i = 0; i < 16; ++i) rgba.insert(rgba.end(), {204, 128, 230, 255});
    return rgba;
  }();
  ASSERT_TRUE(pass->setNormalMap(TextureData{.width = 4, .height = 4, .rgba = texels}).has_value());
  const std::vector<DirectionalLight> lights{{.direction = {1.0f, 0.0f, 0.0f}, .color = glm::vec3(1.0f)}};
  const Quad quad(0.1f, 0.05f);
  const Drawn drawn = draw(device(), *pass, quad, {.lights = lights});
  ASSERT_EQ(drawn.irradiance.size(), kSize * kSize);
  const glm::vec3 n = glm::normalize(glm::vec3(204, 128, 230) / 255.0f * 2.0f - 1.0f);
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x)
      if (quad.inside(kSize, x, y, 0.5f)) {
        ASSERT_NEAR(drawn.irradiance[y * kSize + x].r, n.x, 2e-3 * n.x) << "texel (" << x << ", " << y << ")";
      }

  // Without the map, the light grazes the quad: only the (zero) ambient is left.
  ASSERT_TRUE(pass->setNormalMap(std::nullopt).has_value());
  const Drawn flat = draw(device(), *pass, quad, {.lights = lights});
  ASSERT_EQ(flat.irradiance.size(), kSize * kSize);
  EXPECT_EQ(flat.irradiance[(kSize / 2 - 8) * kSize + kSize / 2], glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

TEST_F(SkinIrradianceTest, TheStretchMapHoldsTheQuadsSizePerTexel) {
  // The quad is 100 mm along u over 0.5 of the map and 20 mm along v over 0.25: at 256² that is
  // 100/128 = 0.78125 and 20/64 = 0.3125 mm per texel; scaled 2× by the model, twice that.
  // Exact in closed form; tolerance 1e-3 relative (half floats, and the derivative of the
  // interpolated world position in single precision). Off the quad: 0.
  constexpr std::uint32_t kSize = 256;
  auto pass = SkinDiffusionPass::create(device(), {.size = kSize});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const Quad quad;
  for (const float scale : {1.0f, 2.0f}) {
    const Drawn drawn = draw(device(), *pass, quad, {.model = glm::scale(glm::mat4(1.0f), glm::vec3(scale))});
    ASSERT_EQ(drawn.stretch.size(), kSize * kSize);
    const glm::vec2 expected = glm::vec2(0.78125f, 0.3125f) * scale;
    for (std::uint32_t y = 0; y < kSize; ++y)
      for (std::uint32_t x = 0; x < kSize; ++x) {
        const glm::vec2 texel = drawn.stretch[y * kSize + x];
        if (quad.inside(kSize, x, y, 0.5f)) {
          ASSERT_NEAR(texel.x, expected.x, 1e-3 * expected.x) << "along u at (" << x << ", " << y << ")";
          ASSERT_NEAR(texel.y, expected.y, 1e-3 * expected.y) << "along v at (" << x << ", " << y << ")";
        } else if (quad.outside(kSize, x, y, 0.5f)) {
          ASSERT_EQ(texel, glm::vec2(0.0f)) << "at (" << x << ", " << y << ")";
        }
      }
  }
}

// The error of a failed Result, or a note that it did not fail.
template <class T>
std::string errorOf(const Result<T>& result) {
  return result ? std::string("(no error)") : result.error().message;
}

TEST_F(SkinIrradianceTest, HairShadowsDimTheFirstLightAsTheirLookupSays) {
  // A sheet of 1,500 strands 1 cm above the left half of the quad (x < 5 cm), the first light
  // straight down through it, a second light unshadowed. Each texel on the quad must hold
  // ambient + T·E0 + E1 with T the opacity shadow map's own lookup at the texel's point
  // (OpacityShadowMapPass::probe); texture-space soft shadows are the blurs of exactly this.
  constexpr std::uint32_t kSize = 128;
  const Quad quad;
  std::vector<glm::vec4> strands;
  std::uint64_t state = 12345;
  const auto uniform = [&] {  // a fixed LCG: the same sheet every run
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return float(state >> 40) / float(1ull << 24);
  };
  constexpr std::uint32_t kVertices = 8;
  for (int s = 0; s < 1500; ++s) {
    const float x = 0.05f * uniform();
    const float z = 0.01f + 0.002f * uniform();
    for (std::uint32_t v = 0; v < kVertices; ++v)
      strands.emplace_back(x, -0.01f + 0.04f * float(v) / (kVertices - 1), z, 0.0f);
  }
  const Buffer positions =
      Buffer::withData(device(), std::as_bytes(std::span(strands)),
                       vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer);
  auto shadows = HairShadowPass::create(device());
  ASSERT_TRUE(shadows.has_value()) << shadows.error().message;
  const std::array grooms{HairShadowPass::Groom{
      .strands = {&positions, std::uint32_t(strands.size() / kVertices), kVertices}, .width = 4e-5f}};
  ASSERT_TRUE((*shadows)->setGrooms(grooms, {.resolution = 256}).has_value());
  ASSERT_TRUE((*shadows)->setBounds(0, *boundingSphere(strands)).has_value());
  auto pass = SkinDiffusionPass::create(device(), {.size = kSize}, shadows->get());
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const std::vector<DirectionalLight> lights{{.direction = {0, 0, 1}, .intensity = 2.0f},
                                             {.direction = {0.6f, 0, 0.8f}, .intensity = 0.5f}};
  const glm::vec3 ambient(0.05f);
  auto mesh = SkinDiffusionMesh::create(device(), quad.mesh());
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    (*shadows)->record(commands, lights[0].direction);
    pass->recordIrradiance(commands, *mesh, {.lights = lights, .ambient = ambient});
  });
  auto irradiance = pass->readIrradiance();
  ASSERT_TRUE(irradiance.has_value()) << irradiance.error().message;

  std::vector<glm::uvec2> texels;
  std::vector<glm::vec3> points;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x)
      if (quad.inside(kSize, x, y, 0.5f)) {
        const glm::vec2 uv = (glm::vec2(x, y) + 0.5f) / float(kSize);
        texels.emplace_back(x, y);
        points.emplace_back((uv.x - quad.uvMin.x) / (quad.uvMax.x - quad.uvMin.x) * quad.width,
                            (quad.uvMax.y - uv.y) / (quad.uvMax.y - quad.uvMin.y) * quad.height, 0.0f);
      }
  const std::vector<glm::vec2> lookup = (*shadows)->map(0).probe(points);
  double shadowedLeft = 0.0, litRight = 0.0;
  int left = 0, right = 0;
  for (std::size_t i = 0; i < texels.size(); ++i) {
    const float t = lookup[i].y;
    const float expected = ambient.x + 2.0f * t + 0.5f * 0.8f;
    const glm::vec4 texel = (*irradiance)[texels[i].y * kSize + texels[i].x];
    ASSERT_NEAR(texel.r, expected, 2e-3f * expected) << "texel (" << texels[i].x << ", " << texels[i].y << ")";
    if (points[i].x < 0.045f) shadowedLeft += t, ++left;
    if (points[i].x > 0.055f) litRight += t, ++right;
  }
  EXPECT_LT(shadowedLeft / left, 0.8) << "the sheet must shadow the left half";
  EXPECT_NEAR(litRight / right, 1.0, 1e-3) << "nothing shadows the right half";
}

TEST_F(SkinIrradianceTest, BadSettingsAndMeshesGiveClearErrors) {
  using ::testing::HasSubstr;
  EXPECT_THAT(errorOf(validate(SkinDiffusionSettings{.size = 0})), HasSubstr("size is 0"));
  EXPECT_THAT(errorOf(validate(SkinDiffusionSettings{.size = 8})),
              HasSubstr("expected a multiple of 8 from 16 to 8192"));
  EXPECT_THAT(errorOf(validate(SkinDiffusionSettings{.size = 1020})), HasSubstr("size is 1020"));
  EXPECT_THAT(errorOf(validate(SkinDiffusionSettings{.size = 100000})), HasSubstr("size is 100000"));
  SkinProfile negative;
  negative.gaussians[2].variance = -1.0;
  EXPECT_THAT(errorOf(SkinDiffusionPass::create(device(), {.size = 64, .profile = negative})),
              HasSubstr("gaussians[2].variance"));
  SkinProfile unscaled;
  unscaled.millimetresPerUnit = 0.0;
  EXPECT_THAT(errorOf(SkinDiffusionPass::create(device(), {.size = 64, .profile = unscaled})),
              HasSubstr("millimetresPerUnit"));
  SkinProfile unbalanced;
  unbalanced.gaussians[0].weight.g = 0.9;
  EXPECT_THAT(errorOf(SkinDiffusionPass::create(device(), {.size = 64, .profile = unbalanced})),
              HasSubstr("channel 1 sum to"));

  Quad quad;
  MeshData mesh = quad.mesh();
  mesh.uvs = {};
  EXPECT_THAT(errorOf(SkinDiffusionMesh::create(device(), mesh)), HasSubstr("uvs has 0 entries"));
  mesh = quad.mesh();
  mesh.normals = std::span(quad.normals).first(3);
  EXPECT_THAT(errorOf(SkinDiffusionMesh::create(device(), mesh)), HasSubstr("normals has 3 entries"));
  const std::vector<std::uint32_t> pastTheEnd{0, 1, 4}, notTriangles{0, 1, 2, 3};
  mesh = quad.mesh();
  mesh.indices = pastTheEnd;
  EXPECT_THAT(errorOf(SkinDiffusionMesh::create(device(), mesh)), HasSubstr("indices[2] is 4"));
  mesh.indices = notTriangles;
  EXPECT_THAT(errorOf(SkinDiffusionMesh::create(device(), mesh)), HasSubstr("multiple of 3"));
  quad.positions[1].y = std::nanf("");
  EXPECT_THAT(errorOf(SkinDiffusionMesh::create(device(), quad.mesh())), HasSubstr("positions[1] is not finite"));
  Quad flat;
  flat.uvs.assign(4, glm::vec2(0.5f));
  EXPECT_THAT(errorOf(SkinDiffusionMesh::create(device(), flat.mesh())), HasSubstr("no triangle has an area"));

  auto pass = SkinDiffusionPass::create(device(), {.size = 16});
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const std::vector<glm::vec4> irradiance(16 * 16, glm::vec4(1.0f));
  const std::vector<glm::vec2> stretch(16 * 15, glm::vec2(1.0f));
  EXPECT_THAT(errorOf(pass->setMaps(irradiance, stretch)),
              HasSubstr("stretch map has 240 texels, expected size² = 256"));
  std::vector<glm::vec4> notFinite = irradiance;
  notFinite[17].b = INFINITY;
  const std::vector<glm::vec2> fullStretch(16 * 16, glm::vec2(1.0f));
  EXPECT_THAT(errorOf(pass->setMaps(notFinite, fullStretch)), HasSubstr("irradiance map's texel 17 is not finite"));
  const std::vector<std::uint8_t> short_(10);
  EXPECT_THAT(errorOf(pass->setNormalMap(TextureData{.width = 2, .height = 2, .rgba = short_})),
              HasSubstr("10 bytes for 2×2 texels"));
}

}  // namespace
}  // namespace mane::render
