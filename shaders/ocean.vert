#version 450
#extension GL_GOOGLE_include_directive : require
// The projected grid's vertices as shaders/ocean_grid.comp placed them (Johanson, "Real-time
// water rendering: introducing the projected grid concept", 2004; the grid of NVIDIA's "Clear
// Sailing"), and the horizon's colour along each one's ray, which the fog fades the water to.
#include "frame_uniforms.glsl"
#include "ocean_uniforms.glsl"
#include "ocean_grid.glsl"

layout(set = 1, binding = 2, std430) readonly buffer Grid { OceanGridVertex vertices[]; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec2 outRest;
layout(location = 2) out vec3 outNormal;
layout(location = 3) out float outJacobian;
layout(location = 4) out float outFootprint;
layout(location = 5) out vec3 outHorizon;

void main() {
  OceanGridVertex vertex = vertices[gl_VertexIndex];
  outWorld = vertex.world.xyz;
  outRest = vertex.rest.xy;
  outNormal = vertex.normal.xyz;
  outJacobian = vertex.world.w;
  outFootprint = vertex.normal.w;
  vec2 away = outWorld.xz - ocean.eye.xz;
  vec3 level = normalize(vec3(away.x, 0.02 * max(length(away), 1e-6), away.y));
  outHorizon = frame.lightCount.y != 0 ? textureLod(environmentSpecular, level, 1.0).rgb : ocean.fog.rgb;
  gl_Position = frame.viewProjection * vec4(outWorld, 1.0);
}
