// The Renderer end to end (surface pass → output pass → sRGB read-back) on a flat quad whose
// shading is known in closed form: Lambert, E = ambient + Σ radiance·max(n·l, 0), encoded with
// the sRGB transfer function (IEC 61966-2-1). The normal-map case checks the tangent frame and
// the map's +Y-up convention: a texel tilted towards +X (or +Y) must brighten a light from +X
// (or +Y) exactly as the tilted normal predicts. Skin on the same quad, given a curvature,
// against the CPU references of the pre-integrated diffuse table and of the
// Kelemen/Szirmay-Kalos specular (render/luts/preintegrated_skin.hpp, skin_specular.hpp).

#include <array>
#include <cmath>
#include <span>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "render/luts/preintegrated_skin.hpp"
#include "render/luts/skin_specular.hpp"
#include "render/renderer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{96, 64};
const std::array<glm::vec3, 4> kPositions{glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(1, 1, 0),
                                          glm::vec3(-1, 1, 0)};
const std::array<glm::vec3, 4> kNormals{glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1)};
// v = 0 is the top row of the image, as in glTF.
const std::array<glm::vec2, 4> kUvs{glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(1, 0), glm::vec2(0, 0)};
const std::array<std::uint32_t, 6> kIndices{0, 1, 2, 0, 2, 3};

double srgbEncode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double unorm(std::uint8_t value) {
  return value / 255.0;
}

struct Shot {
  std::vector<std::uint8_t> rgba;
  std::vector<PassTiming> timings;
  std::array<int, 3> centre() const {
    const std::size_t i = (std::size_t(kExtent.height / 2) * kExtent.width + kExtent.width / 2) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2]};
  }
};

class Surface : public testing::VulkanTest {
public:
  Shot render(const MaterialData& material, const DirectionalLight& light, glm::vec3 ambient,
              std::span<const float> curvatures = {}) {
    return renderFrom(glm::vec3(0, 0, 2), glm::mat4(1.0f), material, light, ambient, curvatures);
  }

  /// The quad placed by `model`, seen from `eye` towards the origin.
  Shot renderFrom(glm::vec3 eye, const glm::mat4& model, const MaterialData& material, const DirectionalLight& light,
                  glm::vec3 ambient, std::span<const float> curvatures = {}) {
    auto renderer = Renderer::create(device(), {.extent = kExtent});
    EXPECT_TRUE(renderer.has_value());
    StaticScene scene{
        .meshes = {MeshData{
            .positions = kPositions, .normals = kNormals, .uvs = kUvs, .indices = kIndices, .curvatures = curvatures}},
        .materials = {material}};
    EXPECT_TRUE((*renderer)->setScene(scene).has_value());
    FrameInput frame{.camera = {.position = eye, .target = {0, 0, 0}},
                     .lights = {light},
                     .instances = {{.mesh = 0, .material = 0, .model = model}},
                     .ambient = ambient};
    auto timings = (*renderer)->render(frame);
    EXPECT_TRUE(timings.has_value());
    auto rgba = (*renderer)->readOutput();
    EXPECT_TRUE(rgba.has_value());
    return {*rgba, *timings};
  }
};

TEST_F(Surface, LambertOnAFlatQuadMatchesTheClosedForm) {
  const glm::vec3 base(0.8f, 0.6f, 0.4f);
  const glm::vec3 ambient(0.05f);
  const DirectionalLight light{
      .direction = glm::normalize(glm::vec3(0, 0.6f, 0.8f)), .color = {1, 1, 1}, .intensity = 0.9f};
  const Shot shot = render({.baseColor = base}, light, ambient);
  const auto centre = shot.centre();
  for (int c = 0; c < 3; ++c) {
    const double expected = 255.0 * srgbEncode(base[c] * (ambient[c] + 0.9 * 0.8));
    // ±1: the sRGB encode of the attachment may round either way (Vulkan allows it).
    EXPECT_NEAR(centre[c], expected, 1.0) << "channel " << c;
  }
  ASSERT_EQ(shot.timings.size(), 3u);
  EXPECT_EQ(shot.timings[0].pass, PassName::kSurfaceShadows);
  EXPECT_EQ(shot.timings[1].pass, PassName::kSurfaces);
  EXPECT_EQ(shot.timings[2].pass, PassName::kOutput);
  for (const auto& timing : shot.timings) EXPECT_GT(timing.milliseconds, 0.0) << timing.pass;
}

