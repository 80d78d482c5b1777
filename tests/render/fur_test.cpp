// The fur pass (render/passes/fur_pass.hpp) on lavapipe, against references independent of it:
//  - memory: the GPU memory the pass holds (Device::allocatedBytes) is the same for N = 4 and
//    N = 32 layers (Ukaji et al. §3.3: only the photo and per-layer thresholds);
//  - geometry: a furred unit sphere covers pixels beyond the bare sphere's analytic silhouette
//    and none beyond the fur's outer sphere; fins change only pixels at the silhouette;
//  - leaning fur: combed fur moves the way it is combed and stays within its length; per-vertex
//    leans equal to the comb's projection draw the same fur;
//  - the fur-direction field: the photo laid along it matches the same coordinates given as uvs;
//  - shadows: the fur's shadow strands run from skin to tip; in its own opacity map the fur
//    darkens its far side and not its lit side;
//  - colour: under white light without specular, every fur pixel's chromaticity lies within
//    the photo's (the colour is the photo's, scaled by lighting);
//  - a small golden image of the sphere furred with the real cat-fur photo.
// Every test runs with the validation layers on; any message fails it (VulkanTest).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/fur_surfaces.hpp"
#include "render/passes/fur_pass.hpp"
#include "render/render_target.hpp"
#include "render/environment/spherical_harmonics.hpp"
#include "scenes/image.hpp"
#include "tests/render/environment_cubes.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/image_compare.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{160, 120};
constexpr float kEyeDistance = 3.2f;  // metres from the sphere's centre
constexpr float kThickness = 0.12f;   // h_b, metres (unit sphere)
const Camera kCamera{.position = {0, 0, kEyeDistance}, .target = {0, 0, 0}, .verticalFovRadians = 0.7f};

struct SphereMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;
  MeshData data() const { return {.positions = positions, .normals = normals, .uvs = uvs, .indices = indices}; }
};

// Unit sphere; the photo repeats 6 times around and 3 times pole to pole (uvs > 1, repeat sampler).
SphereMesh unitSphere(int rings, int segments) {
  SphereMesh mesh;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const double theta = std::numbers::pi * r / rings, phi = 2.0 * std::numbers::pi * s / segments;
      const bool pole = r == 0 || r == rings;  // one point, so the pole has no boundary edges
      const glm::vec3 p =
          pole ? glm::vec3(0.0f, float(std::cos(theta)), 0.0f)
               : glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(p);
      mesh.normals.push_back(p);
      mesh.uvs.emplace_back(6.0f * float(s) / float(segments), 3.0f * float(r) / float(rings));
    }
  const auto at = [&](int r, int s) { return std::uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s)
      mesh.indices.insert(mesh.indices.end(),
                          {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r + 1, s)});
  return mesh;
}

using Pixels = std::vector<glm::vec4>;  // linear RGBA, rows top to bottom

FurView sphereView(const FurLook& look) {
  return {.viewProjection = kCamera.projection(float(kExtent.width) / float(kExtent.height)) * kCamera.view(),
          .eye = glm::vec4(kCamera.position, 1.0f),
          .extent = kExtent,
          .light = {.direction = glm::normalize(glm::vec3(-0.4f, 0.5f, 0.8f)), .color = {1, 1, 1}, .intensity = 1.0f},
          .ambient = glm::vec3(0.15f),
          .look = look};
}

/// sphereView from `distance` metres away on the view's axis instead.
FurView sphereViewFrom(float distance, const FurLook& look) {
  const Camera camera{.position = {0, 0, distance}, .target = {0, 0, 0}, .verticalFovRadians = 0.7f};
  FurView view = sphereView(look);
  view.viewProjection = camera.projection(float(kExtent.width) / float(kExtent.height)) * camera.view();
  view.eye = glm::vec4(camera.position, 1.0f);
  return view;
}

/// The pixel radius of a sphere of radius `radius` at the view's centre (perspective).
double projectedRadius(double radius) {
  const double halfAngle = std::asin(radius / kEyeDistance);
  return std::tan(halfAngle) / std::tan(0.5 * kCamera.verticalFovRadians) * 0.5 * kExtent.height;
}

double pixelRadius(std::size_t index) {
  const double x = double(index % kExtent.width) + 0.5 - 0.5 * kExtent.width;
  const double y = double(index / kExtent.width) + 0.5 - 0.5 * kExtent.height;
  return std::hypot(x, y);
}

double srgbEncode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

class FurPassTest : public testing::VulkanTest {
protected:
  static TextureData texture(const scenes::Image& image) {
    return {std::uint32_t(image.width), std::uint32_t(image.height), image.rgba};
  }

