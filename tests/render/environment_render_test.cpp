// The environment on the GPU, end to end (upload → background and surfaces → sRGB read-back):
// the background shows the radiance along each pixel's ray, computed here from the camera alone;
// a Lambertian sphere under a constant environment shows albedo × L (the white furnace); under a
// sky linear in y it shows albedo × (a + ⅔·b·n_y), the cosine-convolved sky in closed form; a skin
// sphere under a constant environment shows albedo × L plus its specular albedo at N·V × ρs × L;
// the linear HDR frame holds the background's radiance above 1, which the 8-bit output clips.

#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "render/luts/preintegrated_skin.hpp"
#include "render/luts/skin_specular.hpp"
#include "render/renderer.hpp"
#include "scenes/procedural.hpp"
#include "tests/render/environment_cubes.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{96, 64};
const Camera kCamera{.position = {0.0f, 0.0f, 3.0f}, .target = {0.0f, 0.0f, 0.0f}, .verticalFovRadians = 0.9f};

double srgbEncode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// The ray through the centre of pixel (x, y).
glm::vec3 pixelRay(int x, int y) {
  const float aspect = float(kExtent.width) / float(kExtent.height);
  const glm::mat4 toDirection = glm::inverse(kCamera.projection(aspect) * glm::mat4(glm::mat3(kCamera.view())));
  const glm::vec2 ndc((float(x) + 0.5f) / float(kExtent.width) * 2.0f - 1.0f,
                      (float(y) + 0.5f) / float(kExtent.height) * 2.0f - 1.0f);
  const glm::vec4 far = toDirection * glm::vec4(ndc, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(far) / far.w);
}

// Where the ray of pixel (x, y) meets the unit sphere at the origin, if it does well inside its
// outline (the mesh's facets stray from the sphere near it).
std::optional<glm::vec3> sphereNormal(int x, int y) {
  const glm::vec3 d = pixelRay(x, y), o = kCamera.position;
  const float b = glm::dot(o, d), c = glm::dot(o, o) - 1.0f;
  const float discriminant = b * b - c;
  if (discriminant < 0.1f) return std::nullopt;
  return glm::normalize(o + (-b - std::sqrt(discriminant)) * d);
}

class EnvironmentRender : public testing::VulkanTest {
public:
  std::vector<std::uint8_t> render(CubeMap environment, glm::vec3 albedo) {
    return render(std::move(environment), MaterialData{.baseColor = albedo});
  }

  std::vector<std::uint8_t> render(CubeMap environment, const MaterialData& material) {
    auto renderer = renderScene(std::move(environment), material);
    if (!renderer) return {};
    auto rgba = renderer->readOutput();
    EXPECT_TRUE(rgba.has_value());
    return rgba ? *rgba : std::vector<std::uint8_t>{};
  }

  /// The renderer after one frame of the unit sphere under `environment`, its skin shaded as if
  /// of curvature `curvature` per metre; null on failure.
  std::unique_ptr<Renderer> renderScene(CubeMap environment, const MaterialData& material, float curvature = 0.0f) {
    const scenes::Mesh sphere = scenes::makeSphere(96, 192, 1.0f);
    const std::vector<float> curvatures(curvature > 0.0f ? sphere.positions.size() : 0, curvature);
    auto renderer = Renderer::create(device(), {.extent = kExtent});
    EXPECT_TRUE(renderer.has_value());
    if (!renderer) return nullptr;
    StaticScene scene{.environment = EnvironmentData{.radiance = std::move(environment)},
                      .meshes = {MeshData{.positions = sphere.positions,
                                          .normals = sphere.normals,
                                          .uvs = sphere.uvs,
                                          .indices = sphere.indices,
                                          .curvatures = curvatures}},
                      .materials = {material}};
    auto set = (*renderer)->setScene(scene);
    EXPECT_TRUE(set.has_value()) << set.error().message;
    if (!set) return nullptr;
    FrameInput frame{.camera = kCamera, .instances = {{.mesh = 0, .material = 0}}, .ambient = glm::vec3(0.0f)};
    auto timings = (*renderer)->render(frame);
    EXPECT_TRUE(timings.has_value()) << timings.error().message;
    return timings ? std::move(*renderer) : nullptr;
  }

  static glm::dvec3 pixel(const std::vector<std::uint8_t>& rgba, int x, int y) {
    const std::size_t i = (std::size_t(y) * kExtent.width + std::size_t(x)) * 4;
    return glm::dvec3(rgba[i], rgba[i + 1], rgba[i + 2]) / 255.0;
  }
};