// A thin sheet of transmission t: lit from the front it shows (1 − t)·albedo·E·cos θ, lit from
// behind t·albedo·E·|cos θ| on the face the camera sees, and both fall to the ambient edge-on.
TEST_F(Surface, AThinSheetPassesItsTransmissionOfTheLightBehindIt) {
  const glm::vec3 base(0.8f, 0.7f, 0.5f);
  const float t = 0.3f;
  const glm::vec3 ambient(0.02f);
  for (float z : {0.8f, -0.8f, 0.0f}) {
    const DirectionalLight light{
        .direction = glm::normalize(glm::vec3(0, 0.6f, z)), .color = {1, 1, 1}, .intensity = 0.9f};
    const float cosine = light.direction.z;
    const float share = cosine > 0.0f ? (1.0f - t) * cosine : t * -cosine;
    const Shot shot = render({.baseColor = base, .transmission = t}, light, ambient);
    const auto centre = shot.centre();
    for (int c = 0; c < 3; ++c) {
      const double expected = 255.0 * srgbEncode(base[c] * (ambient[c] + 0.9 * share));
      EXPECT_NEAR(centre[c], expected, 1.0) << "light z " << z << ", channel " << c;
    }
  }
}

// Skin at 1/r = 0.2 mm⁻¹ with both integration ranges, lit at N·L = 0.25 and from just behind
// the terminator (N·L = −0.15): the table lookup reproduces the CPU integral (the table's
// bilinear error and 16-bit storage are below 1e-3, then the 8-bit sRGB output: ±1.5 levels);
// behind the terminator, where Lambert is black, scattered red light still arrives.
TEST_F(Surface, SkinDiffuseMatchesThePreintegratedIntegral) {
  const glm::vec3 base(0.9f, 0.7f, 0.6f);
  const glm::vec3 ambient(0.02f);
  const std::array<float, 4> curvatures{200.0f, 200.0f, 200.0f, 200.0f};  // per metre: 0.2 mm⁻¹
  for (const SkinIntegrationRange range : {SkinIntegrationRange::kCurvature, SkinIntegrationRange::kPenner})
    for (const double nDotL : {0.25, -0.15}) {
      const DirectionalLight light{.direction = glm::vec3(0.0f, float(std::sqrt(1.0 - nDotL * nDotL)), float(nDotL)),
                                   .intensity = 1.2f};
      const MaterialData skin{
          .baseColor = base, .shading = SurfaceShading::kSkin, .skin = {.range = range, .specularIntensity = 0.0f}};
      const Shot shot = render(skin, light, ambient, curvatures);
      const glm::dvec3 diffuse = preintegratedDiffuse(SkinProfile{}, range, nDotL, 0.2);
      const auto centre = shot.centre();
      for (int c = 0; c < 3; ++c) {
        const double expected = 255.0 * srgbEncode(base[c] * (ambient[c] + 1.2 * diffuse[c]));
        EXPECT_NEAR(centre[c], expected, 1.5) << "range " << int(range) << " N·L " << nDotL << " channel " << c;
      }
      if (nDotL < 0.0) {
        EXPECT_GT(centre[0], 255.0 * srgbEncode(base.r * ambient.r) + 3.0) << "range " << int(range);
      }
    }
}