  std::unique_ptr<FurPass> makePass(const scenes::Image& image, const FurPassSettings& settings,
                                    std::uint32_t layers = 15) {
    auto pass = FurPass::create(device(), settings, texture(image), {.layers = layers, .thickness = kThickness});
    EXPECT_TRUE(pass.has_value()) << pass.error().message;
    return pass ? std::move(*pass) : nullptr;
  }

  Pixels render(FurPass& pass, const FurView& view) {
    const auto updated = pass.update(view);
    EXPECT_TRUE(updated.has_value()) << updated.error().message;
    const RenderTarget target(device(), {.extent = kExtent});
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      using Layout = vk::ImageLayout;
      using Stage = vk::PipelineStageFlagBits2;
      using Access = vk::AccessFlagBits2;
      target.beginScene(commands, glm::vec4(0.0f));
      pass.draw(commands);
      commands.endRendering();
      transition(commands, target.hdr(), Layout::eColorAttachmentOptimal, Layout::eTransferSrcOptimal,
                 Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eTransfer, Access::eTransferRead);
    });
    const std::vector<std::byte> bytes = readBack(device(), target.hdr(), 8);
    Pixels pixels(std::size_t(kExtent.width) * kExtent.height);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      std::array<std::uint16_t, 4> halves{};
      std::memcpy(halves.data(), bytes.data() + 8 * i, 8);
      for (int c = 0; c < 4; ++c) pixels[i][c] = glm::unpackHalf1x16(halves[c]);
    }
    return pixels;
  }
};

/// The cat-fur crop as `var` (a scenes::Image), or skip the test when the assets are absent.
#define MANE_PHOTO_OR_SKIP(var)                                                 \
  MANE_RESOLVE_OR_SKIP(var##Path_, "fur/chelsea_forehead_fur_crop_110x80.png"); \
  auto var##Loaded_ = scenes::loadImage(var##Path_);                            \
  ASSERT_TRUE(var##Loaded_.has_value()) << var##Loaded_.error().message;        \
  const scenes::Image& var = *var##Loaded_;

// Memory: everything the pass allocates (photo with mips, mesh, fin buffer, uniforms) after a
// mesh upload and a frame's update, for N = 4 and N = 32: equal to the byte, and setShells does
// not change it either.
TEST_F(FurPassTest, GpuMemoryDoesNotGrowWithTheLayerCount) {
  MANE_PHOTO_OR_SKIP(image);
  const SphereMesh sphere = unitSphere(24, 48);
  std::array<std::uint64_t, 2> used{};
  for (int k = 0; k < 2; ++k) {
    const std::uint64_t before = device().allocatedBytes();
    auto pass = makePass(image, {}, k == 0 ? 4 : 32);
    ASSERT_TRUE(pass);
    ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
    ASSERT_TRUE(pass->update(sphereView({})).has_value());
    used[k] = device().allocatedBytes() - before;
    ASSERT_TRUE(pass->setShells(64, kThickness).has_value());
    ASSERT_TRUE(pass->update(sphereView({})).has_value());
    EXPECT_EQ(device().allocatedBytes() - before, used[k]) << "after setShells(64)";
  }
  EXPECT_GT(used[0], 0u);
  EXPECT_EQ(used[0], used[1]);
  std::printf("fur pass GPU memory: %llu bytes at N = 4 and %llu at N = 32\n", (unsigned long long)used[0],
              (unsigned long long)used[1]);
}

// The furred sphere covers the bare sphere's disc and a ring beyond its analytic silhouette (the
// fur), and nothing beyond the fur's outer sphere (radius 1 + h_b). 1.5 pixels of slack: pixel
// centres against the analytic circle plus the polygonal sphere's facets (48 segments: the
// chord sags 0.2 % of the radius, 0.1 pixel).
TEST_F(FurPassTest, FurReachesBeyondTheBareSilhouetteButNotBeyondItsThickness) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {});
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const Pixels pixels = render(*pass, sphereView({}));
  const double bare = projectedRadius(1.0), outer = projectedRadius(1.0 + kThickness);
  std::size_t insideCovered = 0, inside = 0, ring = 0, beyond = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const double r = pixelRadius(i);
    const bool covered = pixels[i].a > 0.5f;
    if (r < bare - 1.5) {
      ++inside;
      insideCovered += covered;
    }
    if (r > bare + 1.5 && r < outer - 1.5) ring += covered;
    if (r > outer + 1.5) beyond += covered;
  }
  EXPECT_EQ(insideCovered, inside) << "the skin layer is opaque";
  EXPECT_GT(ring, 100u) << "fur beyond the silhouette (ring " << bare << " … " << outer << " px)";
  EXPECT_EQ(beyond, 0u);
}

