#version 450
// God rays, step 1 (render/passes/post_pass.hpp): the downsampled copy's bright texels, rgb ·
// max(L − threshold, 0)/L; everything darker is an occluder, 0 (godRayBright in
// render/passes/post_reference.hpp).

#extension GL_GOOGLE_include_directive : require
#include "post_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D quarter;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D bright;

layout(push_constant) uniform Bright {
  float threshold;  // PostSettings::godRayThreshold, luminance
} settings;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(bright)))) return;
  vec3 rgb = imageLoad(quarter, texel).rgb;
  float l = postLuminance(rgb);
  float share = l > 0.0 ? max(l - settings.threshold, 0.0) / l : 0.0;
  imageStore(bright, texel, vec4(rgb * share, 1.0));
}
