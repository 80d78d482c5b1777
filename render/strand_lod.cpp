#include "render/strand_lod.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "render/passes/hair_lighting_pass.hpp"

namespace mane::render {

float keptStrandShare(float strandPixels, float lodPixels) {
  if (!(lodPixels > 0.0f) || !(strandPixels < lodPixels)) return 1.0f;
  return std::max(strandPixels / lodPixels, kLeastKeptStrands);
}

float pixelsPerMetreAt(const glm::mat4& viewProjection, glm::vec2 viewport, glm::vec3 point) {
  const glm::vec4 centre = viewProjection * glm::vec4(point, 1.0f);
  if (!(centre.w > 0.0f)) return 0.0f;
  // A step perpendicular to the line of sight, as the strands' ribbons are widened.
  const glm::vec4 eye = hairEye(viewProjection);
  const glm::vec3 toEye = eye.w != 0.0f ? glm::normalize(glm::vec3(eye) - point) : glm::vec3(eye);
  const glm::vec3 side =
      glm::normalize(glm::cross(toEye, std::abs(toEye.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
  const float step = 1e-3f * centre.w;  // small against the view, large against float rounding
  const glm::vec4 moved = viewProjection * glm::vec4(point + side * step, 1.0f);
  const glm::vec2 shift = (glm::vec2(moved) / moved.w - glm::vec2(centre) / centre.w) * 0.5f * viewport;
  return glm::length(shift) / step;
}

}  // namespace mane::render