// A single-sided fur (the material's double_sided: false) culls its far side, which a closed
// mesh hides under its near side: the picture stays the same but at the silhouette, where the
// far side's fur stood out past the near side's (measured: 12 of about 5,000 fur pixels).
TEST_F(FurPassTest, ASingleSidedFurOnAClosedMeshDrawsTheSamePicture) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {});
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const Pixels both = render(*pass, sphereView({.doubleSided = true}));
  const Pixels front = render(*pass, sphereView({.doubleSided = false}));
  // Only the far side's fur that stands out past the silhouette goes, where fins stand too.
  const double bare = projectedRadius(1.0), outer = projectedRadius(1.0 + kThickness);
  std::size_t covered = 0, differing = 0, differingInside = 0;
  for (std::size_t i = 0; i < both.size(); ++i) {
    covered += both[i].a > 0.5f;
    const bool differs = glm::length(glm::vec3(both[i]) - glm::vec3(front[i])) > 1e-3f || both[i].a != front[i].a;
    differing += differs;
    differingInside += differs && pixelRadius(i) < bare - 1.5;
  }
  EXPECT_GT(covered, 3000u);
  EXPECT_EQ(differingInside, 0u);
  EXPECT_LE(differing, covered / 200) << "of " << covered << " fur pixels, all within the ring " << bare << " … "
                                      << outer + 1.5 << " px";
  // And the culling is done: the same sphere wound inside out (its faces turned inwards) loses
  // its near side, and the fur seen is the far side's, from within: most of the disc changes.
  SphereMesh inverted = sphere;
  for (std::size_t t = 0; t < inverted.indices.size(); t += 3)
    std::swap(inverted.indices[t + 1], inverted.indices[t + 2]);
  ASSERT_TRUE(pass->setMesh(inverted.data()).has_value());
  const Pixels insideOut = render(*pass, sphereView({.doubleSided = false}));
  std::size_t changed = 0;
  for (std::size_t i = 0; i < both.size(); ++i)
    changed += both[i].a > 0.5f && glm::length(glm::vec3(both[i]) - glm::vec3(insideOut[i])) > 1e-3f;
  EXPECT_GT(changed, covered / 2) << "of " << covered << " fur pixels";
}

// Shells per pixel of fur height on screen (FurLook::pixelsPerLayer), against the projection of
// h_b at the fur's nearest point: on the axis, at distance d − R from the eye (R the fur's outer
// radius), a step h_b across the view spans h_b·(H/2)/tan(fov/2)/(d − R) pixels. R here is
// 1 + h_b; the pass's bound is a little larger (its shadow strands lean), hence ±1 shell.
TEST_F(FurPassTest, FewerShellsWhereTheFurIsShortOnScreen) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {}, 15);
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const double focal = 0.5 * kExtent.height / std::tan(0.5 * kCamera.verticalFovRadians);
  for (const float distance : {2.0f, 3.2f, 6.0f, 12.0f, 40.0f})
    for (const float pixelsPerLayer : {0.5f, 1.0f, 2.0f}) {
      ASSERT_TRUE(pass->update(sphereViewFrom(distance, {.pixelsPerLayer = pixelsPerLayer})).has_value());
      const double height = kThickness * focal / (distance - (1.0 + kThickness));
      const double expected = std::clamp(std::ceil(height / pixelsPerLayer), 1.0, 15.0);
      EXPECT_NEAR(double(pass->drawnLayers()), expected, 1.0)
          << distance << " m, fur " << height << " px tall, " << pixelsPerLayer << " px per shell";
    }
  ASSERT_TRUE(pass->update(sphereView({.pixelsPerLayer = 0.0f})).has_value());
  EXPECT_EQ(pass->drawnLayers(), 15u) << "0: every shell";
}

