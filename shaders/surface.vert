#version 450
#extension GL_GOOGLE_include_directive : require
// Meshes in world space for the Lambert surface pass.
#include "frame_uniforms.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(push_constant) uniform Draw {
  mat4 model;
  vec4 baseColor;   // rgb, a unused
  ivec4 flags;      // x: has normal map
} draw;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out vec2 outUv;

void main() {
  vec4 world = draw.model * vec4(inPosition, 1.0);
  outWorldPosition = world.xyz;
  // Inverse-transpose for non-uniform scale.
  outWorldNormal = transpose(inverse(mat3(draw.model))) * inNormal;
  // glTF and OBJ put v = 0 at the top of the image: no flip needed with Vulkan's texture origin.
  outUv = inUv;
  gl_Position = frame.viewProjection * world;
}
