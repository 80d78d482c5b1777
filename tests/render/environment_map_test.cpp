// Environment maps on the CPU: panorama and cube-map directions, the cube's solid angles, the
// panorama → cube conversion, nine spherical harmonics against closed forms and brute force, the
// Preetham sky's properties, and the sun cut out of an environment with its energy kept.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "render/environment/environment_map.hpp"
#include "render/environment/specular_reference.hpp"
#include "render/environment/sky_model.hpp"
#include "render/environment/spherical_harmonics.hpp"
#include "render/environment/sun_extraction.hpp"
#include "render/luts/skin_specular.hpp"
#include "tests/render/environment_cubes.hpp"

namespace mane::render {
namespace {

constexpr double kPi = std::numbers::pi;

EquirectImage panoramaOf(int width, int height, auto radiance) {
  EquirectImage image{.width = width, .height = height};
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column)
      image.texels.push_back(
          radiance(equirectDirection({(float(column) + 0.5f) / float(width), (float(row) + 0.5f) / float(height)})));
  return image;
}

// E(n) = Σ L·max(n·ω, 0)·dω over every texel: the irradiance by brute force.
glm::dvec3 bruteForceIrradiance(const CubeMap& cube, glm::vec3 normal) {
  glm::dvec3 sum(0.0);
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < cube.size; ++row)
      for (int column = 0; column < cube.size; ++column) {
        const glm::vec3 d =
            cubeDirection(face, {(float(column) + 0.5f) / float(cube.size), (float(row) + 0.5f) / float(cube.size)});
        sum += glm::dvec3(cube.at(face, column, row)) * double(std::max(glm::dot(normal, d), 0.0f)) *
               cubeTexelSolidAngle(cube.size, column, row);
      }
  return sum;
}

std::vector<glm::vec3> testNormals() {
  std::vector<glm::vec3> normals;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x != 0 || y != 0 || z != 0) normals.push_back(glm::normalize(glm::vec3(x, y, z)));
  return normals;
}