// Where the fur is short on screen, one shell per pixel of its height draws what every shell
// draws: far from the sphere (fur about 4 pixels tall: 5 shells of 15). Pixel by pixel the alpha
// test flips where a luminance sits between two thresholds, so the measure is what a viewer sees
// of fur this small, the mean of 4 × 4-pixel blocks (sRGB-encoded, blocks wholly on the fur):
// within 2/255 on average. Measured: 1.4/255 at one shell per pixel, 2.4 at one per two pixels
// (3 shells), 4.0 at one per three (2 shells); per pixel 4.1, 8.5 and 15.6.
TEST_F(FurPassTest, OneShellPerPixelOfFurLooksLikeEveryShell) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {}, 15);
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  constexpr float kFar = 6.0f;
  const Pixels every = render(*pass, sphereViewFrom(kFar, {.pixelsPerLayer = 0.0f}));
  // The mean over whole blocks of fur of |blocks' mean sRGB difference|, levels of 255.
  const auto blockDifference = [&](float pixelsPerLayer) {
    const Pixels fewer = render(*pass, sphereViewFrom(kFar, {.pixelsPerLayer = pixelsPerLayer}));
    double sum = 0.0;
    std::size_t blocks = 0;
    for (std::uint32_t top = 0; top + 4 <= kExtent.height; top += 4)
      for (std::uint32_t left = 0; left + 4 <= kExtent.width; left += 4) {
        glm::dvec3 a(0.0), b(0.0);
        bool fur = true;
        for (std::uint32_t y = top; y < top + 4; ++y)
          for (std::uint32_t x = left; x < left + 4; ++x) {
            const std::size_t i = std::size_t(y) * kExtent.width + x;
            fur = fur && every[i].a > 0.5f && fewer[i].a > 0.5f;
            for (int c = 0; c < 3; ++c) {
              a[c] += srgbEncode(every[i][c]) / 16.0;
              b[c] += srgbEncode(fewer[i][c]) / 16.0;
            }
          }
        if (!fur) continue;
        ++blocks;
        sum += (std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z)) * 255.0 / 3.0;
      }
    EXPECT_GT(blocks, 100u);
    return std::pair(sum / double(std::max<std::size_t>(blocks, 1)), pass->drawnLayers());
  };
  const auto [perPixel, shells] = blockDifference(1.0f);
  const auto [perThreePixels, fewerShells] = blockDifference(3.0f);
  EXPECT_LT(shells, 8u);
  EXPECT_LT(fewerShells, shells);
  EXPECT_LE(perPixel, 2.0) << shells << " shells of 15";
  EXPECT_GT(perThreePixels, perPixel) << "the measure sees fewer shells";
}

// Under white light with no specular, a fur pixel is the photo's colour times a scalar, so its
// chromaticity (r, g)/(r + g + b) lies within the photo's, whatever the filtering mixes (a
// blend's chromaticity is inside the hull of its parts'). Tolerance 0.01: half-float storage.
TEST_F(FurPassTest, FurColourComesFromThePhoto) {
  MANE_PHOTO_OR_SKIP(image);
  glm::dvec2 lo(1.0), hi(0.0);
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    const glm::dvec3 rgb(linearFromSrgb(image.rgba[i]), linearFromSrgb(image.rgba[i + 1]),
                         linearFromSrgb(image.rgba[i + 2]));
    const double sum = rgb.r + rgb.g + rgb.b;
    if (sum < 0.02) continue;
    lo = glm::min(lo, glm::dvec2(rgb) / sum);
    hi = glm::max(hi, glm::dvec2(rgb) / sum);
  }
  auto pass = makePass(image, {});
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const Pixels pixels = render(*pass, sphereView({.specularStrength = 0.0f}));
  std::size_t checked = 0;
  for (const glm::vec4& pixel : pixels) {
    const double sum = pixel.r + pixel.g + pixel.b;
    if (pixel.a < 0.5f || sum < 0.05) continue;
    const glm::dvec2 chromaticity = glm::dvec2(pixel.r, pixel.g) / sum;
    EXPECT_GE(chromaticity.x, lo.x - 0.01);
    EXPECT_LE(chromaticity.x, hi.x + 0.01);
    EXPECT_GE(chromaticity.y, lo.y - 0.01);
    EXPECT_LE(chromaticity.y, hi.y + 0.01);
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
}

