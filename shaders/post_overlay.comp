#version 450
// Post chain, the hand-off (render/passes/post_pass.hpp, step 5): what the output pass does with
// the chain's results, folded on the downsampled copy's grid so that the full-size output pass
// samples one image there instead of two and reads no buffer: rgb = g·(s·glow + r·rays) and
// a = g·(1 − s), for the gain g (the auto gain or the exposure), the glow's share s and the god
// rays' strength r. The output pass multiplies the frame by a and adds rgb: the mix, the add and
// the gain it applied before, reordered (bilinear filtering is linear).

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const bool kAutoGain = false;
layout(constant_id = 1) const bool kGlow = false;
layout(constant_id = 2) const bool kGodRays = false;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D glow;
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D godRays;
layout(set = 0, binding = 2, std430) readonly buffer Exposure {
  float adaptedLogLuminance;
  float frameLogLuminance;
  float gain;
  uint frames;
} state;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D overlay;

layout(push_constant) uniform Overlay {
  float exposure;      // the gain without auto gain
  float glowStrength;  // the glow's share, 0..1
  float godRays;       // PostSettings::godRays: the rays' strength
} settings;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(overlay)))) return;
  float gain = kAutoGain ? state.gain : settings.exposure;
  vec3 added = vec3(0.0);
  float kept = 1.0;
  if (kGlow) {
    added = settings.glowStrength * imageLoad(glow, texel).rgb;
    kept = 1.0 - settings.glowStrength;
  }
  if (kGodRays) added += settings.godRays * imageLoad(godRays, texel).rgb;
  imageStore(overlay, texel, vec4(gain * added, gain * kept));
}
