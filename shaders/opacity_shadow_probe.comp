#version 450
#extension GL_GOOGLE_include_directive : require
// Runs shaders/opacity_shadow.glsl at a list of world points (tests and tools): for each, the
// opacity and the transmittance towards the light.
#include "opacity_shadow.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform sampler2DArray opacity;
layout(set = 0, binding = 1) uniform sampler2D firstDepth;
layout(set = 0, binding = 2, std430) readonly buffer Points {
  vec4 points[];  // xyz metres
};
layout(set = 0, binding = 3, std430) writeonly buffer Results {
  vec2 results[];  // x opacity, y transmittance
};
layout(push_constant) uniform Probe {
  OpacityShadow osm;
  uint count;
} probe;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= probe.count) return;
  vec3 p = points[i].xyz;
  results[i] = vec2(opacityShadowOpacity(opacity, firstDepth, probe.osm, p),
                    opacityShadowTransmittance(opacity, firstDepth, probe.osm, p));
}
