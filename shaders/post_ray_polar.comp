#version 450
// God rays, step 2 (render/passes/post_pass.hpp): the bright image in polar coordinates around
// the light, texel (i, j) at the angle θ = 2π(i + ½)/A and the radius r = j copy texels, over the
// A angles and R radii the light uses (the rest of the image is left as it is): a
// bilinear sample at centre + r(cos θ, sin θ), clamped to the edge (toPolar in
// render/passes/post_reference.hpp). Manual bilinear on storage images, as the CPU does it.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D polar;

layout(push_constant) uniform Centre {
  vec2 centre;   // the light, in copy texel coordinates (texel x covers [x, x + 1])
  ivec2 extent;  // the angles and radii this light uses (godRayPolarExtent), within the image
} settings;

vec4 sampleClamped(vec2 c) {
  ivec2 last = imageSize(source) - 1;
  vec2 f = c - 0.5;
  vec2 base = floor(f);
  vec2 t = f - base;
  ivec2 i0 = ivec2(base);
  vec4 a = imageLoad(source, clamp(i0, ivec2(0), last));
  vec4 b = imageLoad(source, clamp(i0 + ivec2(1, 0), ivec2(0), last));
  vec4 c0 = imageLoad(source, clamp(i0 + ivec2(0, 1), ivec2(0), last));
  vec4 d = imageLoad(source, clamp(i0 + ivec2(1, 1), ivec2(0), last));
  return mix(mix(a, b, t.x), mix(c0, d, t.x), t.y);
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = settings.extent;
  if (any(greaterThanEqual(texel, size))) return;
  float theta = 6.283185307 * (float(texel.x) + 0.5) / float(size.x);
  vec2 at = settings.centre + float(texel.y) * vec2(cos(theta), sin(theta));
  imageStore(polar, texel, sampleClamped(at));
}
