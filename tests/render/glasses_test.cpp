// Spectacle lenses (render/passes/glasses_pass.hpp) against geometric optics in closed form: a
// tilted glass slab shifts what lies behind it sideways by t·sin(θi − θr)/cos θr (Snell's law), a
// plus lens magnifies as the thin-lens equation says, and the glass reflects the environment as
// Fresnel's equations say.

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/lens.hpp"
#include "render/renderer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr float kIor = 1.5f;

/// A white Lambertian rectangle facing +z at z = 0, over x ∈ [x0, x1], y ∈ [−1, 1].
MeshData whiteRectangle(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals, std::vector<glm::vec2>& uvs,
                        std::vector<std::uint32_t>& indices, float x0, float x1) {
  positions = {{x0, -1, 0}, {x1, -1, 0}, {x1, 1, 0}, {x0, 1, 0}};
  normals.assign(4, glm::vec3(0, 0, 1));
  uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  indices = {0, 1, 2, 0, 2, 3};
  return {.positions = positions, .normals = normals, .uvs = uvs, .indices = indices};
}

class Glasses : public testing::VulkanTest {
protected:
  static constexpr vk::Extent2D kExtent{512, 64};

  /// A camera on +z looking down −z at the origin, seeing ±halfWidth·distance across.
  static Camera cameraAt(float z, float tanHalfWidth) {
    const float aspect = float(kExtent.width) / float(kExtent.height);
    return {.position = {0, 0, z}, .target = {0, 0, 0}, .verticalFovRadians = 2.0f * std::atan(tanHalfWidth / aspect)};
  }

  /// The middle row's radiance (red), rendered with the rectangle [x0, x1] lit from `towardLight`,
  /// and `lenses`.
  std::vector<double> middleRow(const Camera& camera, float x0, float x1, std::vector<Lens> lenses,
                                glm::vec3 towardLight = {0, 0, 1}) {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<std::uint32_t> indices;
    auto renderer = Renderer::create(device(), {.extent = kExtent, .msaaSamples = 4});
    EXPECT_TRUE(renderer.has_value());
    if (!renderer) return {};
    const StaticScene scene{.meshes = {whiteRectangle(positions, normals, uvs, indices, x0, x1)},
                            .materials = {MaterialData{.baseColor = glm::vec3(1.0f)}}};
    EXPECT_TRUE((*renderer)->setScene(scene).has_value());
    const FrameInput frame{.camera = camera,
                           .lights = {{.direction = towardLight, .intensity = 1.0f}},
                           .instances = {{.mesh = 0, .material = 0}},
                           .ambient = glm::vec3(0.0f),
                           .background = glm::vec3(0.0f),
                           .lenses = std::move(lenses)};
    auto timings = (*renderer)->render(frame);
    EXPECT_TRUE(timings.has_value()) << (timings ? "" : timings.error().message);
    auto halves = (*renderer)->readHdrOutput();
    EXPECT_TRUE(halves.has_value());
    std::vector<double> row(kExtent.width);
    const std::size_t y = kExtent.height / 2;
    for (std::size_t x = 0; x < kExtent.width; ++x)
      row[x] = glm::unpackHalf1x16((*halves)[(y * kExtent.width + x) * 4]);
    return row;
  }

  /// Where, in pixels from the left edge, the row first rises through half of `level` going right
  /// from `from`, interpolated between pixel centres.
  static std::optional<double> risingEdge(const std::vector<double>& row, double level, std::size_t from = 0) {
    for (std::size_t x = from + 1; x < row.size(); ++x)
      if (row[x - 1] < 0.5 * level && row[x] >= 0.5 * level)
        return double(x - 1) + 0.5 + (0.5 * level - row[x - 1]) / (row[x] - row[x - 1]);
    return std::nullopt;
  }
  static std::optional<double> fallingEdge(const std::vector<double>& row, double level, std::size_t from) {
    for (std::size_t x = from + 1; x < row.size(); ++x)
      if (row[x - 1] >= 0.5 * level && row[x] < 0.5 * level)
        return double(x - 1) + 0.5 + (row[x - 1] - 0.5 * level) / (row[x - 1] - row[x]);
    return std::nullopt;
  }

  /// The pixel column (from the left edge) of a ray at angle φ from the view axis, towards +x.
  static double columnOf(double phi, double tanHalfWidth) {
    return (std::tan(phi) / tanHalfWidth + 1.0) * 0.5 * kExtent.width;
  }
};

/// Fresnel's reflectance of unpolarised light meeting glass of index n from air at angle θi.
double fresnel(double thetaI, double n) {
  const double thetaT = std::asin(std::sin(thetaI) / n);
  const double ci = std::cos(thetaI), ct = std::cos(thetaT);
  const double rs = (ci - n * ct) / (ci + n * ct), rp = (n * ci - ct) / (n * ci + ct);
  return 0.5 * (rs * rs + rp * rp);
}

