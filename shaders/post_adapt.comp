#version 450
// Automatic gain control (render/passes/post_pass.hpp): the log-average luminance of the tiny
// image, L̄ = exp(mean(log(δ + L))) (Reinhard et al. 2002, eq. 1), by one workgroup: each
// invocation sums a fixed stride of texels in order, then a tree in shared memory adds the 256
// partial sums in a fixed order, so the result is the same run after run. The adapted log
// luminance then moves `rate` = 1 − exp(−Δt/τ) of the way towards this frame's (the first frame,
// or a rate of 1, snaps), and the gain that maps it to the key value, exposure · a / L̄_adapted,
// is left in the exposure state for the output pass.

#extension GL_GOOGLE_include_directive : require
#include "post_common.glsl"

layout(local_size_x = 256) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D tiny;
// Mirrors PostExposure in render/passes/post_pass.hpp.
layout(set = 0, binding = 1, std430) buffer Exposure {
  float adaptedLogLuminance;
  float frameLogLuminance;
  float gain;
  uint frames;
} state;

layout(push_constant) uniform Adapt {
  float rate;      // 1 − exp(−Δt/τ); 1 snaps
  float key;       // a
  float exposure;  // FrameInput::exposure: compensation on top of the key
} adapt;

shared float partialSums[256];

void main() {
  ivec2 size = imageSize(tiny);
  int count = size.x * size.y;
  uint invocation = gl_LocalInvocationIndex;
  float sum = 0.0;
  for (int t = int(invocation); t < count; t += 256) {
    vec3 rgb = imageLoad(tiny, ivec2(t % size.x, t / size.x)).rgb;
    sum += log(kPostLogDelta + postLuminance(rgb));
  }
  partialSums[invocation] = sum;
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    if (invocation < stride) partialSums[invocation] += partialSums[invocation + stride];
    barrier();
  }
  if (invocation != 0u) return;
  float frameLog = partialSums[0] / float(count);
  float previous = state.adaptedLogLuminance;
  float adapted = state.frames == 0u ? frameLog : previous + adapt.rate * (frameLog - previous);
  state.adaptedLogLuminance = adapted;
  state.frameLogLuminance = frameLog;
  state.gain = adapt.exposure * adapt.key / exp(adapted);
  state.frames = min(state.frames, 0x7ffffffeu) + 1u;
}
