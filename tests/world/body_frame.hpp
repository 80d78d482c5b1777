#pragma once
// A simulated point taken into the body frame it collides in (scenes/README.md, "Colliders"),
// for tests that measure hair or cloth against a body's shapes.

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include "scenes/scene.hpp"

namespace mane::scenes::testing {

/// World → body frame of `mesh` at `time`, from the placement the renderer draws the mesh with
/// (`animatedMatrix`) and the README's definition: that placement without the mesh's scale.
inline glm::mat4 worldToBody(const Scene& scene, const MeshInstance& mesh, double time) {
  const glm::mat4 model = animatedMatrix(scene, mesh, static_cast<float>(time));
  return glm::inverse(model * glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / mesh.transform.scale)));
}

inline glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

}  // namespace mane::scenes::testing
