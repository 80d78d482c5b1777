#include "render/frame.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace mane::render {

glm::mat4 Camera::view() const {
  return glm::lookAtRH(position, target, up);
}

glm::mat4 Camera::projection(float aspect) const {
  glm::mat4 result = glm::perspectiveRH_ZO(verticalFovRadians, aspect, nearPlane, farPlane);
  result[1][1] = -result[1][1];
  return result;
}

}  // namespace mane::render