// Specular alone (black albedo, ρs 5 — skin's F0 of 0.028 keeps the usual 0.57 dim at 8 bits —,
// m 0.3): a light 6° off the camera's axis gives the Kelemen/Szirmay-Kalos radiance × N·L × E of the CPU model (the
// Beckmann term decodes within 1 %, then the 8-bit output).
TEST_F(Surface, SkinSpecularMatchesKelemenSzirmayKalos) {
  const glm::dvec3 toLight = glm::normalize(glm::dvec3(0.0, 0.1, 1.0));
  const DirectionalLight light{.direction = glm::vec3(toLight), .intensity = 1.0f};
  const MaterialData skin{.baseColor = glm::vec3(0.0f),
                          .shading = SurfaceShading::kSkin,
                          .skin = {.roughness = 0.3f, .specularIntensity = 5.0f}};
  const Shot shot = render(skin, light, glm::vec3(0.0f));
  const glm::dvec3 normal(0, 0, 1), toEye(0, 0, 1);  // the centre pixel, camera on the axis
  const double radiance = kelemenSzirmayKalos(normal, toLight, toEye, 0.3, 5.0) * toLight.z;
  const double expected = 255.0 * srgbEncode(radiance);
  ASSERT_GT(radiance, 0.05);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(shot.centre()[c], expected, 2.0) << "channel " << c;
}

// Texture-space diffusion of a uniformly lit quad: the blurs of a constant irradiance give it
// back (coverage-normalised kernels), so the centre pixel is albedo × (ambient + N·L·E), as
// Lambert, with the specular term off.
TEST_F(Surface, TextureSpaceSkinOfAUniformlyLitQuadKeepsItsIrradiance) {
  const glm::vec3 base(0.9f, 0.7f, 0.6f);
  const glm::vec3 ambient(0.03f);
  const DirectionalLight light{.direction = glm::normalize(glm::vec3(0, 0.6f, 0.8f)), .intensity = 0.9f};
  const MaterialData skin{
      .baseColor = base,
      .shading = SurfaceShading::kSkin,
      .skin = {.diffusion = SkinDiffusion::kTextureSpace, .irradianceSize = 256, .specularIntensity = 0.0f}};
  const Shot shot = render(skin, light, ambient);
  const auto centre = shot.centre();
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(centre[c], 255.0 * srgbEncode(base[c] * (ambient[c] + 0.9 * 0.8)), 1.5) << "channel " << c;
  ASSERT_GE(shot.timings.size(), 4u);
  EXPECT_EQ(shot.timings[0].pass, PassName::kSurfaceShadows);
  EXPECT_EQ(shot.timings[1].pass, PassName::kSkinDiffusion);
}

TEST_F(Surface, BackgroundOutsideTheQuad) {
  const Shot shot = render({.baseColor = glm::vec3(1)}, {.direction = {0, 0, 1}}, glm::vec3(0));
  const glm::vec3 background = FrameInput{}.background;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(shot.rgba[c], 255.0 * srgbEncode(background[c]), 1.0) << "channel " << c;
}

// The quad faces +z (counter-clockwise seen from there). Double-sided, it is drawn from either
// side; single-sided, only from +z, also when a mirroring model matrix turns its winding
// clockwise (its faces still face the way its normals do).
TEST_F(Surface, SingleSidedMaterialsHideOnlyTheFacesTurnedAway) {
  const DirectionalLight light{.direction = {0, 0, 1}};
  const glm::vec3 ambient(0.5f);
  const auto drawn = [](const Shot& shot) {
    const std::array<int, 3> centre = shot.centre();
    const glm::vec3 background = FrameInput{}.background;
    return std::abs(centre[0] - 255.0 * srgbEncode(background[0])) > 2.0;
  };
  const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1));
  for (const bool doubleSided : {true, false}) {
    const MaterialData material{.baseColor = glm::vec3(1.0f), .doubleSided = doubleSided};
    EXPECT_TRUE(drawn(renderFrom({0, 0, 2}, glm::mat4(1.0f), material, light, ambient))) << doubleSided;
    EXPECT_TRUE(drawn(renderFrom({0, 0, 2}, mirror, material, light, ambient))) << doubleSided;
    EXPECT_EQ(drawn(renderFrom({0, 0, -2}, glm::mat4(1.0f), material, light, ambient)), doubleSided) << doubleSided;
    EXPECT_EQ(drawn(renderFrom({0, 0, -2}, mirror, material, light, ambient)), doubleSided) << doubleSided;
  }
}