TEST(EnvironmentMap, PanoramaCoordinatesFollowTheStatedAxes) {
  EXPECT_NEAR(equirectCoordinates({0, 0, -1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(equirectCoordinates({1, 0, 0}).x, 0.75f, 1e-6f);
  EXPECT_NEAR(equirectCoordinates({0, 1, 0}).y, 0.0f, 1e-6f);
  EXPECT_NEAR(equirectCoordinates({0, 0, -1}).y, 0.5f, 1e-6f);
  for (float u = 0.05f; u < 1.0f; u += 0.1f)
    for (float v = 0.05f; v < 1.0f; v += 0.1f) {
      const glm::vec2 back = equirectCoordinates(equirectDirection({u, v}));
      EXPECT_NEAR(back.x, u, 1e-5f);
      EXPECT_NEAR(back.y, v, 1e-5f);
    }
}

TEST(EnvironmentMap, CubeFacesFollowVulkansFaceSelectionTable) {
  // Each face's centre looks along its axis; s and t grow along the table's sc and tc.
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const glm::vec3 sAxis[6] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {-1, 0, 0}};
  const glm::vec3 tAxis[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  for (int face = 0; face < 6; ++face) {
    EXPECT_LT(glm::length(cubeDirection(face, {0.5f, 0.5f}) - axes[face]), 1e-6f) << face;
    EXPECT_LT(glm::length(cubeDirection(face, {1.0f, 0.5f}) - glm::normalize(axes[face] + sAxis[face])), 1e-6f) << face;
    EXPECT_LT(glm::length(cubeDirection(face, {0.5f, 1.0f}) - glm::normalize(axes[face] + tAxis[face])), 1e-6f) << face;
    for (float s = 0.1f; s < 1.0f; s += 0.2f)
      for (float t = 0.1f; t < 1.0f; t += 0.2f) {
        const CubeCoordinates back = cubeCoordinates(cubeDirection(face, {s, t}));
        EXPECT_EQ(back.face, face);
        EXPECT_NEAR(back.st.x, s, 1e-5f);
        EXPECT_NEAR(back.st.y, t, 1e-5f);
      }
  }
}

TEST(EnvironmentMap, CubeTexelSolidAnglesSumToTheWholeSphere) {
  for (int size : {1, 7, 64}) {
    double sum = 0.0;
    for (int row = 0; row < size; ++row)
      for (int column = 0; column < size; ++column) sum += cubeTexelSolidAngle(size, column, row);
    EXPECT_NEAR(6.0 * sum, 4.0 * kPi, 1e-9) << size;
  }
  // A face's centre texel against its small-texel limit, area × cos³ at unit distance.
  const int size = 1001;
  EXPECT_NEAR(cubeTexelSolidAngle(size, 500, 500), std::pow(2.0 / size, 2.0), 1e-11);
}

TEST(EnvironmentMap, PanoramaToCubeAndBackKeepsASmoothEnvironment) {
  const auto radiance = [](glm::vec3 d) {
    return glm::vec3(1.0f + 0.5f * d.x, 1.0f + 0.8f * d.y * d.y, 1.5f + std::sin(2.0f * d.z) + 0.3f * d.x * d.y);
  };
  const EquirectImage panorama = panoramaOf(256, 128, radiance);
  const CubeMap cube = cubeFromEquirect(panorama, 64);
  float worst = 0.0f;
  for (int row = 0; row < panorama.height; ++row)
    for (int column = 0; column < panorama.width; ++column) {
      const glm::vec3 d = equirectDirection({(float(column) + 0.5f) / 256.0f, (float(row) + 0.5f) / 128.0f});
      const glm::vec3 back = sampleCube(cube, d), original = panorama.at(column, row);
      worst = std::max(worst, glm::length(back - original) / glm::length(original));
    }
  EXPECT_LT(worst, 0.01f);
}

TEST(EnvironmentMap, RotationTurnsThePanoramaCounterClockwiseSeenFromAbove) {
  // A bright patch straight ahead (−Z) turned a quarter turn lies towards −X.
  const EquirectImage panorama = panoramaOf(
      128, 64, [](glm::vec3 d) { return glm::vec3(glm::dot(d, glm::vec3(0, 0, -1)) > 0.95f ? 10.0f : 0.1f); });
  const CubeMap cube = cubeFromEquirect(panorama, 32, float(kPi / 2.0), 2.0f);
  EXPECT_NEAR(sampleCube(cube, {-1, 0, 0}).x, 20.0f, 1e-3f);
  EXPECT_NEAR(sampleCube(cube, {0, 0, -1}).x, 0.2f, 1e-4f);
}

TEST(SphericalHarmonics, AConstantEnvironmentGivesPiTimesItsRadianceFromEveryNormal) {
  const glm::vec3 radiance(0.7f, 1.3f, 2.0f);
  const SphericalHarmonics9 irradiance =
      irradianceFromRadiance(projectRadiance(cubeOf(32, [&](glm::vec3) { return radiance; })));
  for (glm::vec3 n : testNormals()) {
    const glm::vec3 e = evaluate(irradiance, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], kPi * radiance[c], 2e-5 * kPi * radiance[c]);
  }
}

TEST(SphericalHarmonics, ProjectionMatchesTheClosedFormCoefficients) {
  // L = a + b·y + c·(3z² − 1) + e·xy: its coefficients are the harmonics' inverse normalisations.
  const float a = 0.8f, b = 0.5f, c = 0.2f, e = 0.3f;
  const SphericalHarmonics9 sh = projectRadiance(
      cubeOf(64, [&](glm::vec3 d) { return glm::vec3(a + b * d.y + c * (3 * d.z * d.z - 1) + e * d.x * d.y); }));
  const double expected[9] = {a * std::sqrt(4 * kPi),
                              b * std::sqrt(4 * kPi / 3),
                              0,
                              0,
                              e * std::sqrt(4 * kPi / 15),
                              0,
                              c * std::sqrt(16 * kPi / 5),
                              0,
                              0};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(sh[i].x, expected[i], 1e-4) << "coefficient " << i;
}

TEST(SphericalHarmonics, IrradianceOfALinearSkyIsExact) {
  // L = a + b·y: E(n) = π·a + (2π/3)·b·n_y, against the brute-force cosine integral as well.
  const float a = 1.0f, b = 0.6f;
  const CubeMap cube = cubeOf(48, [&](glm::vec3 d) { return glm::vec3(a + b * d.y); });
  const SphericalHarmonics9 irradiance = irradianceFromRadiance(projectRadiance(cube));
  for (glm::vec3 n : testNormals()) {
    const double exact = kPi * a + 2.0 * kPi / 3.0 * b * n.y;
    EXPECT_NEAR(evaluate(irradiance, n).x, exact, 1e-4 * exact);
    EXPECT_NEAR(bruteForceIrradiance(cube, n).x, exact, 2e-3 * exact);
  }
}

TEST(SphericalHarmonics, NineTermsFollowABruteForceIrradianceOfADaylightSky) {
  // Ramamoorthi and Hanrahan give an average error under 3 % for natural light; a sky with its
  // sun's glow and a horizon is such light.
  const CubeMap sky = skyCubeMap({.towardSun = glm::normalize(glm::vec3(0.4f, 0.5f, -0.3f)), .turbidity = 3.0f}, 32);
  const SphericalHarmonics9 irradiance = irradianceFromRadiance(projectRadiance(sky));
  double sumError = 0.0, sumExact = 0.0;
  for (glm::vec3 n : testNormals()) {
    const double exact = bruteForceIrradiance(sky, n).y;
    const double error = std::abs(double(evaluate(irradiance, n).y) - exact);
    sumError += error;
    sumExact += exact;
    EXPECT_LT(error, 0.1 * exact) << n.x << " " << n.y << " " << n.z;
  }
  EXPECT_LT(sumError / sumExact, 0.03);
}

TEST(SkyModel, TheZenithShowsItsLuminanceAndTheSkyIsSymmetricAboutTheSunsPlane) {
  const SkySettings sky{.towardSun = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)), .zenithLuminance = 2.0f};
  const glm::vec3 zenith = skyRadiance(sky, {0, 1, 0});
  EXPECT_NEAR(glm::dot(zenith, glm::vec3(0.2126f, 0.7152f, 0.0722f)), 2.0f, 1e-3f);
  EXPECT_GT(zenith.b, 1.3f * zenith.r);  // a clear sky's zenith is blue
  const glm::vec3 left = skyRadiance(sky, glm::normalize(glm::vec3(0.3f, 0.4f, 0.7f)));
  const glm::vec3 right = skyRadiance(sky, glm::normalize(glm::vec3(0.3f, 0.4f, -0.7f)));
  EXPECT_LT(glm::length(left - right), 1e-6f);
}

