#version 450
// One of the glow's four separable Gaussian blurs (x, y, x, y; render/passes/post_pass.hpp) on
// the downsampled copy: 2R + 1 taps with the normalised weights of glowKernel()
// (render/passes/post_reference.hpp), clamped to the edge. The radius and the axis are
// specialisation constants, so the loop has a fixed trip count and no branch depends on a
// uniform (lavapipe runs both sides of those).

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const int kRadius = 8;  // R ≤ kGlowMaxRadius
layout(constant_id = 1) const int kAxis = 0;    // 0 along x, 1 along y

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D destination;

// w[k] for the offsets ±k, k = 0…R: w[k] = weights[k / 4][k % 4].
layout(push_constant) uniform Kernel {
  vec4 weights[3];
} kernel;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(source);
  if (any(greaterThanEqual(texel, size))) return;
  // Arithmetic, not a vector select on the constant: lavapipe (Mesa 22.3) turned
  // `kAxis == 0 ? ivec2(1, 0) : ivec2(0, 1)` into (1, 1), a diagonal blur.
  ivec2 step = ivec2(1 - kAxis, kAxis);
  vec4 sum = kernel.weights[0][0] * imageLoad(source, texel);
  for (int k = 1; k <= kRadius; ++k) {
    vec4 pair = imageLoad(source, clamp(texel + k * step, ivec2(0), size - 1)) +
                imageLoad(source, clamp(texel - k * step, ivec2(0), size - 1));
    sum += kernel.weights[k / 4][k % 4] * pair;
  }
  imageStore(destination, texel, sum);
}
