#include "scenes/joint_colliders.hpp"

#include <glm/matrix.hpp>

namespace mane::scenes {
namespace {

glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

}  // namespace

Result<JointColliders> JointColliders::create(const Colliders& colliders, physics::ColliderSet fixed,
                                              const SceneCharacter& character) {
  JointColliders result;
  result.fixed_ = std::move(fixed);
  for (const JointSphere& sphere : colliders.jointSpheres) {
    auto joint = character.findJoint(sphere.joint);
    if (!joint) return std::unexpected(joint.error());
    result.spheres_.push_back({*joint, sphere.sphere});
  }
  for (const JointCapsule& capsule : colliders.jointCapsules) {
    auto joint = character.findJoint(capsule.joint);
    if (!joint) return std::unexpected(joint.error());
    int toJoint = -1;
    if (!capsule.toJoint.empty()) {
      auto found = character.findJoint(capsule.toJoint);
      if (!found) return std::unexpected(found.error());
      toJoint = *found;
    }
    result.capsules_.push_back({*joint, toJoint, capsule.capsule});
  }
  return result;
}

physics::ColliderSet JointColliders::at(const SceneCharacter& character, const glm::mat4& body) const {
  physics::ColliderSet set = fixed_;
  const glm::mat4 worldToBody = glm::inverse(body);
  for (const Sphere& sphere : spheres_) {
    const glm::mat4 toBody = worldToBody * character.jointFrame(sphere.joint);
    set.spheres.push_back({transformPoint(toBody, sphere.local.centre), sphere.local.radius});
  }
  for (const Capsule& capsule : capsules_) {
    const glm::mat4 toBody = worldToBody * character.jointFrame(capsule.joint);
    physics::CapsuleCollider placed{.radius = capsule.local.radius};
    if (capsule.toJoint < 0) {
      placed.a = transformPoint(toBody, capsule.local.a);
      placed.b = transformPoint(toBody, capsule.local.b);
    } else {
      placed.a = glm::vec3(toBody[3]);
      placed.b = glm::vec3((worldToBody * character.jointFrame(capsule.toJoint))[3]);
    }
    set.capsules.push_back(placed);
  }
  return set;
}

}  // namespace mane::scenes
