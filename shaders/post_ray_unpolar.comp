#version 450
// God rays, step 4 (render/passes/post_pass.hpp): the (blurred) polar image back on the
// downsampled copy's grid: each texel centre's angle and radius around the light, sampled
// bilinearly, wrapping in angle and clamped in radius (fromPolar in
// render/passes/post_reference.hpp). The output pass adds the result.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D polar;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D rays;

layout(push_constant) uniform Centre {
  vec2 centre;   // the light, in copy texel coordinates
  ivec2 extent;  // the angles and radii of the polar image it uses (godRayPolarExtent)
} settings;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(rays)))) return;
  ivec2 size = settings.extent;
  vec2 d = vec2(texel) + 0.5 - settings.centre;
  float theta = atan(d.y, d.x);
  theta += theta < 0.0 ? 6.283185307 : 0.0;
  vec2 f = vec2(theta * float(size.x) / 6.283185307, length(d) + 0.5) - 0.5;
  vec2 base = floor(f);
  vec2 t = f - base;
  ivec2 i0 = ivec2(base);
  // Angles wrap (x mod A, also for −1), radii clamp.
  int x0 = (i0.x % size.x + size.x) % size.x;
  int x1 = (x0 + 1) % size.x;
  int y0 = clamp(i0.y, 0, size.y - 1);
  int y1 = clamp(i0.y + 1, 0, size.y - 1);
  vec4 top = mix(imageLoad(polar, ivec2(x0, y0)), imageLoad(polar, ivec2(x1, y0)), t.x);
  vec4 bottom = mix(imageLoad(polar, ivec2(x0, y1)), imageLoad(polar, ivec2(x1, y1)), t.x);
  imageStore(rays, texel, mix(top, bottom, t.y));
}
