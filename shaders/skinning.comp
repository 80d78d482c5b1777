#version 460
// A skinned, morphing mesh deformed per vertex: the GPU twin of physics::SkinnedMesh::deform
// (physics/skinning.hpp), same steps in the same order, in float. The joints' dual-quaternion
// parts come precomputed from the host (render/passes/skinning_pass.hpp).
//
// Everything that decides a branch or a trip count is in storage buffers or specialisation
// constants, never in a uniform block, so lavapipe does not recompile the shader when it binds.
//
// Buffers (std430):
//   0 rest vertices   position (w unused), normal (w 0), tangent (w handedness)
//   1 influences      kInfluenceGroups per vertex: 4 joint indices and their weights each
//   2 morph deltas    target-major, one per target and vertex: position, normal, tangent deltas
//   3 frame           x: vertex count, y: morph target count; then one weight per target
//   4 joints          per joint: its matrix and, for DQS, rotation, dual part and stretch
//   5–7 outputs       positions (w 1), normals (w 0), tangents (w handedness), one vec4 per vertex
//   8–10 vertex targets  other passes' interleaved vertex buffers, as floats: the deformed position
//                     and normal written into each at its stride and offsets, so those passes draw
//                     the deformed mesh with their own vertex layouts (kVertexTargets of them)

layout(local_size_x = 64) in;

layout(constant_id = 0) const uint kInfluenceGroups = 1;  // influences per vertex / 4
layout(constant_id = 1) const bool kDualQuaternion = false;
layout(constant_id = 2) const uint kVertexTargets = 0;  // 0 to 3
// Per target: floats per vertex, and from a vertex's start to its position's and normal's x.
layout(constant_id = 3) const uint kStride0 = 3;
layout(constant_id = 4) const uint kPosition0 = 0;
layout(constant_id = 5) const uint kNormal0 = 0;
layout(constant_id = 6) const uint kStride1 = 3;
layout(constant_id = 7) const uint kPosition1 = 0;
layout(constant_id = 8) const uint kNormal1 = 0;
layout(constant_id = 9) const uint kStride2 = 3;
layout(constant_id = 10) const uint kPosition2 = 0;
layout(constant_id = 11) const uint kNormal2 = 0;

struct RestVertex {
  vec4 position;
  vec4 normal;
  vec4 tangent;
};
struct Influence {
  uvec4 joints;
  vec4 weights;
};
struct MorphDelta {
  vec4 position;
  vec4 normal;
  vec4 tangent;
};
struct Joint {
  mat4 matrix;
  vec4 real;        // rotation quaternion (x, y, z, w)
  vec4 dual;        // ½·t·real
  vec4 stretch[3];  // columns of the symmetric stretch S in matrix = [R·S | t]
};

layout(std430, set = 0, binding = 0) readonly buffer Rest { RestVertex rest[]; };
layout(std430, set = 0, binding = 1) readonly buffer Influences { Influence influences[]; };
layout(std430, set = 0, binding = 2) readonly buffer Morphs { MorphDelta morphs[]; };
layout(std430, set = 0, binding = 3) readonly buffer Frame {
  uvec4 counts;
  float morphWeights[];
};
layout(std430, set = 0, binding = 4) readonly buffer Joints { Joint joints[]; };
layout(std430, set = 0, binding = 5) writeonly buffer Positions { vec4 positions[]; };
layout(std430, set = 0, binding = 6) writeonly buffer Normals { vec4 normals[]; };
layout(std430, set = 0, binding = 7) writeonly buffer Tangents { vec4 tangents[]; };
layout(std430, set = 0, binding = 8) writeonly buffer Target0 { float target0[]; };
layout(std430, set = 0, binding = 9) writeonly buffer Target1 { float target1[]; };
layout(std430, set = 0, binding = 10) writeonly buffer Target2 { float target2[]; };

#define WRITE_TARGET(target, stride, positionOffset, normalOffset)   \
  {                                                                  \
    const uint base = v * stride;                                    \
    target[base + positionOffset] = position.x;                      \
    target[base + positionOffset + 1u] = position.y;                \
    target[base + positionOffset + 2u] = position.z;                \
    target[base + normalOffset] = normal.x;                          \
    target[base + normalOffset + 1u] = normal.y;                    \
    target[base + normalOffset + 2u] = normal.z;                    \
  }