TEST_F(Glasses, ATiltedSlabShiftsWhatLiesBehindItAsSnellsLawSays) {
  // A flat slab 3 cm thick, turned 30° about +y, halfway between the camera and a white half-plane
  // x > 0. A ray at angle φ meets it at θi = 30° + φ and leaves it parallel, shifted towards −x by
  // d = t·sin(θi − θr)/cos θr: it lands on the plane at 0.5·tan φ − d/cos φ. Turned a further
  // 180°, its back face towards the camera (traced mirrored through its mid-plane), it is the
  // same slab and shifts the edge alike.
  constexpr double kThickness = 0.03, kTilt = 30.0, kTanHalfWidth = 0.12;
  const Camera camera = cameraAt(0.5f, float(kTanHalfWidth));
  const LensShape slab{.centreThickness = float(kThickness), .halfAperture = {0.1f, 0.1f}, .ior = kIor};
  const auto landing = [&](double phi) {
    const double thetaI = glm::radians(kTilt) + phi, thetaR = std::asin(std::sin(thetaI) / kIor);
    return 0.5 * std::tan(phi) - kThickness * std::sin(thetaI - thetaR) / std::cos(thetaR) / std::cos(phi);
  };
  double low = 0.0, high = 0.2;  // landing(low) < 0 < landing(high)
  for (int i = 0; i < 60; ++i) ((landing(0.5 * (low + high)) < 0.0) ? low : high) = 0.5 * (low + high);
  const double expected = columnOf(0.5 * (low + high), kTanHalfWidth);

  const std::vector<double> bare = middleRow(camera, 0.0f, 1.0f, {});
  const double lit = bare.back();
  EXPECT_NEAR(lit, 1.0, 0.01);
  const std::optional<double> bareEdge = risingEdge(bare, lit);
  ASSERT_TRUE(bareEdge);
  EXPECT_NEAR(*bareEdge, 0.5 * kExtent.width, 0.5);
  // What passes both faces: (1 − R(θi))(1 − R(θr seen from inside)), the same factor twice.
  const double thetaI = glm::radians(kTilt) + std::atan((expected / kExtent.width * 2.0 - 1.0) * kTanHalfWidth);
  const double passed = std::pow(1.0 - fresnel(thetaI, kIor), 2.0);
  for (const double turn : {kTilt, kTilt + 180.0}) {
    SCOPED_TRACE(turn);
    const glm::mat4 placement = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 0.25f)),
                                            glm::radians(float(turn)), glm::vec3(0, 1, 0));
    const std::vector<double> through = middleRow(camera, 0.0f, 1.0f, {Lens{slab, placement}});
    ASSERT_EQ(through.size(), kExtent.width);
    const std::optional<double> shiftedEdge = risingEdge(through, through.back());
    ASSERT_TRUE(shiftedEdge);
    EXPECT_GT(*shiftedEdge - *bareEdge, 20.0);
    EXPECT_NEAR(*shiftedEdge, expected, 0.5) << "the slab moved the edge from " << *bareEdge;
    EXPECT_NEAR(through.back(), lit * passed, 0.01 * lit);
  }
}

TEST_F(Glasses, APlusLensMagnifiesAsTheThinLensEquationSays) {
  // A plano-convex +4 D lens (f = 0.25 m), its curved face 0.3 m from the camera, 5 cm in front of
  // a white band 16 mm wide. Thick, it obeys the thin-lens equation measured from its principal
  // planes (Hecht, Optics, 4th ed., §6.2; light from the band meets the flat face first): H' at
  // the curved vertex, H at h₁ = −f(n − 1)t/(n·R₂) = f(n − 1)t·c/n from the flat face towards it.
  constexpr double kPower = 4.0, kGap = 0.05, kEye = 0.3, kHalfBand = 0.008, kTanHalfWidth = 0.04;
  constexpr double kFocal = 1.0 / kPower, kCurvature = kPower / (kIor - 1.0), kThickness = 0.0045;
  const LensShape lens{.frontCurvature = float(kCurvature),
                       .backCurvature = 0.0f,
                       .centreThickness = float(kThickness),
                       .halfAperture = {0.03f, 0.03f},
                       .ior = kIor};
  ASSERT_TRUE(validateLensShape(lens).has_value());
  const double front = kGap + kThickness;  // the curved vertex's z
  const Camera camera = cameraAt(float(front + kEye), float(kTanHalfWidth));
  const glm::mat4 placement = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, float(front)));

  const double objectDistance = kGap + kFocal * (kIor - 1.0) * kThickness * kCurvature / kIor;  // from H
  const double imageDistance = 1.0 / (1.0 / kFocal - 1.0 / objectDistance);  // < 0: virtual, behind H'
  const double magnification = -imageDistance / objectDistance;
  // The band's angular size from the camera: m·h at kEye − imageDistance, against h at front + kEye.
  const double expected = magnification * (front + kEye) / (kEye - imageDistance);

  // Lit from above, so that the lens's glint of the light lies beyond its outline.
  const glm::vec3 towardLight(0.0f, 0.6f, 0.8f);
  const std::vector<double> bare = middleRow(camera, -float(kHalfBand), float(kHalfBand), {}, towardLight);
  const std::vector<double> through =
      middleRow(camera, -float(kHalfBand), float(kHalfBand), {Lens{lens, placement}}, towardLight);
  ASSERT_EQ(through.size(), kExtent.width);
  const double middle = kExtent.width / 2;
  const auto width = [&](const std::vector<double>& row) -> std::optional<double> {
    const double level = row[std::size_t(middle)];
    const auto rise = risingEdge(row, level), fall = fallingEdge(row, level, std::size_t(middle));
    if (!rise || !fall) return std::nullopt;
    return *fall - *rise;
  };
  const std::optional<double> bareWidth = width(bare), magnifiedWidth = width(through);
  ASSERT_TRUE(bareWidth && magnifiedWidth);
  EXPECT_NEAR(*bareWidth, 2.0 * kHalfBand / (front + kEye) / kTanHalfWidth * middle, 0.5);
  EXPECT_NEAR(*magnifiedWidth / *bareWidth, expected, 0.01 * expected)
      << "bare " << *bareWidth << " px, through the lens " << *magnifiedWidth << " px";
}