// The environment lights each fibre by its irradiance averaged round the fibre's side, as it does
// a hair. Under L = a + c·y², E/π at a normal n is a + c·(1 + n_y²)/4 (∫ ω_i ω_j max(n·ω, 0) dω =
// π(δ_ij + n_i n_j)/4), and the mean of n_y² over the normals perpendicular to a fibre along t is
// (1 − t_y²)/2: white fur growing along the sphere's normal shows a + c·(3 − t_y²)/8 with no light.
TEST_F(FurPassTest, TheEnvironmentLightsEachFibreRoundItsSide) {
  // White but for one texel a step darker: a photo needs some contrast to make shells of.
  scenes::Image white{.width = 4, .height = 4, .rgba = std::vector<std::uint8_t>(64, 255)};
  for (int k = 0; k < 3; ++k) white.rgba[std::size_t(k)] = 254;
  auto pass = makePass(white, {});
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(48, 96);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  constexpr float a = 0.1f, c = 1.0f;
  SphericalHarmonics9 environment =
      irradianceFromRadiance(projectRadiance(cubeOf(32, [&](glm::vec3 d) { return glm::vec3(a + c * d.y * d.y); })));
  for (glm::vec3& coefficient : environment) coefficient /= std::numbers::pi_v<float>;
  FurView view = sphereView({.specularStrength = 0.0f});
  view.light.intensity = 0.0f;
  view.ambient = glm::vec3(0.0f);
  view.environment = environment;
  const Pixels pixels = render(*pass, view);
  // A pixel shows fibres where its ray crosses the fur, between the skin (radius 1) and the top
  // shell (1 + h_b), growing along the sphere's normal there: between what the two normals give.
  const float aspect = float(kExtent.width) / float(kExtent.height);
  const glm::mat4 toWorld = glm::inverse(kCamera.projection(aspect) * kCamera.view());
  const auto fibreAt = [&](glm::vec3 ray, float radius) -> std::optional<glm::vec3> {
    const float b = glm::dot(kCamera.position, ray);
    const float discriminant = b * b - (glm::dot(kCamera.position, kCamera.position) - radius * radius);
    if (discriminant < 0.3f) return std::nullopt;  // near the outline, where the fins show
    return glm::normalize(kCamera.position + (-b - std::sqrt(discriminant)) * ray);
  };
  const auto shown = [&](glm::vec3 t) { return a + c * (3.0 - t.y * t.y) / 8.0; };
  std::size_t checked = 0;
  double lowest = 1.0, highest = 0.0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    if (pixels[i].a < 0.5f) continue;
    const glm::vec2 ndc((float(i % kExtent.width) + 0.5f) / float(kExtent.width) * 2.0f - 1.0f,
                        (float(i / kExtent.width) + 0.5f) / float(kExtent.height) * 2.0f - 1.0f);
    const glm::vec4 far = toWorld * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 ray = glm::normalize(glm::vec3(far) / far.w - kCamera.position);
    const auto top = fibreAt(ray, 1.0f + kThickness), skin = fibreAt(ray, 1.0f);
    if (!top || !skin) continue;
    const double low = std::min(shown(*top), shown(*skin)), high = std::max(shown(*top), shown(*skin));
    // The darker texel, and the shading interpolated between the shells' vertices: within 1 %.
    ASSERT_GE(pixels[i].r, 0.99 * low) << "pixel " << i << " t_y " << top->y;
    ASSERT_LE(pixels[i].r, 1.01 * high) << "pixel " << i << " t_y " << top->y;
    lowest = std::min(lowest, low);
    highest = std::max(highest, high);
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(highest - lowest, 0.04);  // the check spans the fibres' turn towards the poles
}

// Fins change only pixels at the silhouette: the difference between renders with and without
// fins lies in the ring between the bare sphere's and the fur's projected radii (± 2 pixels), and
// it is not empty (fins fill the grazing gaps between shells).
TEST_F(FurPassTest, FinsChangeOnlyPixelsAtTheSilhouette) {
  MANE_PHOTO_OR_SKIP(image);
  const SphereMesh sphere = unitSphere(24, 48);
  auto withFins = makePass(image, {.fins = true});
  auto withoutFins = makePass(image, {.fins = false});
  ASSERT_TRUE(withFins && withoutFins);
  ASSERT_TRUE(withFins->setMesh(sphere.data()).has_value());
  ASSERT_TRUE(withoutFins->setMesh(sphere.data()).has_value());
  const Pixels a = render(*withFins, sphereView({}));
  const Pixels b = render(*withoutFins, sphereView({}));
  EXPECT_GT(withFins->finCount(), 40u);
  const double bare = projectedRadius(1.0), outer = projectedRadius(1.0 + kThickness);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (glm::all(glm::lessThan(glm::abs(a[i] - b[i]), glm::vec4(1e-3f)))) continue;
    ++changed;
    const double r = pixelRadius(i);
    EXPECT_GE(r, bare - 2.0) << "pixel " << i;
    EXPECT_LE(r, outer + 2.0) << "pixel " << i;
  }
  EXPECT_GT(changed, 20u);
}