// The deformed vertex v, written to the outputs and to every vertex target.
void store(uint v, vec3 position, vec3 normal, vec4 tangent) {
  positions[v] = vec4(position, 1.0);
  normals[v] = vec4(normal, 0.0);
  tangents[v] = tangent;
  if (kVertexTargets > 0u) WRITE_TARGET(target0, kStride0, kPosition0, kNormal0)
  if (kVertexTargets > 1u) WRITE_TARGET(target1, kStride1, kPosition1, kNormal1)
  if (kVertexTargets > 2u) WRITE_TARGET(target2, kStride2, kPosition2, kNormal2)
}

// Columns c1×c2, c2×c0, c0×c1: det(L)·L⁻ᵀ, which carries normals without a division.
mat3 cofactor(mat3 l) {
  return mat3(cross(l[1], l[2]), cross(l[2], l[0]), cross(l[0], l[1]));
}

vec3 normalisedOr(vec3 v, vec3 fallback) {
  const float len = length(v);
  return len > 0.0 && !isinf(len) ? v / len : fallback;
}

// v rotated by the unit quaternion q: v + 2·r × (r × v + w·v).
vec3 rotate(vec4 q, vec3 v) {
  return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v);
}

void main() {
  const uint v = gl_GlobalInvocationID.x;
  const uint vertexCount = counts.x;
  if (v >= vertexCount) return;

  // 1. Morph targets, in target order.
  const RestVertex r = rest[v];
  vec3 position = r.position.xyz;
  vec3 normal = r.normal.xyz;
  vec4 tangent = r.tangent;
  for (uint k = 0u; k < counts.y; ++k) {
    const float w = morphWeights[k];
    if (w == 0.0) continue;
    const MorphDelta d = morphs[k * vertexCount + v];
    position += w * d.position.xyz;
    normal += w * d.normal.xyz;
    tangent.xyz += w * d.tangent.xyz;
  }
  const vec3 restNormal = normalisedOr(normal, r.normal.xyz);
  const vec3 restTangent = normalisedOr(tangent.xyz, r.tangent.xyz);

  // 2. Skinning.
  if (!kDualQuaternion) {
    mat4 blended = mat4(0.0);
    for (uint g = 0u; g < kInfluenceGroups; ++g) {
      const Influence influence = influences[v * kInfluenceGroups + g];
      for (uint i = 0u; i < 4u; ++i) blended += influence.weights[i] * joints[influence.joints[i]].matrix;
    }
    const mat3 linear = mat3(blended);
    const float mirror = determinant(linear) < 0.0 ? -1.0 : 1.0;
    store(v, (blended * vec4(position, 1.0)).xyz, normalisedOr(mirror * (cofactor(linear) * restNormal), restNormal),
          vec4(normalisedOr(linear * restTangent, restTangent), tangent.w * mirror));
    return;
  }

  // DQS: antipodal quaternions are one rotation; align every influence with the first weighted
  // one so the blend takes the short way round.
  vec4 pivot = vec4(0.0);
  bool pivotFound = false;
  vec4 real = vec4(0.0);
  vec4 dual = vec4(0.0);
  mat3 stretch = mat3(0.0);
  for (uint g = 0u; g < kInfluenceGroups; ++g) {
    const Influence influence = influences[v * kInfluenceGroups + g];
    for (uint i = 0u; i < 4u; ++i) {
      const float w = influence.weights[i];
      if (w == 0.0) continue;
      const Joint joint = joints[influence.joints[i]];
      if (!pivotFound) {
        pivot = joint.real;
        pivotFound = true;
      }
      const float signedWeight = dot(joint.real, pivot) < 0.0 ? -w : w;
      real += signedWeight * joint.real;
      dual += signedWeight * joint.dual;
      stretch += w * mat3(joint.stretch[0].xyz, joint.stretch[1].xyz, joint.stretch[2].xyz);
    }
  }
  const float len = length(real);
  real /= len;
  dual /= len;
  // The blended motion's translation: the vector part of 2·dual·conj(real).
  const vec3 translation = 2.0 * (real.w * dual.xyz - dual.w * real.xyz + cross(real.xyz, dual.xyz));
  store(v, rotate(real, stretch * position) + translation,
        normalisedOr(rotate(real, cofactor(stretch) * restNormal), restNormal),
        vec4(normalisedOr(rotate(real, stretch * restTangent), restTangent), tangent.w));
}
