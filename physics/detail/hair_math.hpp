#pragma once
// Small exact helpers shared by the hair system's setup (hair.cpp) and its step
// (hair_step.cpp), the cloth's wind, the floating body and the debris: points, quaternions as (x, y, z, w),
// rotations. Only + − × ÷ and sqrt, no
// libm trigonometry, so they give the same bits everywhere (docs/design.md#determinism).

#include <cmath>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace mane::physics::detail {

inline bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline bool isFinite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

inline glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

// Quaternions as (x, y, z, w). Only + − × ÷ and sqrt: no libm trigonometry in the step.
inline float dot4(const glm::vec4& a, const glm::vec4& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}

inline glm::vec4 normalized(const glm::vec4& q) {
  const float n = std::sqrt(dot4(q, q));
  return n > 0.0f ? q / n : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

// Rotation of a rigid transform as a unit quaternion (Shoemake 1985, "Animating Rotation with
// Quaternion Curves", the largest-diagonal branch for accuracy). Columns are normalised first so
// that a uniform scale does not leak in.
inline glm::vec4 rotationOf(const glm::mat4& transform) {
  glm::vec3 c[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = glm::vec3(transform[i]);
    const float n = std::sqrt(c[i].x * c[i].x + c[i].y * c[i].y + c[i].z * c[i].z);
    if (n > 0.0f) c[i] /= n;
  }
  // mRC: row R, column C.
  const float m00 = c[0].x, m10 = c[0].y, m20 = c[0].z, m01 = c[1].x, m11 = c[1].y, m21 = c[1].z;
  const float m02 = c[2].x, m12 = c[2].y, m22 = c[2].z;
  const float trace = m00 + m11 + m22;
  glm::vec4 q;
  if (trace > 0.0f) {
    const float s = std::sqrt(trace + 1.0f) * 2.0f;
    q = {(m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25f * s};
  } else if (m00 > m11 && m00 > m22) {
    const float s = std::sqrt(1.0f + m00 - m11 - m22) * 2.0f;
    q = {0.25f * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s};
  } else if (m11 > m22) {
    const float s = std::sqrt(1.0f + m11 - m00 - m22) * 2.0f;
    q = {(m01 + m10) / s, 0.25f * s, (m12 + m21) / s, (m02 - m20) / s};
  } else {
    const float s = std::sqrt(1.0f + m22 - m00 - m11) * 2.0f;
    q = {(m02 + m20) / s, (m12 + m21) / s, 0.25f * s, (m10 - m01) / s};
  }
  return normalized(q);
}

// Hamilton product a ⊗ b (apply b, then a).
inline glm::vec4 multiply(const glm::vec4& a, const glm::vec4& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

inline glm::vec3 cross(const glm::vec3& a, const glm::vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// v rotated by unit quaternion q: v + w·t + u × t with t = 2·(u × v).
inline glm::vec3 rotate(const glm::vec4& q, const glm::vec3& v) {
  const glm::vec3 u(q.x, q.y, q.z);
  const glm::vec3 t = cross(u, v) * 2.0f;
  return v + t * q.w + cross(u, t);
}

// The shortest-arc rotation taking direction a onto direction b, as a unit quaternion
// (|a||b| + a·b, a × b) normalised; identity when a and b are opposite or zero (no unique arc).
inline glm::vec4 shortestArc(const glm::vec3& a, const glm::vec3& b) {
  const float aa = a.x * a.x + a.y * a.y + a.z * a.z, bb = b.x * b.x + b.y * b.y + b.z * b.z;
  const glm::vec3 axis = cross(a, b);
  const float w = std::sqrt(aa * bb) + (a.x * b.x + a.y * b.y + a.z * b.z);
  const float n2 = w * w + axis.x * axis.x + axis.y * axis.y + axis.z * axis.z;
  if (!(n2 > 1e-12f * aa * bb)) return {0.0f, 0.0f, 0.0f, 1.0f};
  const float inverse = 1.0f / std::sqrt(n2);
  return {axis.x * inverse, axis.y * inverse, axis.z * inverse, w * inverse};
}

}  // namespace mane::physics::detail