TEST_F(EnvironmentRender, TheBackgroundShowsTheRadianceAlongEachPixelsRay) {
  const auto radiance = [](glm::vec3 d) { return glm::vec3(0.5f) + 0.4f * d; };
  const std::vector<std::uint8_t> rgba = render(cubeOf(64, radiance), glm::vec3(0.5f));
  ASSERT_FALSE(rgba.empty());
  int checked = 0;
  for (int y = 0; y < int(kExtent.height); y += 3)
    for (int x = 0; x < int(kExtent.width); x += 3) {
      const glm::vec3 d = pixelRay(x, y);
      if (glm::length(glm::cross(d, kCamera.position)) < 1.1f)
        continue;  // the ray passes through the sphere or near it
      const glm::dvec3 got = pixel(rgba, x, y);
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(got[c], srgbEncode(radiance(d)[c]), 2.5 / 255.0) << "pixel " << x << ", " << y << " channel " << c;
      ++checked;
    }
  EXPECT_GT(checked, 300);
}

// The linear HDR frame (`mane render --exr`) keeps what the 8-bit output clips: radiance up to 3.
TEST_F(EnvironmentRender, TheHdrFrameHoldsTheRadianceBeyondWhite) {
  const auto radiance = [](glm::vec3 d) { return glm::vec3(1.5f) + glm::vec3(1.5f, 1.0f, -0.5f) * d; };
  auto renderer = renderScene(cubeOf(64, radiance), MaterialData{.baseColor = glm::vec3(0.5f)});
  ASSERT_NE(renderer, nullptr);
  auto halves = renderer->readHdrOutput();
  ASSERT_TRUE(halves.has_value()) << halves.error().message;
  ASSERT_EQ(halves->size(), std::size_t(kExtent.width) * kExtent.height * 4);
  int checked = 0, aboveWhite = 0;
  for (int y = 0; y < int(kExtent.height); y += 3)
    for (int x = 0; x < int(kExtent.width); x += 3) {
      const glm::vec3 d = pixelRay(x, y);
      if (glm::length(glm::cross(d, kCamera.position)) < 1.1f) continue;
      const std::size_t i = (std::size_t(y) * kExtent.width + std::size_t(x)) * 4;
      for (int c = 0; c < 3; ++c) {
        const float expected = radiance(d)[c], got = glm::unpackHalf1x16((*halves)[i + std::size_t(c)]);
        // fp16 cube texels, filtered: within 1 % and fp16's step at 3.
        ASSERT_NEAR(got, expected, 0.01f * expected + 0.002f) << "pixel " << x << ", " << y << " channel " << c;
        aboveWhite += expected > 1.0f ? 1 : 0;
      }
      ++checked;
    }
  EXPECT_GT(checked, 300);
  EXPECT_GT(aboveWhite, checked);
}

TEST_F(EnvironmentRender, ALambertianSphereUnderAConstantEnvironmentShowsAlbedoTimesRadiance) {
  const glm::vec3 radiance(0.5f, 0.7f, 0.9f), albedo(0.8f, 0.6f, 0.4f);
  const std::vector<std::uint8_t> rgba = render(cubeOf(16, [&](glm::vec3) { return radiance; }), albedo);
  ASSERT_FALSE(rgba.empty());
  int checked = 0;
  for (int y = 0; y < int(kExtent.height); ++y)
    for (int x = 0; x < int(kExtent.width); ++x) {
      if (!sphereNormal(x, y)) continue;
      const glm::dvec3 got = pixel(rgba, x, y);
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(got[c], srgbEncode(albedo[c] * radiance[c]), 1.5 / 255.0) << "pixel " << x << ", " << y;
      ++checked;
    }
  EXPECT_GT(checked, 500);
}

TEST_F(EnvironmentRender, ALambertianSphereUnderALinearSkyShowsItsCosineConvolution) {
  // L = a + b·y: E/π = a + ⅔·b·n_y, exactly within nine harmonics.
  const float a = 0.45f, b = 0.4f;
  const glm::vec3 albedo(0.9f);
  const std::vector<std::uint8_t> rgba =
      render(cubeOf(32, [&](glm::vec3 d) { return glm::vec3(a + b * d.y); }), albedo);
  ASSERT_FALSE(rgba.empty());
  int checked = 0;
  double lowest = 1.0, highest = 0.0;
  for (int y = 0; y < int(kExtent.height); ++y)
    for (int x = 0; x < int(kExtent.width); ++x) {
      const std::optional<glm::vec3> n = sphereNormal(x, y);
      if (!n) continue;
      const double expected = srgbEncode(0.9 * (a + 2.0 / 3.0 * b * n->y));
      ASSERT_NEAR(pixel(rgba, x, y).x, expected, 2.0 / 255.0) << "pixel " << x << ", " << y << " n_y " << n->y;
      lowest = std::min(lowest, expected);
      highest = std::max(highest, expected);
      ++checked;
    }
  EXPECT_GT(checked, 500);
  EXPECT_GT(highest - lowest, 0.2);  // the check spans the sky's gradient
}

