#version 450
// HDR scene colour → display (render/passes/output_pass.hpp): the post chain's overlay applied
// (its gain, glow and god rays, folded on the downsampled copy's grid by
// shaders/post_overlay.comp), or without the chain the exposure, then the tone map; the sRGB
// attachment encodes on write. Each combination is its own pipeline (specialisation constants):
// lavapipe would run both sides of a branch on a uniform. With the defaults (linear, no chain)
// this is the plain exposure scale, clamped.

#extension GL_GOOGLE_include_directive : require
#include "post_common.glsl"

layout(constant_id = 0) const int kToneMapping = 0;  // ToneMapping: 0 linear, 1 Reinhard
// PostPass::OverlayUse: 0 none (the exposure), 1 its scale alone (auto gain only), 2 filtered.
layout(constant_id = 1) const int kOverlay = 0;

layout(set = 0, binding = 0) uniform sampler2D hdrColor;
layout(set = 0, binding = 1) uniform sampler2D overlay;  // rgb added, a the frame's scale

layout(push_constant) uniform Output {
  vec2 overlayUvScale;  // frame uv → overlay uv: size / (4 · downsampled size)
  float exposure;
} settings;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  // The frame is the output's size: its texel at this pixel, without filtering.
  vec3 color = texelFetch(hdrColor, ivec2(gl_FragCoord.xy), 0).rgb;
  if (kOverlay == 2) {
    vec4 added = texture(overlay, inUv * settings.overlayUvScale);
    color = color * added.a + added.rgb;
  } else {
    // Every texel holds the same scale: one texel, unfiltered.
    color *= kOverlay == 1 ? texelFetch(overlay, ivec2(0), 0).a : settings.exposure;
  }
  // Reinhard et al. 2002, eq. 3 on the luminance, the colour scaled by L_d / L: c / (1 + L).
  if (kToneMapping == 1) color /= 1.0 + postLuminance(color);
  outColor = vec4(clamp(color, 0.0, 1.0), 1.0);
}