// Leaning fur (FurLook::comb, FurPass::setLeans). A fibre at s·h_b is at p + h_b·(s·n + s²·λ)
// with λ ⟂ n. On a flat square (|x|, |z| ≤ 1, normal +y) seen from in front and a little above,
// fur combed twice its height along +x reaches past the square's right edge by up to 2·h_b and never past its
// left one; combed along −x the reverse. "Past" is beyond every corner of the unleaning fur's
// box (|x|, |z| ≤ 1, 0 ≤ y ≤ h_b) as projected, plus 1.5 pixels.
TEST_F(FurPassTest, CombedFurLeansTheWayItIsCombed) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {.fins = false});
  ASSERT_TRUE(pass);
  SphereMesh square;  // 2 × 2 m, normal +y; the photo 3 times across
  square.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  square.normals.assign(4, glm::vec3(0, 1, 0));
  square.uvs = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  square.indices = {0, 2, 1, 0, 3, 2};
  ASSERT_TRUE(pass->setMesh(square.data()).has_value());
  const Camera camera{.position = {0.0f, 1.2f, 4.0f}, .target = {0.0f, 0.0f, 0.0f}, .verticalFovRadians = 0.7f};
  const glm::mat4 viewProjection = camera.projection(float(kExtent.width) / float(kExtent.height)) * camera.view();
  double left = kExtent.width, right = 0.0;
  for (const float x : {-1.0f, 1.0f})
    for (const float y : {0.0f, kThickness})
      for (const float z : {-1.0f, 1.0f}) {
        const glm::vec4 clip = viewProjection * glm::vec4(x, y, z, 1.0f);
        const double pixel = (0.5 * clip.x / clip.w + 0.5) * kExtent.width;
        left = std::min(left, pixel);
        right = std::max(right, pixel);
      }
  std::array<std::array<std::size_t, 2>, 2> past{};  // [comb +x, −x][past left, past right]
  for (int k = 0; k < 2; ++k) {
    FurView view = sphereView({.comb = glm::vec3(k == 0 ? 2.0f : -2.0f, 0.0f, 0.0f)});
    view.viewProjection = viewProjection;
    view.eye = glm::vec4(camera.position, 1.0f);
    const Pixels pixels = render(*pass, view);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      if (pixels[i].a < 0.5f) continue;
      const double x = double(i % kExtent.width) + 0.5;
      if (x < left - 1.5) ++past[k][0];
      if (x > right + 1.5) ++past[k][1];
    }
  }
  EXPECT_GT(past[0][1], 20u) << "combed along +x, fur reaches past the right edge";
  EXPECT_EQ(past[0][0], 0u);
  EXPECT_GT(past[1][0], 20u) << "combed along -x, fur reaches past the left edge";
  EXPECT_EQ(past[1][1], 0u);
}

// Per-vertex leans are the comb's path for one vertex at a time: setting each vertex's lean to
// the comb's projection on its tangent plane (what the shader does with the comb) draws the same
// fur. Pixels may differ only where float rounding flips the alpha test: under 1 %.
TEST_F(FurPassTest, PerVertexLeansMatchTheCombTheyProject) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {});
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const glm::vec3 comb(0.3f, -0.8f, 0.2f);
  const Pixels combed = render(*pass, sphereView({.comb = comb}));
  std::vector<glm::vec3> leans;
  for (const glm::vec3& n : sphere.normals) {
    const glm::vec3 unit = glm::normalize(n);
    leans.push_back(comb - glm::dot(comb, unit) * unit);
  }
  ASSERT_TRUE(pass->setLeans(leans).has_value());
  const Pixels leaning = render(*pass, sphereView({}));
  std::size_t differing = 0;
  for (std::size_t i = 0; i < combed.size(); ++i)
    differing += glm::any(glm::greaterThan(glm::abs(combed[i] - leaning[i]), glm::vec4(2e-2f)));
  EXPECT_LT(double(differing), 0.01 * double(combed.size()));
  EXPECT_FALSE(pass->setLeans(std::span(leans).first(3)).has_value()) << "one lean per vertex";
  leans[5].y = std::nanf("");
  EXPECT_FALSE(pass->setLeans(leans).has_value()) << "a NaN lean";
}

