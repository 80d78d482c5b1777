#version 450
#extension GL_GOOGLE_include_directive : require
// The waves at given rest points, for the comparison with the CPU's sum
// (render/passes/ocean_pass.hpp, OceanPass::probe).
layout(local_size_x = 64) in;
#define OCEAN_SET 0
#include "ocean_uniforms.glsl"
#include "ocean_waves.glsl"

layout(set = 0, binding = 1, std430) readonly buffer Points { vec2 rests[]; };
// Per point: displacement and J, then the normal.
layout(set = 0, binding = 2, std430) writeonly buffer Samples { vec4 samples[]; };

layout(push_constant) uniform Probe { uint count; } probe;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= probe.count) return;
  OceanPoint point = oceanWaves(rests[i], 0.0);
  samples[2 * i] = vec4(point.displacement, point.jacobian);
  samples[2 * i + 1] = vec4(point.normal, 0.0);
}
