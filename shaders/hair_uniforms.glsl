// Per-frame data of the hair ribbon pass; mirrors HairUniforms in render/passes/hair_pass.cpp (std140).
// Include after `#extension GL_GOOGLE_include_directive : require`.
layout(set = 0, binding = 0, std140) uniform HairUniforms {
  mat4 viewProjection;  // world (metres) → clip
  vec4 eye;             // w = 1: eye position (metres); w = 0: unit direction towards the eye
  vec4 groom;           // x: root width (m), y: tip width scale, z: opacity, w: min width (px)
  vec4 viewport;        // xy: extent in pixels
  uvec4 counts;         // y: vertices per strand
} hair;

// Unit vector from `position` (world, metres) towards the eye.
vec3 hairToEye(vec3 position) {
  return hair.eye.w != 0.0 ? normalize(hair.eye.xyz - position) : hair.eye.xyz;
}