TEST(SkyModel, AClearSkyIsBlueAndBrightestAroundTheSun) {
  const glm::vec3 towardSun = glm::normalize(glm::vec3(0.0f, 1.0f, -1.0f));
  const SkySettings sky{.towardSun = towardSun, .turbidity = 2.5f};
  const glm::vec3 nearSun = skyRadiance(sky, glm::normalize(towardSun + glm::vec3(0.05f, 0.0f, 0.0f)));
  const glm::vec3 opposite = skyRadiance(sky, glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f)));
  const glm::vec3 aside = skyRadiance(sky, glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
  EXPECT_GT(nearSun.g, 3.0f * opposite.g);
  EXPECT_GT(aside.b, aside.r);  // Rayleigh scattering: blue away from the sun
  // Haze whitens the sky: blue over red falls with the turbidity.
  const glm::vec3 hazy = skyRadiance({.towardSun = towardSun, .turbidity = 8.0f}, glm::normalize(glm::vec3(1, 1, 0)));
  EXPECT_LT(hazy.b / hazy.r, aside.b / aside.r);
}

TEST(SkyModel, TheGroundShowsTheSunsLightTimesItsAlbedo) {
  // With no sky, the ground is Lambertian under the sun alone: albedo × light × sin(elevation).
  const SkySettings sky{.towardSun = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f)),
                        .zenithLuminance = 0.0f,
                        .groundAlbedo = 0.5f,
                        .sunLight = {2.0f, 2.0f, 2.0f}};
  const CubeMap cube = skyCubeMap(sky, 8);
  EXPECT_NEAR(sampleCube(cube, {0, -1, 0}).x, 0.5f * 2.0f * std::sqrt(0.5f), 1e-6f);
  EXPECT_EQ(sampleCube(cube, {0, 1, 0}).x, 0.0f);
}

TEST(SkyModel, SettingsOutOfRangeAreRefusedByName) {
  EXPECT_TRUE(validateSky({}).has_value());
  const auto message = [](const SkySettings& s) { return validateSky(s).error().message; };
  EXPECT_NE(message({.turbidity = 12.0f}).find("turbidity"), std::string::npos);
  EXPECT_NE(message({.towardSun = glm::vec3(0.0f)}).find("sun"), std::string::npos);
  EXPECT_NE(message({.groundAlbedo = 1.5f}).find("albedo"), std::string::npos);
  EXPECT_NE(message({.zenithLuminance = -1.0f}).find("zenith"), std::string::npos);
}

