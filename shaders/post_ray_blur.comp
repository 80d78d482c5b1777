#version 450
// God rays, step 3 (render/passes/post_pass.hpp): the blur along each ray of the polar image (a
// vertical blur: one column per angle), towards the light: out(j) = Σ_{k: j − k·step ≥ 0} w[k] ·
// in(j − k·step) with w[k] = w₀·d^k·(1 − k²/K²) for k < K taps (godRayWeights), so light only
// moves outwards and fades; taps that would reach past the light add nothing, so each ray keeps
// the light it had (radialBlur in render/passes/post_reference.hpp).
//
// One invocation walks a whole column outwards and keeps, per residue of j mod step, three
// running sums over the last K taps: A = Σ d^k·in, B = Σ k·d^k·in, C = Σ k²·d^k·in. One step
// outwards multiplies every term by d and raises its k by one, which the binomial expansion of
// (k + 1)ⁿ turns into A' = in + d·A, B' = d·(B + A), C' = d·(C + 2B + A), less the term that
// leaves the window (k = K); out = w₀·(A − C/K²). So two loads per texel instead of K: on
// lavapipe the direct sum's loads would be more than half of the god rays' cost
// (docs/lavapipe.md#branches-run-every-lane).
// The sums are rounded differently from the direct sum's, by a few units of the last place in
// fp32, well below the fp16 image's rounding. Taps and step are specialisation constants.

layout(local_size_x = 32) in;

layout(constant_id = 0) const int kTaps = 32;  // kGodRayTaps
layout(constant_id = 1) const int kStep = 2;   // kGodRayStep

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D polar;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D blurred;

layout(push_constant) uniform Kernel {
  ivec2 extent;        // the angles and radii of the polar image in use (godRayPolarExtent)
  float decay;         // d
  float firstWeight;   // w₀ = w[0]
  float decayPastEnd;  // d^K
} kernel;

void main() {
  int column = int(gl_GlobalInvocationID.x);
  if (column >= kernel.extent.x) return;
  const float taps = float(kTaps);
  const float tapsSquared = taps * taps;
  vec4 a[kStep], b[kStep], c[kStep];
  for (int residue = 0; residue < kStep; ++residue) {
    a[residue] = vec4(0.0);
    b[residue] = vec4(0.0);
    c[residue] = vec4(0.0);
  }
  // kStep rows an iteration, so that the residue, and with it every array index, is a constant
  // once the inner loop is unrolled. The outer loop runs to the image's height and breaks at the
  // extent's: a trip count read from push constants alone would let lavapipe fold it into the
  // shader and compile it again for every value.
  int rows = imageSize(polar).y;
  for (int first = 0; first < rows; first += kStep) {
    if (first >= kernel.extent.y) break;
    for (int residue = 0; residue < kStep; ++residue) {
      int row = min(first + residue, rows - 1);
      vec4 entering = imageLoad(polar, ivec2(column, row));
      int leavingRow = row - kTaps * kStep;
      vec4 leaving = leavingRow >= 0 ? kernel.decayPastEnd * imageLoad(polar, ivec2(column, max(leavingRow, 0)))
                                     : vec4(0.0);
      vec4 a0 = a[residue], b0 = b[residue], c0 = c[residue];
      a[residue] = entering + kernel.decay * a0 - leaving;
      b[residue] = kernel.decay * (b0 + a0) - taps * leaving;
      c[residue] = kernel.decay * (c0 + 2.0 * b0 + a0) - tapsSquared * leaving;
      if (first + residue < kernel.extent.y)
        imageStore(blurred, ivec2(column, row), kernel.firstWeight * (a[residue] - c[residue] / tapsSquared));
    }
  }
}