// The fur-direction field (FurLook::layDirection): the shaders' photo coordinates equal the
// CPU's for the same frames, (p·(n × f), p·f) × repeats per metre with f the field projected on
// the surface: the sphere drawn with the field matches the sphere whose uvs are those
// coordinates, drawn by its uvs (pixels may differ only where rounding flips the alpha test:
// under 1 %). And it is not the uv mapping: without the field the image differs.
TEST_F(FurPassTest, TheFurDirectionFieldLaysThePhotoAlongTheSurface) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {});
  ASSERT_TRUE(pass);
  SphereMesh sphere = unitSphere(24, 48);
  const glm::vec3 field(0.0f, -1.0f, 0.3f);
  constexpr float kRepeats = 2.5f;
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const Pixels laid = render(*pass, sphereView({.layDirection = field, .layRepeatsPerMetre = kRepeats}));
  const Pixels byUvs = render(*pass, sphereView({}));
  const glm::vec3 d = glm::normalize(field);
  for (std::size_t v = 0; v < sphere.positions.size(); ++v) {
    const glm::vec3 n = glm::normalize(sphere.normals[v]);
    glm::vec3 f = d - glm::dot(d, n) * n;
    if (glm::dot(f, f) < 1e-6f)
      f = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
    f = glm::normalize(f);
    const glm::vec3& p = sphere.positions[v];
    sphere.uvs[v] = glm::vec2(glm::dot(p, glm::cross(n, f)), glm::dot(p, f)) * kRepeats;
  }
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const Pixels reference = render(*pass, sphereView({}));
  std::size_t differing = 0, differingFromUvs = 0;
  for (std::size_t i = 0; i < laid.size(); ++i) {
    differing += glm::any(glm::greaterThan(glm::abs(laid[i] - reference[i]), glm::vec4(2e-2f)));
    differingFromUvs += glm::any(glm::greaterThan(glm::abs(laid[i] - byUvs[i]), glm::vec4(2e-2f)));
  }
  EXPECT_LT(double(differing), 0.01 * double(laid.size()));
  EXPECT_GT(double(differingFromUvs), 0.05 * double(laid.size()));
}

// The fur as a shadow caster: one strand per vertex from the placed skin point p to the top of
// its fur, p + h_b·(n + λ) with λ the comb projected on the surface, in world space, its ends
// moved half a mean edge (× the scale, 2) back and forward along furShadowTangent(n).
TEST_F(FurPassTest, ShadowStrandsRunFromTheSkinToTheTopOfTheFur) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {});
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(12, 24);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const glm::vec3 comb(0.0f, -0.5f, 0.0f);
  FurView view = sphereView({.comb = comb});
  view.model =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.2f, 0.1f)) * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
  ASSERT_TRUE(pass->update(view).has_value());
  const OpacityShadowStrands strands = pass->shadowStrands();
  ASSERT_EQ(strands.strandCount, sphere.positions.size());
  ASSERT_EQ(strands.verticesPerStrand, 2u);
  const auto* points = reinterpret_cast<const glm::vec4*>(strands.positions->mapped().data());
  const BoundingSphere& bounds = pass->shadowBounds();
  for (std::size_t v = 0; v < sphere.positions.size(); ++v) {
    const glm::vec3 n = glm::normalize(sphere.normals[v]);
    const glm::vec3 across = 0.5f * pass->meanEdgeLength() * 2.0f * furShadowTangent(n);
    const glm::vec3 root = 2.0f * sphere.positions[v] + glm::vec3(0.3f, -0.2f, 0.1f) - across;
    const glm::vec3 tip = root + kThickness * (n + comb - glm::dot(comb, n) * n) + 2.0f * across;
    EXPECT_LT(glm::distance(glm::vec3(points[2 * v]), root), 1e-5f) << "vertex " << v;
    EXPECT_LT(glm::distance(glm::vec3(points[2 * v + 1]), tip), 1e-5f) << "vertex " << v;
    EXPECT_LE(glm::distance(tip, bounds.centre), bounds.radius);
    EXPECT_LE(glm::distance(root, bounds.centre), bounds.radius);
  }
  EXPECT_FLOAT_EQ(pass->shadowColumnWidth(), 2.0f * pass->meanEdgeLength());  // at the model's scale
}

