#include "render/environment/sky_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace mane::render {
namespace {

constexpr double kPi = std::numbers::pi;

// The Perez function's five coefficients for one of Y, x, y.
struct Perez {
  double a, b, c, d, e;

  // F(θ, γ) = (1 + A·e^(B/cos θ))·(1 + C·e^(Dγ) + E·cos²γ): θ from the zenith, γ from the sun.
  double operator()(double cosTheta, double gamma) const {
    const double cosGamma = std::cos(gamma);
    return (1.0 + a * std::exp(b / cosTheta)) * (1.0 + c * std::exp(d * gamma) + e * cosGamma * cosGamma);
  }
};

// The paper's appendix A.2, coefficients as linear functions of the turbidity T.
Perez luminanceCoefficients(double t) {
  return {0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771, -0.0670 * t + 0.3703};
}
Perez xCoefficients(double t) {
  return {-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989, -0.0033 * t + 0.0452};
}
Perez yCoefficients(double t) {
  return {-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537, -0.0109 * t + 0.0529};
}

// The zenith's chromaticity: [T² T 1] · M · [θs³ θs² θs 1]ᵀ (appendix A.2).
double zenithChromaticity(const double (&m)[3][4], double t, double thetaSun) {
  const double tv[3] = {t * t, t, 1.0};
  const double sv[4] = {thetaSun * thetaSun * thetaSun, thetaSun * thetaSun, thetaSun, 1.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) sum += tv[i] * m[i][j] * sv[j];
  return sum;
}
constexpr double kZenithX[3][4] = {
    {0.00166, -0.00375, 0.00209, 0.0}, {-0.02903, 0.06377, -0.03202, 0.00394}, {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {
    {0.00275, -0.00610, 0.00317, 0.0}, {-0.04214, 0.08970, -0.04153, 0.00516}, {0.15346, -0.26756, 0.06670, 0.26688}};

// CIE XYZ → linear sRGB (IEC 61966-2-1, D65 white).
glm::dvec3 linearSrgb(double x, double y, double luminance) {
  const double bigX = x / y * luminance;
  const double bigZ = (1.0 - x - y) / y * luminance;
  return {3.2404542 * bigX - 1.5371385 * luminance - 0.4985314 * bigZ,
          -0.9692660 * bigX + 1.8760108 * luminance + 0.0415560 * bigZ,
          0.0556434 * bigX - 0.2040259 * luminance + 1.0572252 * bigZ};
}

// The sun's zenith angle, at most just short of the horizon.
double sunZenithAngle(glm::vec3 towardSun) {
  const double elevation = std::max(double(glm::normalize(towardSun).y), 0.0);
  return std::min(std::acos(elevation), 0.5 * kPi - 1e-3);
}

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Result<void> validateSky(const SkySettings& settings) {
  if (!finite(settings.towardSun) || !(glm::length(settings.towardSun) > 0.0f))
    return fail("the direction towards the sun must be finite and not zero");
  if (!(settings.turbidity >= 1.7f && settings.turbidity <= 10.0f))
    return fail("turbidity " + std::to_string(settings.turbidity) + " is outside [1.7, 10]");
  if (!(settings.zenithLuminance >= 0.0f && std::isfinite(settings.zenithLuminance)))
    return fail("the zenith's luminance must be finite and not negative");
  if (!(settings.groundAlbedo >= 0.0f && settings.groundAlbedo <= 1.0f))
    return fail("ground albedo " + std::to_string(settings.groundAlbedo) + " is outside [0, 1]");
  if (!finite(settings.sunLight) || glm::any(glm::lessThan(settings.sunLight, glm::vec3(0.0f))))
    return fail("the sun's light must be finite and not negative");
  return {};
}

glm::vec3 skyRadiance(const SkySettings& settings, glm::vec3 direction) {
  const double t = settings.turbidity;
  const double thetaSun = sunZenithAngle(settings.towardSun);
  // The sun at its clamped zenith angle, in its own azimuth (any, when it stands at the zenith).
  glm::dvec3 horizontal(settings.towardSun.x, 0.0, settings.towardSun.z);
  horizontal = glm::length(horizontal) > 1e-9 ? glm::normalize(horizontal) : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 sun = std::sin(thetaSun) * horizontal + glm::dvec3(0.0, std::cos(thetaSun), 0.0);
  const glm::dvec3 d = glm::normalize(glm::dvec3(direction));
  const double cosTheta = std::max(d.y, 1e-3);
  const double gamma = std::acos(std::clamp(glm::dot(d, sun), -1.0, 1.0));
  const Perez luminance = luminanceCoefficients(t), px = xCoefficients(t), py = yCoefficients(t);
  // Each quantity is its zenith value × F(θ, γ) / F(0, θs).
  const double x = zenithChromaticity(kZenithX, t, thetaSun) * px(cosTheta, gamma) / px(1.0, thetaSun);
  const double y = zenithChromaticity(kZenithY, t, thetaSun) * py(cosTheta, gamma) / py(1.0, thetaSun);
  const double relativeLuminance = luminance(cosTheta, gamma) / luminance(1.0, thetaSun);
  const glm::dvec3 colour = glm::max(linearSrgb(x, y, relativeLuminance), glm::dvec3(0.0));
  return glm::vec3(colour * double(settings.zenithLuminance));
}

CubeMap skyCubeMap(const SkySettings& settings, int size) {
  CubeMap cube;
  cube.size = size;
  glm::dvec3 skyIrradiance(0.0);  // on the ground, facing up
  for (int face = 0; face < 6; ++face) {
    cube.faces[static_cast<std::size_t>(face)].assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size),
                                                      glm::vec3(0.0f));
    for (int row = 0; row < size; ++row)
      for (int column = 0; column < size; ++column) {
        const glm::vec3 d =
            cubeDirection(face, {(float(column) + 0.5f) / float(size), (float(row) + 0.5f) / float(size)});
        if (!(d.y > 0.0f)) continue;
        const glm::vec3 radiance = skyRadiance(settings, d);
        cube.faces[static_cast<std::size_t>(face)][static_cast<std::size_t>(row) * static_cast<std::size_t>(size) +
                                                   static_cast<std::size_t>(column)] = radiance;
        skyIrradiance += glm::dvec3(radiance) * double(d.y) * cubeTexelSolidAngle(size, column, row);
      }
  }
  const float sunElevation = std::max(glm::normalize(settings.towardSun).y, 0.0f);
  const glm::vec3 ground = settings.groundAlbedo * (glm::vec3(skyIrradiance / kPi) + settings.sunLight * sunElevation);
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < size; ++row)
      for (int column = 0; column < size; ++column) {
        const glm::vec3 d =
            cubeDirection(face, {(float(column) + 0.5f) / float(size), (float(row) + 0.5f) / float(size)});
        if (d.y > 0.0f) continue;
        cube.faces[static_cast<std::size_t>(face)][static_cast<std::size_t>(row) * static_cast<std::size_t>(size) +
                                                   static_cast<std::size_t>(column)] = ground;
      }
  return cube;
}

}  // namespace mane::render
