#version 450
#extension GL_GOOGLE_include_directive : require
// The foam map, over the sea at rest (the water a texel holds only circles about it, so foam
// stays with its water as the waves pass): each frame the foam fades by 2^(−Δt/T½), and breaking
// crests (J under the threshold, over 0.2 of J) and the frame's sources (a ship's wake, each
// falling off as exp(−d²/r²)) add to it, up to 1.
layout(local_size_x = 8, local_size_y = 8) in;
#define OCEAN_SET 0
#include "ocean_uniforms.glsl"
#include "ocean_waves.glsl"

layout(set = 0, binding = 1, r32f) uniform image2D foamMap;

// Each invocation updates a run of kJacobianRun texels along x.
void main() {
  ivec2 first = ivec2(gl_GlobalInvocationID.x * kJacobianRun, gl_GlobalInvocationID.y);
  int side = int(ocean.foamMap.w);
  if (first.x >= side || first.y >= side) return;
  float metresPerTexel = 1.0 / (ocean.foamMap.z * float(side));
  vec2 firstRest = ocean.foamMap.xy + (vec2(first) + 0.5) * metresPerTexel;
  float jacobians[kJacobianRun];
  if (ocean.foamStep.y > 0.0) oceanJacobianRun(firstRest, metresPerTexel, metresPerTexel, jacobians);
  int sources = int(ocean.foamStep.z);
  for (int j = 0; j < kJacobianRun; ++j) {
    ivec2 texel = first + ivec2(j, 0);
    if (texel.x >= side) break;
    vec2 rest = firstRest + vec2(float(j) * metresPerTexel, 0.0);
    float breaking = ocean.foamStep.y > 0.0 ? clamp((ocean.foam.a - jacobians[j]) / 0.2, 0.0, 1.0) : 0.0;
    float laid = 0.0;
    for (int i = 0; i < sources; ++i) {
      vec4 source = ocean.foamSources[i];
      vec2 d = rest - source.xy;
      float spread = dot(d, d) * source.z;
      // Beyond 3 r it adds less than 2e-4 of its centre's.
      if (spread < 9.0) laid += source.w * exp(-spread);
    }
    float foam = imageLoad(foamMap, texel).r * ocean.foamStep.x + breaking * ocean.foamStep.y + laid;
    imageStore(foamMap, texel, vec4(min(foam, 1.0)));
  }
}