// Self-shadowing: the fur's own strands in a 16-slice opacity map of the first light (as the
// renderer registers them: a texel about one column wide). Lit from the side (+x), the fur on
// the lit side has nothing between it and the light but its own column, while light reaching
// the far side has crossed the fur layer at least twice. Seen from the light, a tilted column
// covers about w² of the w² of surface per vertex, so a crossing keeps about exp(−o) = 0.74
// (o = kFurColumnOpacity) and two 0.55, less towards the terminator, where the light grazes the
// layer: on the lit third of the disc the direct light must keep more than 0.7 of the
// unshadowed render (measured 0.72), and over the far third less than 0.55 (0.25).
TEST_F(FurPassTest, FurShadowsItsFarSideThroughTheOpacityMap) {
  MANE_PHOTO_OR_SKIP(image);
  auto shadows = HairShadowPass::create(device());
  ASSERT_TRUE(shadows.has_value());
  auto pass = FurPass::create(device(), {}, texture(image), {.layers = 15, .thickness = kThickness}, shadows->get());
  ASSERT_TRUE(pass.has_value()) << pass.error().message;
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE((*pass)->setMesh(sphere.data()).has_value());
  FurView view = sphereView({.specularStrength = 0.0f});
  view.light.direction = glm::vec3(1.0f, 0.0f, 0.0f);
  view.ambient = glm::vec3(0.0f);            // direct light only: the part the map attenuates
  const Pixels bare = render(**pass, view);  // no map yet: every slot empty, T = 1

  const std::array<HairShadowPass::Groom, 1> casters{{{.strands = (*pass)->shadowStrands(),
                                                       .width = (*pass)->shadowColumnWidth(),
                                                       .opacity = kFurColumnOpacity,
                                                       .extinction = 1.0f,
                                                       .resolution = (*pass)->shadowResolution()}}};
  ASSERT_TRUE((*shadows)->setGrooms(casters, {}).has_value());
  const auto noWidth = (*shadows)->setStrandWidth(0, 0.0f);
  ASSERT_FALSE(noWidth.has_value());
  EXPECT_NE(noWidth.error().message.find("strand width 0.000000 m is not positive"), std::string::npos)
      << noWidth.error().message;
  ASSERT_TRUE((*shadows)->setBounds(0, (*pass)->shadowBounds()).has_value());
  device().submitAndWait(
      [&](const vk::raii::CommandBuffer& commands) { (*shadows)->record(commands, view.light.direction); });
  // One texel of the map spans about one column, so that the columns fill it without gaps.
  const float texel = (*shadows)->uniforms().maps[0].texels.w;
  std::printf("fur self-shadow: %u texels per side, a texel %.3f of a column\n", (*pass)->shadowResolution(),
              static_cast<double>(texel / (*pass)->shadowColumnWidth()));
  EXPECT_GT(texel, 0.7f * (*pass)->shadowColumnWidth());
  EXPECT_LT(texel, 1.5f * (*pass)->shadowColumnWidth());
  (*pass)->refreshShadows();
  (*pass)->setShadowUniforms((*shadows)->uniforms());
  const Pixels shadowed = render(**pass, view);

  // Screen x > 0 is the lit side (+x), x < 0 the far side; only the body's disc.
  std::array<double, 2> litSum{}, farSum{};  // [bare, shadowed]
  for (std::size_t i = 0; i < bare.size(); ++i) {
    if (bare[i].a < 0.5f || pixelRadius(i) > projectedRadius(1.0) - 2.0) continue;
    const double x = double(i % kExtent.width) + 0.5 - 0.5 * kExtent.width;
    const double b = bare[i].r + bare[i].g + bare[i].b, s = shadowed[i].r + shadowed[i].g + shadowed[i].b;
    if (std::abs(x) < 0.3 * projectedRadius(1.0)) continue;
    auto& sums = x > 0.0 ? litSum : farSum;
    sums[0] += b;
    sums[1] += s;
  }
  ASSERT_GT(litSum[0], 0.0);
  ASSERT_GT(farSum[0], 0.0);
  std::printf("fur self-shadow: direct light kept %.3f on the lit third, %.3f on the far third\n",
              litSum[1] / litSum[0], farSum[1] / farSum[0]);
  EXPECT_GT(litSum[1] / litSum[0], 0.7) << "the lit side keeps most of its light";
  EXPECT_LT(farSum[1] / farSum[0], 0.55) << "the far side is in the fur's shadow";
}

// 160×120, 15 shells + fins, the real photo. Tolerance: 8 levels on 2 % of the pixels — the
// alpha test flips pixels whose luminance sits at a threshold when the LLVM or Mesa version
// rounds a texture filter differently.
TEST_F(FurPassTest, FurredSphereMatchesTheGoldenImage) {
  MANE_PHOTO_OR_SKIP(image);
  auto pass = makePass(image, {});
  ASSERT_TRUE(pass);
  const SphereMesh sphere = unitSphere(24, 48);
  ASSERT_TRUE(pass->setMesh(sphere.data()).has_value());
  const Pixels pixels = render(*pass, sphereView({.pixelsPerLayer = 0.0f}));
  std::vector<std::uint8_t> rgba(pixels.size() * 4);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = std::uint8_t(std::lround(255.0 * srgbEncode(pixels[i][c])));
    rgba[4 * i + 3] = 255;
  }
  const auto comparison = testing::compareWithGolden("fur_sphere", {kExtent.width, kExtent.height, rgba},
                                                     {.maxChannelDifference = 8, .maxFailingFraction = 0.02});
  EXPECT_TRUE(comparison.passed) << comparison.message;
}

}  // namespace
}  // namespace mane::render
