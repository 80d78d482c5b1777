#version 450
// The auto gain's tiny image (render/passes/post_pass.hpp): each texel the mean of a k×k block
// of the downsampled copy, over the texels of the block inside it (tinyForAutoGain in
// render/passes/post_reference.hpp). k is fixed per frame size: a specialisation constant.

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const int kBlock = 1;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D quarter;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D tiny;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(tiny)))) return;
  ivec2 size = imageSize(quarter);
  vec4 sum = vec4(0.0);
  float count = 0.0;
  for (int dy = 0; dy < kBlock; ++dy)
    for (int dx = 0; dx < kBlock; ++dx) {
      ivec2 at = kBlock * texel + ivec2(dx, dy);
      bool inside = all(lessThan(at, size));
      sum += inside ? imageLoad(quarter, min(at, size - 1)) : vec4(0.0);
      count += inside ? 1.0 : 0.0;
    }
  imageStore(tiny, texel, sum / count);
}
