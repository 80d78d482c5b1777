#version 450
// One of the twelve blurs of texture-space diffusion (render/passes/skin_diffusion_pass.hpp): a 1D
// Gaussian along u or v whose width in texels follows the stretch map, with the taps of
// render/passes/skin_diffusion_kernel.hpp (the CPU reference,
// render/passes/skin_diffusion_reference.cpp, does the same arithmetic). A blur along v also
// adds its result, weighted per RGB, into the running sums of the diffused irradiance and of the
// coverage; the last one divides the two (the resolve) and leaves the result in `accumulated`.
// No branch or loop here depends on the texel: lavapipe runs those slowly (see the kernel file).

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const int kHalfTaps = 6;   // H: 12 or 6 (SkinDiffusionStage::halfTaps)
layout(constant_id = 1) const int kAccumulate = 0;  // one of the kAccumulate* below

const int kAccumulateNone = 0;     // a blur along u
const int kAccumulateFirst = 1;    // the first blur along v: starts the sums
const int kAccumulateAdd = 2;
const int kAccumulateResolve = 3;  // the last: adds, divides, writes the result

const float kReach = 3.0;          // kSkinBlurReach
const float kMinSigma = 1e-3;      // kSkinBlurMinSigma, texels
const float kMinCoverage = 1e-3;   // kSkinMinCoverage

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D source;  // rgb E × coverage, a coverage
layout(set = 0, binding = 1) uniform sampler2D stretch;  // mm per texel along u, v; 0 off the mesh
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D destination;
layout(set = 0, binding = 3, rgba16f) uniform image2D accumulated;  // Σ w·blur(E·c); after the resolve, the result
layout(set = 0, binding = 4, rgba16f) uniform image2D coverage;     // Σ w·blur(c), per RGB

// Mirrors BlurConstants in render/passes/skin_diffusion_pass.cpp.
layout(push_constant) uniform Blur {
  vec4 stage;   // x σ of this blur alone (mm), y stretch for texels off the mesh (mm per texel)
  vec4 weight;  // rgb: the profile's weight of the Gaussian this blur completes
  ivec4 mode;   // x axis (0 u, 1 v)
} blur;

ivec2 mapSize;

vec4 fetch(ivec2 texel) {
  // Off the map: transparent black, no coverage. A select, not a branch.
  bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, mapSize));
  vec4 value = imageLoad(source, clamp(texel, ivec2(0), mapSize - 1));
  return inside ? value : vec4(0.0);
}

void main() {
  mapSize = imageSize(source);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  // Dispatches cover the map exactly (its size is a multiple of 8), so no invocation is idle.
  ivec2 step = blur.mode.x == 0 ? ivec2(1, 0) : ivec2(0, 1);
  float mmPerTexel = texelFetch(stretch, texel, 0)[blur.mode.x];
  mmPerTexel = mmPerTexel > 0.0 ? mmPerTexel : blur.stage.y;
  float sigma = max(blur.stage.x / mmPerTexel, kMinSigma);
  float spacing = max(1.0, kReach * sigma / float(kHalfTaps));
  float exponent = -0.5 / (sigma * sigma);

  // Trapezoid weights on the rounded nodes x_k = round(k·spacing): G(x_k)·(x_(k+1) − x_(k−1))/2.
  float previous = 0.0;
  float here = 0.0;
  float next = floor(spacing + 0.5);
  vec4 sum = next * fetch(texel);  // the centre: G(0)·(x_1 − x_(−1))/2 = x_1
  float total = next;
  for (int k = 1; k <= kHalfTaps; ++k) {
    previous = here;
    here = next;
    next = floor(float(k + 1) * spacing + 0.5);
    float w = exp(exponent * here * here) * 0.5 * (next - previous);
    int offset = int(here);
    sum += w * (fetch(texel + offset * step) + fetch(texel - offset * step));
    total += 2.0 * w;
  }
  sum /= total;

  if (kAccumulate != kAccumulateResolve) imageStore(destination, texel, sum);
  if (kAccumulate == kAccumulateNone) return;
  vec3 diffused = blur.weight.rgb * sum.rgb;
  vec3 covered = blur.weight.rgb * sum.a;
  if (kAccumulate != kAccumulateFirst) {
    diffused += imageLoad(accumulated, texel).rgb;
    covered += imageLoad(coverage, texel).rgb;
  }
  if (kAccumulate != kAccumulateResolve) {
    imageStore(accumulated, texel, vec4(diffused, 0.0));
    imageStore(coverage, texel, vec4(covered, 0.0));
    return;
  }
  // Normalised convolution: Σ w·blur(E·c) / Σ w·blur(c) per channel, so texels off the mesh
  // (c = 0) neither darken the islands' borders nor stay black beside them.
  bvec3 defined = greaterThanEqual(covered, vec3(kMinCoverage));
  vec3 result = mix(vec3(0.0), diffused / max(covered, vec3(kMinCoverage)), defined);
  imageStore(accumulated, texel, vec4(result, min(covered.r, min(covered.g, covered.b))));
}
