#version 450
#extension GL_GOOGLE_include_directive : require
// A mesh drawn at its texture coordinates (render/passes/skin_diffusion_pass.hpp): every texel of the
// irradiance map receives the surface point that maps to it. The draw list
// (render/passes/skin_uv_seams.hpp) names mesh vertices and where they land: the mesh's own
// triangles at their uvs, and its seams' skirts unfolded past the islands' borders.
#include "skin_irradiance.glsl"

// SkinDiffusionVertex: position, normal, uv as eight floats (the skinning pass rewrites the
// first six of a skinned mesh every frame).
layout(set = 1, binding = 0, std430) readonly buffer MeshVertices {
  float meshVertices[];
};

layout(location = 0) in uint inSource;  // the mesh vertex
layout(location = 1) in float inDepth;  // 0 on the mesh, the distance to its seam on a skirt
layout(location = 2) in vec2 inDrawUv;  // where it lands in the map

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out vec2 outUv;  // the vertex's own uv: where the normal map is read

void main() {
  const uint base = inSource * 8u;
  vec3 position = vec3(meshVertices[base], meshVertices[base + 1u], meshVertices[base + 2u]);
  vec3 normal = vec3(meshVertices[base + 3u], meshVertices[base + 4u], meshVertices[base + 5u]);
  vec4 world = irradiance.model * vec4(position, 1.0);
  outWorldPosition = world.xyz;
  outWorldNormal = mat3(irradiance.normalMatrix) * normal;
  outUv = vec2(meshVertices[base + 6u], meshVertices[base + 7u]);
  // uv [0, 1]² → clip [−1, 1]²: texel (i, j) covers uv [i, i + 1]/size × [j, j + 1]/size. Vulkan's
  // framebuffer y points down as the textures' v does, so the final pass samples the map at the
  // fragment's uv as is. UVs outside [0, 1] are clipped (no tiling).
  gl_Position = vec4(inDrawUv * 2.0 - 1.0, inDepth, 1.0);
}