TEST_F(Glasses, TheGlassReflectsTheEnvironmentAsFresnelSays) {
  // Under a constant environment of radiance L, over a black card, a lens shows F(θ)·L: 4 % head
  // on and more at a slant, where a flat lens is turned 60° away.
  constexpr float kRadiance = 2.0f;
  CubeMap constant{.size = 8};
  for (auto& face : constant.faces) face.assign(64, glm::vec3(kRadiance));
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;
  auto renderer = Renderer::create(device(), {.extent = kExtent, .msaaSamples = 1});
  ASSERT_TRUE(renderer.has_value());
  const StaticScene scene{.environment = EnvironmentData{.radiance = constant},
                          .meshes = {whiteRectangle(positions, normals, uvs, indices, -1.0f, 1.0f)},
                          .materials = {MaterialData{.baseColor = glm::vec3(0.0f)}}};
  ASSERT_TRUE((*renderer)->setScene(scene).has_value());
  for (const double tilt : {0.0, 60.0}) {
    SCOPED_TRACE(tilt);
    const LensShape flat{.centreThickness = 0.002f, .halfAperture = {0.1f, 0.1f}, .ior = kIor};
    const glm::mat4 placement = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 0.25f)),
                                            glm::radians(float(tilt)), glm::vec3(0, 1, 0));
    const FrameInput frame{.camera = cameraAt(0.5f, 0.01f),
                           .instances = {{.mesh = 0, .material = 0}},
                           .ambient = glm::vec3(0.0f),
                           .lenses = {Lens{flat, placement}}};
    ASSERT_TRUE((*renderer)->render(frame).has_value());
    auto halves = (*renderer)->readHdrOutput();
    ASSERT_TRUE(halves.has_value());
    const std::size_t centre = (kExtent.height / 2 * kExtent.width + kExtent.width / 2) * 4;
    EXPECT_NEAR(glm::unpackHalf1x16((*halves)[centre]), fresnel(glm::radians(tilt), kIor) * kRadiance,
                0.02 * fresnel(glm::radians(tilt), kIor) * kRadiance);
  }
}

TEST(SpectacleLens, HasThePrescribedPowerAndIsNoThinnerThanAGrinderLeavesIt) {
  for (const float power : {-6.0f, -2.0f, 0.0f, 2.5f, 6.0f}) {
    SCOPED_TRACE(power);
    auto lens = spectacleLens(power, {0.025f, 0.018f});
    ASSERT_TRUE(lens.has_value()) << lens.error().message;
    EXPECT_NEAR(thinLensPower(*lens), power, 1e-4f);
    EXPECT_GT(lens->frontCurvature, 0.0f);  // a meniscus, bulging outwards
    // The thinnest place: the centre of a minus lens, the outline's far end of a plus lens.
    const float edge =
        lens->centreThickness + lensSag(lens->backCurvature, 0.025f) - lensSag(lens->frontCurvature, 0.025f);
    EXPECT_GE(std::min(edge, lens->centreThickness), 1e-3f - 1e-6f);
  }
  EXPECT_FALSE(spectacleLens(25.0f, {0.025f, 0.018f}).has_value());
  EXPECT_FALSE(spectacleLens(2.0f, {0.0f, 0.018f}).has_value());
  const LensShape crossing{.frontCurvature = 30.0f, .backCurvature = 0.0f, .centreThickness = 0.001f};
  const auto refused = validateLensShape(crossing);
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("cross"), std::string::npos) << refused.error().message;
}

}  // namespace
}  // namespace mane::render
