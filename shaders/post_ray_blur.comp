#version 450
// God rays, step 3 (render/passes/post_chain.hpp): the blur along each ray of the polar image (a
// vertical blur: one column per angle), towards the light: out(j) = Σ_{k: j − k·step ≥ 0} w[k] ·
// in(j − k·step) with w[k] ∝ decay^k, tapered (godRayWeights), so light only moves outwards and
// fades; taps that would reach past the light add nothing, so each ray keeps the light it had
// (radialBlur in render/passes/post_reference.hpp). Taps and step are specialisation constants.

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const int kTaps = 32;  // kGodRayTaps, ≤ 32
layout(constant_id = 1) const int kStep = 2;   // kGodRayStep

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D polar;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D blurred;

// w[k] = weights[k / 4][k % 4] (godRayWeights).
layout(push_constant) uniform Weights {
  vec4 weights[8];
} kernel;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(polar)))) return;
  vec4 sum = vec4(0.0);
  // Every tap, those past the light weighted 0 (they read the light's row): a loop of fixed
  // length, which lavapipe ran about a fifth faster than one that ends at the light (god rays in
  // nalu's frame, 19 → 15 ms in a slow spell); also faster than this loop for the workgroups
  // clear of the light with the other for the rest. The sums are the same: the polar image holds
  // finite values, so the extra terms add 0.
  for (int k = 0; k < kTaps; ++k) {
    int row = texel.y - k * kStep;
    float weight = row >= 0 ? kernel.weights[k / 4][k % 4] : 0.0;
    sum += weight * imageLoad(polar, ivec2(texel.x, max(row, 0)));
  }
  imageStore(blurred, texel, sum);
}
