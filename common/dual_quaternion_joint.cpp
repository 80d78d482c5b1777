#include "common/dual_quaternion_joint.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

namespace mane {
namespace {

// The iteration stops when it changes no entry by more than this; it converges quadratically, so
// the rotation is then exact to double rounding.
constexpr double kPolarTolerance = 1e-12;
constexpr int kPolarMaxIterations = 64;

}  // namespace

DualQuaternionJoint decomposeJoint(const glm::mat4& m) {
  DualQuaternionJoint joint;
  const glm::dmat3 linear{glm::mat3(m)};
  if (!(glm::determinant(linear) > 0.0)) return joint;
  glm::dmat3 rotation = linear;
  for (int i = 0; i < kPolarMaxIterations; ++i) {
    const glm::dmat3 next = 0.5 * (rotation + glm::transpose(glm::inverse(rotation)));
    double change = 0.0;
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) change = std::max(change, std::abs(next[c][r] - rotation[c][r]));
    }
    rotation = next;
    if (change <= kPolarTolerance) break;
  }
  const glm::dquat q = glm::normalize(glm::quat_cast(rotation));
  joint.real =
      glm::vec4(static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z), static_cast<float>(q.w));
  joint.stretch = glm::mat3(glm::transpose(rotation) * linear);
  // dual = ½·(t, 0)·real, a quaternion product with the translation as a pure quaternion.
  const glm::vec3 t(m[3]);
  const glm::vec3 r(joint.real);
  joint.dual = 0.5f * glm::vec4(joint.real.w * t + glm::cross(t, r), -glm::dot(t, r));
  joint.proper = true;
  return joint;
}

}  // namespace mane
