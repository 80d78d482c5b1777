#pragma once
// A groom's or cloth's colliders when some of them are carried by a character's joints
// (scene.hpp: JointSphere, JointCapsule): the shapes that stay in the body frame, and per frame
// the joint-borne ones re-expressed in that frame, so the solver, which keeps its colliders in
// the frame of the body it follows, sees each shape where its own joint has moved it.

#include <vector>

#include <glm/mat4x4.hpp>

#include "common/error.hpp"
#include "physics/colliders.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_character.hpp"

namespace mane::scenes {

class JointColliders {
public:
  /// `fixed` holds the shapes that follow the body itself (and the field, friction, thickness);
  /// the joint-bound shapes of `colliders` are resolved by name in `character`. The error names
  /// the joint and lists the character's nodes.
  [[nodiscard]] static Result<JointColliders> create(const Colliders& colliders, physics::ColliderSet fixed,
                                                     const SceneCharacter& character);

  /// The whole set in the body frame `body` (rigid, body → world) at the character's current pose.
  [[nodiscard]] physics::ColliderSet at(const SceneCharacter& character, const glm::mat4& body) const;

private:
  struct Sphere {
    int joint = -1;
    physics::SphereCollider local;
  };
  struct Capsule {
    int joint = -1;
    int toJoint = -1;  ///< -1: `local` holds the axis in the joint's frame
    physics::CapsuleCollider local;
  };
  physics::ColliderSet fixed_;
  std::vector<Sphere> spheres_;
  std::vector<Capsule> capsules_;
};

}  // namespace mane::scenes
