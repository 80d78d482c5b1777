#version 450
#extension GL_GOOGLE_include_directive : require
// Meshes in world space for the surface pass (Lambert or skin).
#include "frame_uniforms.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in float inCurvature;  // 1/r per mesh unit

layout(push_constant) uniform Draw {
  mat4 model;
} draw;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out float outCurvature;  // 1/r in 1/mm
layout(location = 4) out vec3 outObjectPosition;  // mesh units: where the thickness table is indexed
layout(location = 5) flat out vec4 outObjectTowardLight;  // xyz: light 0's direction, mesh units per metre; w: metres per unit

void main() {
  vec4 world = draw.model * vec4(inPosition, 1.0);
  outWorldPosition = world.xyz;
  // Inverse-transpose for non-uniform scale.
  outWorldNormal = transpose(inverse(mat3(draw.model))) * inNormal;
  // glTF and OBJ put v = 0 at the top of the image: no flip needed with Vulkan's texture origin.
  outUv = inUv;
  // Per mesh unit → per metre (the model's uniform scale: its first column's length) → per mm.
  float metresPerUnit = length(draw.model[0].xyz);
  outCurvature = inCurvature / metresPerUnit * 1e-3;
  outObjectPosition = inPosition;
  // A world direction into mesh units: the inverse of the model's linear part (uniform scale).
  outObjectTowardLight = vec4(inverse(mat3(draw.model)) * frame.lightDirection[0].xyz, metresPerUnit);
  gl_Position = frame.viewProjection * world;
}
