#pragma once
// A joint matrix in the parts dual-quaternion skinning blends (Kavan et al. 2008, "Geometric
// Skinning with Approximate Dual Quaternion Blending"): M = [R·S | t] with R a rotation, S
// symmetric (scale and shear, applied before the rotation) and t the translation. Physics' CPU
// skinning and render's compute skinning both take their per-joint values from here, so the two
// paths blend the same numbers.

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace mane {

struct DualQuaternionJoint {
  glm::vec4 real{0.0f, 0.0f, 0.0f, 1.0f};  ///< R as a unit quaternion (x, y, z, w)
  glm::vec4 dual{0.0f};                    ///< ½·(t, 0)·real: the translation
  glm::mat3 stretch{1.0f};                 ///< S
  bool proper = false;  ///< false when M mirrors or flattens space: no rotation expresses it
};

/// The parts of `m`. R comes from the polar decomposition of M's linear part by Higham's
/// iteration X ← (X + X⁻ᵀ)/2 (Higham 1986, "Computing the Polar Decomposition—with
/// Applications"), in double. Where det ≤ 0 the result is the identity with `proper` false.
[[nodiscard]] DualQuaternionJoint decomposeJoint(const glm::mat4& m);

}  // namespace mane