TEST(SunExtraction, TheSunBecomesALightAndTheEnvironmentKeepsTheRest) {
  // A sky of radiance L_s with a sun of angular radius r and radiance L_d towards D.
  const glm::vec3 sky(0.2f, 0.3f, 0.5f), sunRadiance(3000.0f, 2500.0f, 2000.0f);
  const glm::vec3 toward = glm::normalize(glm::vec3(0.3f, 0.5f, -0.8f));
  const double radius = 1.5 * kPi / 180.0;
  const CubeMap before =
      cubeOf(256, [&](glm::vec3 d) { return glm::dot(d, toward) >= float(std::cos(radius)) ? sunRadiance : sky; });
  const SunExtraction cut = extractSun(before);
  ASSERT_TRUE(cut.sun.has_value());
  const DirectionalLight& sun = *cut.sun;
  EXPECT_LT(std::acos(std::min(glm::dot(sun.direction, toward), 1.0f)), 0.2 * kPi / 180.0);
  // The energy is kept: the light plus what is left light any surface as the whole did.
  for (const glm::vec3 normal : {toward, glm::vec3(0, 1, 0), glm::normalize(glm::vec3(1, 0.2f, 0.4f)), -toward}) {
    const glm::dvec3 whole = bruteForceIrradiance(before, normal);
    const glm::dvec3 split =
        bruteForceIrradiance(cut.radiance, normal) +
        glm::dvec3(sun.color * sun.intensity) * double(std::max(glm::dot(normal, sun.direction), 0.0f));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(split[c], whole[c], 1e-3 * whole[c]) << "channel " << c;
  }
  // The light gives what the disc gave above the sky: (L_d − L_s)·Ω of a cone of radius r, within
  // the texels' fit to the disc's rim.
  const double cone = 2.0 * kPi * (1.0 - std::cos(radius));
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(sun.color[c] * sun.intensity, (sunRadiance[c] - sky[c]) * cone,
                0.05 * (sunRadiance[c] - sky[c]) * cone);
  EXPECT_NEAR(sun.discRadius, radius, 0.05 * radius);
  for (const auto& face : cut.radiance.faces)
    for (const glm::vec3& texel : face) ASSERT_LE(texel.g, sky.g * 1.0001f) << "the sun is cut out";
}

TEST(SunExtraction, AnOvercastSkyHasNoSunToCut) {
  const CubeMap overcast = cubeOf(64, [](glm::vec3 d) { return glm::vec3(0.5f + 0.3f * d.y); });
  const SunExtraction cut = extractSun(overcast);
  EXPECT_FALSE(cut.sun.has_value());
  EXPECT_EQ(cut.radiance.faces, overcast.faces);
}

TEST(SkinSpecularAlbedo, ASmoothSurfaceReflectsSchlicksFresnelAndARoughOneLess) {
  // As the roughness goes to 0, h → n and |l + v|² → 4(n·v)²: the Kelemen/Szirmay-Kalos albedo
  // tends to ∫D(h) dh × F(n·v) = F(n·v).
  for (double cosView : {0.3, 0.6, 0.9}) {
    const double smooth = kelemenSzirmayKalosAlbedo(cosView, 0.05);
    EXPECT_NEAR(smooth, schlickFresnel(cosView), 0.03 * schlickFresnel(cosView)) << cosView;
    const double rough = kelemenSzirmayKalosAlbedo(cosView, 0.3);
    EXPECT_GT(rough, 0.0);
    EXPECT_LT(rough, 1.0);
  }
}

TEST(SpecularReference, GgxIsNormalisedOverTheHemisphere) {
  // ∫ D(h)·cos θ_h dω = 1 (Walter et al. 2007, eq. 4), by the midpoint rule in θ.
  for (double roughness : {0.3, 0.6, 1.0}) {
    double sum = 0.0;
    const int steps = 20000;
    for (int i = 0; i < steps; ++i) {
      const double theta = (i + 0.5) * (kPi / 2.0) / steps;
      sum += ggxDistribution(std::cos(theta), roughness) * std::cos(theta) * std::sin(theta) * 2.0 * kPi * (kPi / 2.0) /
             steps;
    }
    EXPECT_NEAR(sum, 1.0, 1e-4) << roughness;
  }
}

}  // namespace
}  // namespace mane::render
