#version 450
// HDR scene colour → display (render/passes/output_pass.hpp): the glow mixed in, the god rays
// added (both from the downsampled copy's grid), a gain (the
// exposure, or the automatic gain the post chain left in its exposure state), then the tone map;
// the sRGB attachment encodes on write. Each combination is its own pipeline (specialisation
// constants): lavapipe would run both sides of a branch on a uniform. With the defaults (linear,
// no auto gain, no glow, no god rays) this is the plain exposure scale, clamped.

#extension GL_GOOGLE_include_directive : require
#include "post_common.glsl"

layout(constant_id = 0) const int kToneMapping = 0;  // ToneMapping: 0 linear, 1 Reinhard
layout(constant_id = 1) const bool kAutoGain = false;
layout(constant_id = 2) const bool kGlow = false;
layout(constant_id = 3) const bool kGodRays = false;

layout(set = 0, binding = 0) uniform sampler2D hdrColor;
layout(set = 0, binding = 1) uniform sampler2D glow;  // the blurred downsampled copy
layout(set = 0, binding = 2, std430) readonly buffer Exposure {
  float adaptedLogLuminance;
  float frameLogLuminance;
  float gain;
  uint frames;
} state;
layout(set = 0, binding = 3) uniform sampler2D godRays;  // the rays, on the glow's grid

layout(push_constant) uniform Output {
  float exposure;
  float glowStrength;  // the blurred image's share, 0..1
  vec2 glowUvScale;    // frame uv → glow uv: size / (4 · downsampled size)
  float godRays;       // PostSettings::godRays: the rays' strength
} settings;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  // The frame is the output's size: its texel at this pixel, without filtering.
  vec3 color = texelFetch(hdrColor, ivec2(gl_FragCoord.xy), 0).rgb;
  if (kGlow) color = mix(color, texture(glow, inUv * settings.glowUvScale).rgb, settings.glowStrength);
  if (kGodRays) color += settings.godRays * texture(godRays, inUv * settings.glowUvScale).rgb;
  color *= kAutoGain ? state.gain : settings.exposure;
  // Reinhard et al. 2002, eq. 3 on the luminance, the colour scaled by L_d / L: c / (1 + L).
  if (kToneMapping == 1) color /= 1.0 + postLuminance(color);
  outColor = vec4(clamp(color, 0.0, 1.0), 1.0);
}
