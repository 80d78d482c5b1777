#version 450
// The post chain's downsampled copy of the HDR frame (render/passes/post_pass.hpp): each texel
// the mean of a 4×4 block of pixels, read as 4 bilinear taps at the centres of the block's 2×2
// quads (each tap halfway between two pixel centres on both axes: the exact mean of its quad).
// The sampler clamps to the edge, which repeats the last row and column as downsampleForPost
// (render/passes/post_reference.hpp) does.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D frame;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D quarter;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(quarter)))) return;
  vec2 pixelSize = 1.0 / vec2(textureSize(frame, 0));
  vec2 corner = vec2(4 * texel);
  vec4 sum = texture(frame, (corner + vec2(1.0, 1.0)) * pixelSize) +
             texture(frame, (corner + vec2(3.0, 1.0)) * pixelSize) +
             texture(frame, (corner + vec2(1.0, 3.0)) * pixelSize) +
             texture(frame, (corner + vec2(3.0, 3.0)) * pixelSize);
  imageStore(quarter, texel, 0.25 * sum);
}