TEST_F(EnvironmentRender, ASkinSphereUnderAConstantEnvironmentShowsItsDiffuseAndSpecularAlbedos) {
  // Skin's diffuse sees E/π = L whatever its blurred normals; its specular reflects L̃ = L at
  // every roughness, scaled by ρs and by the Kelemen/Szirmay-Kalos albedo at N·V.
  const glm::vec3 radiance(0.45f), albedo(0.7f, 0.5f, 0.4f);
  MaterialData skin{.baseColor = albedo, .shading = SurfaceShading::kSkin};
  const std::vector<std::uint8_t> rgba = render(cubeOf(16, [&](glm::vec3) { return radiance; }), skin);
  ASSERT_FALSE(rgba.empty());
  // The albedo at 65 values of N·V, interpolated: the integral is too slow to take per pixel.
  std::array<double, 65> specularAlbedo{};
  for (std::size_t i = 0; i < specularAlbedo.size(); ++i)
    specularAlbedo[i] = kelemenSzirmayKalosAlbedo(double(i) / 64.0, skin.skin.roughness);
  int checked = 0;
  double lowest = 1.0, highest = 0.0;
  for (int y = 0; y < int(kExtent.height); ++y)
    for (int x = 0; x < int(kExtent.width); ++x) {
      const std::optional<glm::vec3> n = sphereNormal(x, y);
      if (!n) continue;
      const double at = std::clamp(double(glm::dot(*n, -pixelRay(x, y))), 0.0, 1.0) * 64.0;
      const std::size_t below = std::min(std::size_t(at), std::size_t(63));
      const double cosView = at / 64.0;
      const double specular =
          skin.skin.specularIntensity *
          (specularAlbedo[below] + (at - double(below)) * (specularAlbedo[below + 1] - specularAlbedo[below]));
      for (int c = 0; c < 3; ++c) {
        const double expected = srgbEncode((albedo[c] + specular) * radiance[c]);
        ASSERT_NEAR(pixel(rgba, x, y)[c], expected, 2.0 / 255.0) << "pixel " << x << ", " << y << " N·V " << cosView;
      }
      lowest = std::min(lowest, specular);
      highest = std::max(highest, specular);
      ++checked;
    }
  EXPECT_GT(checked, 500);
  EXPECT_GT(highest - lowest, 0.005);  // the specular's rise towards the rim is within the check
}

TEST_F(EnvironmentRender, SkinScattersEachBandOfALinearSkyAsItsCurvatureSays) {
  // Under L = a + b·y, Lambert shows a + ⅔·b·n_y; skin of curvature 1/r shows k₀·a + k₁·⅔·b·n_y
  // per channel, k_ℓ the pre-integrated profile's Funk–Hecke factors (preintegratedAmbientBands).
  // At 1/r = 0.5/mm (an ear's rim) red gains 2 % on band 0 and loses 2.7 % on band 1. Read from
  // the linear HDR frame, with no specular (ρs = 0).
  const float a = 0.45f, b = 0.4f;
  constexpr double kCurvature = 0.5;  // 1/mm
  const MaterialData skin{
      .baseColor = glm::vec3(0.9f), .shading = SurfaceShading::kSkin, .skin = {.specularIntensity = 0.0f}};
  auto renderer =
      renderScene(cubeOf(32, [&](glm::vec3 d) { return glm::vec3(a + b * d.y); }), skin, float(kCurvature * 1000.0));
  ASSERT_TRUE(renderer);
  auto halves = renderer->readHdrOutput();
  ASSERT_TRUE(halves.has_value());
  const auto bands = preintegratedAmbientBands(SkinProfile{}, skin.skin.range, kCurvature);
  int checked = 0;
  double furthestFromLambert = 0.0;
  for (int y = 0; y < int(kExtent.height); ++y)
    for (int x = 0; x < int(kExtent.width); ++x) {
      const std::optional<glm::vec3> n = sphereNormal(x, y);
      if (!n) continue;
      for (int c = 0; c < 3; ++c) {
        const double expected = 0.9 * (bands[0][c] * a + bands[1][c] * 2.0 / 3.0 * b * n->y);
        const double shown = glm::unpackHalf1x16((*halves)[(std::size_t(y) * kExtent.width + std::size_t(x)) * 4 + c]);
        ASSERT_NEAR(shown, expected, 2e-3) << "pixel " << x << ", " << y << " channel " << c << " n_y " << n->y;
        furthestFromLambert = std::max(furthestFromLambert, std::abs(expected - 0.9 * (a + 2.0 / 3.0 * b * n->y)));
      }
      ++checked;
    }
  EXPECT_GT(checked, 500);
  EXPECT_GT(furthestFromLambert, 5e-3);  // the check tells skin from Lambert
}

}  // namespace
}  // namespace mane::render