// A constant normal map tilted by the texel; the light comes along the tilt axis.
void expectTiltedNormal(Surface& test, std::array<std::uint8_t, 4> texel, glm::vec3 lightDirection,
                        std::size_t tiltAxis) {
  std::vector<std::uint8_t> pixels(16);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = texel[i % 4];
  const MaterialData material{.baseColor = glm::vec3(1.0f),
                              .normalMap = TextureData{.width = 2, .height = 2, .rgba = pixels}};
  const Shot shot = test.render(material, {.direction = lightDirection}, glm::vec3(0));
  const glm::dvec3 mapped =
      glm::normalize(glm::dvec3(unorm(texel[0]) * 2 - 1, unorm(texel[1]) * 2 - 1, unorm(texel[2]) * 2 - 1));
  // Tangent frame of the quad: +u is world +X, map +Y (up in the image) is world +Y.
  const double cosine = std::max(mapped[tiltAxis], 0.0);
  const double expected = 255.0 * srgbEncode(cosine);
  EXPECT_NEAR(shot.centre()[0], expected, 1.5) << "cosine " << cosine;
}

TEST_F(Surface, NormalMapTiltTowardsPlusXLightsFromPlusX) {
  expectTiltedNormal(*this, {204, 128, 229, 255}, {1, 0, 0}, 0);
}

TEST_F(Surface, NormalMapTiltTowardsPlusYLightsFromPlusY) {
  expectTiltedNormal(*this, {128, 204, 229, 255}, {0, 1, 0}, 1);
}

// The same with a uniform specular map of red 128 (its other channels 0 and 255, which must not
// count): ρs scaled by 128/255. The map rides in the albedo texture's alpha; once with a black
// 4x4 albedo texture (the 2x2 map resampled to its size) and once with none (the albedo from the
// base colour).
TEST_F(Surface, SkinSpecularMapScalesRhoS) {
  const glm::dvec3 toLight = glm::normalize(glm::dvec3(0.0, 0.1, 1.0));
  const DirectionalLight light{.direction = glm::vec3(toLight), .intensity = 1.0f};
  constexpr std::array<std::uint8_t, 2 * 2 * 4> specular{128, 0, 255, 255, 128, 0, 255, 255,
                                                         128, 0, 255, 255, 128, 0, 255, 255};
  const std::vector<std::uint8_t> black = [] {
    std::vector<std::uint8_t> texels(4 * 4 * 4, 0);
    for (std::size_t i = 3; i < texels.size(); i += 4) texels[i] = 255;
    return texels;
  }();
  const double radiance =
      kelemenSzirmayKalos(glm::dvec3(0, 0, 1), toLight, glm::dvec3(0, 0, 1), 0.3, 5.0 * 128.0 / 255.0) * toLight.z;
  ASSERT_GT(radiance, 0.05);
  for (const bool albedoTexture : {true, false}) {
    MaterialData skin{.baseColor = glm::vec3(albedoTexture ? 1.0f : 0.0f),
                      .shading = SurfaceShading::kSkin,
                      .skin = {.roughness = 0.3f, .specularIntensity = 5.0f},
                      .specularMap = TextureData{.width = 2, .height = 2, .rgba = specular}};
    if (albedoTexture) skin.albedo = TextureData{.width = 4, .height = 4, .rgba = black};
    const Shot shot = render(skin, light, glm::vec3(0.0f));
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(shot.centre()[c], 255.0 * srgbEncode(radiance), 2.0) << "albedo texture " << albedoTexture;
  }
}

