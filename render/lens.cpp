#include "render/lens.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/common.hpp>
#include <glm/matrix.hpp>

namespace mane::render {
namespace {

constexpr float kMinusCentreThickness = 1.5e-3f;  // metres: what a minus lens keeps at its thinnest
constexpr float kPlusEdgeThickness = 1e-3f;       // metres: what a plus lens keeps at its edge
constexpr float kMaxHalfAperture = 0.1f;

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

float lensSag(float curvature, float r) {
  const float c2r2 = curvature * curvature * r * r;
  return curvature * r * r / (1.0f + std::sqrt(std::max(1.0f - c2r2, 0.0f)));
}

float thinLensPower(const LensShape& shape) {
  return (shape.ior - 1.0f) * (shape.frontCurvature - shape.backCurvature);
}

Result<void> validateLensShape(const LensShape& shape) {
  const glm::vec2 h = shape.halfAperture;
  if (!std::isfinite(shape.frontCurvature) || !std::isfinite(shape.backCurvature) ||
      !std::isfinite(shape.centreThickness) || !std::isfinite(shape.ior) || !finite(shape.transmittance) ||
      !std::isfinite(h.x) || !std::isfinite(h.y))
    return fail("the lens has a value that is not a finite number");
  if (!(shape.centreThickness > 0.0f)) return fail("the lens's centre thickness must be above 0 m");
  if (!(h.x > 0.0f && h.y > 0.0f && h.x <= kMaxHalfAperture && h.y <= kMaxHalfAperture))
    return fail("the lens's half aperture must lie in (0, 0.1] m on each side");
  if (!(shape.ior >= 1.0f && shape.ior <= 3.0f)) return fail("the lens's index of refraction must lie in [1, 3]");
  if (glm::any(glm::lessThan(shape.transmittance, glm::vec3(0.0f))) ||
      glm::any(glm::greaterThan(shape.transmittance, glm::vec3(1.0f))))
    return fail("the lens's transmittance must lie in [0, 1] in each channel");
  const float reach = std::max(h.x, h.y);  // the outline's farthest point from the axis
  if (std::abs(shape.frontCurvature) * reach >= 1.0f || std::abs(shape.backCurvature) * reach >= 1.0f)
    return fail("the lens is too curved for its outline: a surface of curvature " +
                std::to_string(std::max(std::abs(shape.frontCurvature), std::abs(shape.backCurvature))) +
                "/m ends before " + std::to_string(reach) + " m from the axis");
  // The outline's edge is thinnest at its farthest point or at its nearest (x or y half aperture).
  for (const float r : {h.x, h.y})
    if (shape.centreThickness + lensSag(shape.backCurvature, r) - lensSag(shape.frontCurvature, r) <= 0.0f)
      return fail("the lens's surfaces cross inside its outline: make it thicker at the centre");
  return {};
}

Result<void> validateLens(const Lens& lens) {
  if (auto valid = validateLensShape(lens.shape); !valid) return valid;
  const glm::mat4& m = lens.model;
  for (int c = 0; c < 4; ++c)
    if (!std::isfinite(m[c].x) || !std::isfinite(m[c].y) || !std::isfinite(m[c].z) || !std::isfinite(m[c].w))
      return fail("the lens's placement is not finite");
  const glm::mat3 rotation(m);
  const glm::mat3 error = glm::transpose(rotation) * rotation - glm::mat3(1.0f);
  float worst = 0.0f;
  for (int c = 0; c < 3; ++c)
    worst = std::max({worst, std::abs(error[c].x), std::abs(error[c].y), std::abs(error[c].z)});
  if (worst > 1e-3f || glm::determinant(rotation) < 0.0f || m[0].w != 0.0f || m[1].w != 0.0f || m[2].w != 0.0f ||
      m[3].w != 1.0f)
    return fail("the lens's placement is not a rotation and a translation");
  return {};
}

Result<LensShape> spectacleLens(float powerDioptres, glm::vec2 halfAperture, float ior) {
  if (!std::isfinite(powerDioptres) || std::abs(powerDioptres) > kMaxLensPower)
    return fail("a spectacle lens's power must lie in [-20, 20] dioptres, not " + std::to_string(powerDioptres));
  if (!(ior > 1.0f)) return fail("a spectacle lens's index of refraction must be above 1");
  // Vogel's rule (front surface power, dioptres), for a meniscus with the least oblique astigmatism.
  const float frontPower =
      std::max(powerDioptres >= 0.0f ? powerDioptres / 2.0f + 6.0f : powerDioptres / 4.0f + 6.0f, 1.0f);
  LensShape shape{.frontCurvature = frontPower / (ior - 1.0f),
                  .backCurvature = (frontPower - powerDioptres) / (ior - 1.0f),
                  .halfAperture = halfAperture,
                  .ior = ior};
  const float reach = std::max(halfAperture.x, halfAperture.y);
  if (std::abs(shape.frontCurvature) * reach >= 1.0f || std::abs(shape.backCurvature) * reach >= 1.0f)
    return fail("a " + std::to_string(powerDioptres) + " D lens cannot be cut this wide");
  const float edgeGain = lensSag(shape.backCurvature, reach) - lensSag(shape.frontCurvature, reach);
  shape.centreThickness = std::max(kMinusCentreThickness, kPlusEdgeThickness - edgeGain);
  if (auto valid = validateLensShape(shape); !valid) return std::unexpected(valid.error());
  return shape;
}

}  // namespace mane::render
