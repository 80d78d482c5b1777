#version 450
#extension GL_GOOGLE_include_directive : require
// A mesh drawn at its texture coordinates (render/passes/skin_diffusion_pass.hpp): every texel of the
// irradiance map receives the surface point that maps to it.
#include "skin_irradiance.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out vec2 outUv;

void main() {
  vec4 world = irradiance.model * vec4(inPosition, 1.0);
  outWorldPosition = world.xyz;
  outWorldNormal = mat3(irradiance.normalMatrix) * inNormal;
  outUv = inUv;
  // uv [0, 1]² → clip [−1, 1]²: texel (i, j) covers uv [i, i + 1]/size × [j, j + 1]/size. Vulkan's
  // framebuffer y points down as the textures' v does, so the final pass samples the map at the
  // fragment's uv as is. UVs outside [0, 1] are clipped (no tiling).
  gl_Position = vec4(inUv * 2.0 - 1.0, 0.0, 1.0);
}