// A 4x4 albedo texture whose quarters are 2x2 blocks of one sRGB colour each, on the quad under
// a light along the normal: each quarter of the quad shows its colour, decoded from sRGB to
// linear by the sampler, lit with E = 1 and encoded back, so the output equals the texel. This
// pins the uv orientation (v = 0 at the top row) and the sRGB round trip.
TEST_F(Surface, AlbedoTexelsLandInTheirQuartersAndSurviveTheSrgbRoundTrip) {
  const std::array<std::array<std::uint8_t, 4>, 4> colours{{{200, 30, 30, 255},     // top left: red
                                                            {30, 200, 30, 255},     // top right: green
                                                            {30, 30, 200, 255},     // bottom left: blue
                                                            {200, 200, 30, 255}}};  // bottom right: yellow
  std::vector<std::uint8_t> texels;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const auto& colour = colours[(y / 2) * 2 + x / 2];
      texels.insert(texels.end(), colour.begin(), colour.end());
    }
  const MaterialData material{.baseColor = glm::vec3(1.0f),
                              .albedo = TextureData{.width = 4, .height = 4, .rgba = texels}};
  const Shot shot = render(material, {.direction = {0, 0, 1}, .intensity = 1.0f}, glm::vec3(0));
  // The quad spans ±1 at distance 2 with the default 0.7 rad field of view. Sample at the middle
  // of each quarter (x, y = ±0.5): bilinear filtering there only mixes texels of one colour.
  const float halfHeight = 2.0f * std::tan(0.35f);
  auto pixelOf = [&](float x, float y) {
    const float aspect = float(kExtent.width) / float(kExtent.height);
    const int px = int(std::floor((x / (halfHeight * aspect) * 0.5f + 0.5f) * kExtent.width));
    const int py = int(std::floor((0.5f - y / halfHeight * 0.5f) * kExtent.height));
    const std::size_t i = (std::size_t(py) * kExtent.width + px) * 4;
    return std::array<int, 3>{shot.rgba[i], shot.rgba[i + 1], shot.rgba[i + 2]};
  };
  const std::array<glm::vec2, 4> quarters{glm::vec2(-0.5f, 0.5f), glm::vec2(0.5f, 0.5f), glm::vec2(-0.5f, -0.5f),
                                          glm::vec2(0.5f, -0.5f)};
  for (std::size_t q = 0; q < 4; ++q) {
    const auto pixel = pixelOf(quarters[q].x, quarters[q].y);
    // ±1: the sRGB decode and encode may each round either way.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(pixel[c], colours[q][c], 1) << "quarter " << q << " channel " << c;
  }
}

TEST_F(Surface, RejectsMalformedSceneData) {
  auto renderer = Renderer::create(device(), {.extent = {8, 8}});
  ASSERT_TRUE(renderer.has_value());
  const std::array<std::uint32_t, 3> badIndices{0, 1, 7};
  const auto badMesh = (*renderer)->setScene({.meshes = {MeshData{kPositions, kNormals, kUvs, badIndices}}});
  ASSERT_FALSE(badMesh.has_value());
  EXPECT_NE(badMesh.error().message.find("index 2 is 7"), std::string::npos) << badMesh.error().message;

  const std::array<std::uint8_t, 8> shortTexels{};
  const auto badTexture = (*renderer)->setScene(
      {.materials = {MaterialData{.albedo = TextureData{.width = 2, .height = 2, .rgba = shortTexels}}}});
  ASSERT_FALSE(badTexture.has_value());
  EXPECT_NE(badTexture.error().message.find("material 0 albedo"), std::string::npos) << badTexture.error().message;
  const auto badSpecular = (*renderer)->setScene(
      {.materials = {MaterialData{.specularMap = TextureData{.width = 2, .height = 2, .rgba = shortTexels}}}});
  ASSERT_FALSE(badSpecular.has_value());
  EXPECT_NE(badSpecular.error().message.find("material 0 specular map"), std::string::npos)
      << badSpecular.error().message;

  ASSERT_TRUE((*renderer)->setScene({.meshes = {MeshData{kPositions, kNormals, kUvs, kIndices}}}).has_value());
  const auto noMaterial = (*renderer)->render({.instances = {{.mesh = 0, .material = 0}}});
  ASSERT_FALSE(noMaterial.has_value());
  EXPECT_NE(noMaterial.error().message.find("instance 0"), std::string::npos);
}

TEST_F(Surface, RejectsUnsupportedSettings) {
  EXPECT_FALSE(Renderer::create(device(), {.extent = {0, 10}}).has_value());
  const auto msaa = Renderer::create(device(), {.extent = {8, 8}, .msaaSamples = 2});
  ASSERT_FALSE(msaa.has_value());
  EXPECT_NE(msaa.error().message.find("MSAA"), std::string::npos);
}

}  // namespace
}  // namespace mane::render
