#version 450
// Deep opacity maps, pass 2 (Yuksel & Keyser 2008 §3.2): layer k (0..2) sums the hair with depth
// z0 ≤ z ≤ z0 + (k + 1)·Δ, where z0 is the texel's nearest hair depth from pass 1; layer 3 sums
// all of it (the last layer reaches to infinity). The fragment adds its weight to layers
// k ≥ ceil((z − z0)/Δ) − 1, clamped to 0..3.
#extension GL_GOOGLE_include_directive : require
#include "opacity_shadow_build.glsl"

layout(set = 0, binding = 1) uniform sampler2D firstDepth;
layout(location = 0) flat in float weight;
layout(location = 0) out vec4 layers;

void main() {
  float z0 = texelFetch(firstDepth, ivec2(gl_FragCoord.xy), 0).r;
  float first = clamp(ceil((gl_FragCoord.z - z0) / build.weights.w) - 1.0, 0.0, 3.0);
  layers = weight * step(vec4(first), vec4(0.0, 1.0, 2.0, 3.0));
}
