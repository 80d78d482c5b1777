#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the pre-integrated skin table of render/luts/preintegrated_skin_lut.hpp: rgb = the
// diffuse ring integral, equation (1) of render/luts/preintegrated_skin.hpp, by the same
// quadrature as its CPU reference (render/luts/preintegrated_skin.cpp); a = the encoded Beckmann
// term of render/luts/skin_specular.hpp. The layout is the one shaders/preintegrated_skin.glsl reads.
#include "preintegrated_skin.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, r16f) uniform writeonly image2DArray table;  // layers R, G, B, A

const int kGaussians = 6;
const int kNodes = 12;      // kSkinQuadratureNodes
const int kMaxBreaks = 16;  // −limit, ≤ 12 kinks (1/r ≤ 10 mm⁻¹), 0, +limit

// Mirrors BakeUniforms in render/luts/preintegrated_skin_lut.cpp.
layout(set = 0, binding = 1, std140) uniform Bake {
  vec4 gaussians[kGaussians];  // x variance (mm²), yzw weight per RGB
  vec4 nodes[kNodes];          // x position in [−1, 1], y weight: Gauss-Legendre
  uvec4 sizes;                 // x texels per side, y range (0 Penner, 1 curvature-dependent)
  vec4 scales;                 // x maxCurvature (1/mm), y maxRoughness, z reach (standard deviations)
} bake;

// ∫ max(cos(θ + x), 0) G dx (x) and ∫ G dx (y) for one Gaussian; see integrateGaussian() in the
// CPU reference for the rule. cos(θ + x) is expanded with cos θ = N·L, sin θ = sqrt(1 − N·L²),
// which are exact, so acos's error (~1e-4 rad on lavapipe) only moves the piece boundaries.
vec2 integrateGaussian(float variance, float nDotL, float theta, float curvature, float halfRange) {
  float reach = 0.5 * bake.scales.z * sqrt(variance) * curvature;
  float limit = reach >= 1.0 ? halfRange : min(halfRange, 2.0 * asin(reach));
  float breaks[kMaxBreaks];
  int count = 0;
  breaks[count++] = -limit;
  int first = int(ceil((-limit + theta) / kSkinPi - 0.5));
  int last = int(floor((limit + theta) / kSkinPi - 0.5));
  bool zeroPlaced = false;
  for (int k = first; k <= last && count + 2 < kMaxBreaks; ++k) {
    float kink = (float(k) + 0.5) * kSkinPi - theta;
    if (!zeroPlaced && kink >= 0.0) {
      breaks[count++] = 0.0;
      zeroPlaced = true;
    }
    if (kink > -limit && kink < limit) breaks[count++] = kink;
  }
  if (!zeroPlaced) breaks[count++] = 0.0;
  breaks[count++] = limit;

  float sinTheta = sqrt(max(1.0 - nDotL * nDotL, 0.0));
  float norm = 1.0 / (2.0 * kSkinPi * variance);
  float inverseCurvature = 1.0 / curvature;
  vec2 sum = vec2(0.0);
  for (int piece = 0; piece + 1 < count; ++piece) {
    float a = breaks[piece];
    float b = breaks[piece + 1];
    if (b <= a) continue;
    float middle = 0.5 * (a + b);
    float half_ = 0.5 * (b - a);
    for (int n = 0; n < kNodes; ++n) {
      float x = middle + half_ * bake.nodes[n].x;
      float chord = 2.0 * sin(0.5 * x) * inverseCurvature;
      float g = half_ * bake.nodes[n].y * norm * exp(-chord * chord / (2.0 * variance));
      sum += vec2(max(nDotL * cos(x) - sinTheta * sin(x), 0.0) * g, g);
    }
  }
  return sum;
}

vec3 diffuse(float nDotL, float curvature) {
  if (curvature <= 0.0) return vec3(max(nDotL, 0.0));
  float theta = acos(clamp(nDotL, -1.0, 1.0));
  // π(r + 1)/(2r) = (π/2)(1 + 1/r) for the curvature-dependent range, π/2 for Penner's.
  float halfRange = bake.sizes.y == 0u ? 0.5 * kSkinPi : 0.5 * kSkinPi * (1.0 + curvature);
  vec3 lit = vec3(0.0);
  vec3 total = vec3(0.0);
  for (int i = 0; i < kGaussians; ++i) {
    vec3 weight = bake.gaussians[i].yzw;
    if (weight == vec3(0.0)) continue;
    vec2 m = integrateGaussian(bake.gaussians[i].x, nDotL, theta, curvature, halfRange);
    lit += weight * m.x;
    total += weight * m.y;
  }
  return lit / total;
}

// 0.5·D^0.1 computed in logs: exact where D itself would underflow a float (its tails).
float encodedBeckmann(float nDotH, float roughness) {
  if (nDotH <= 0.0 || roughness <= 0.0) return 0.0;
  float cos2 = nDotH * nDotH;
  float a2 = roughness * roughness;
  float logD = -(1.0 - cos2) / (cos2 * a2) - log(kSkinPi * a2 * cos2 * cos2);
  return 0.5 * exp(0.1 * logD);
}

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  uint size = bake.sizes.x;
  if (any(greaterThanEqual(texel, uvec2(size)))) return;
  vec2 x = skinLutParameter(texel, size);
  vec3 rgb = diffuse(2.0 * x.x - 1.0, x.y * bake.scales.x);
  float a = encodedBeckmann(x.x, x.y * bake.scales.y);
  for (int channel = 0; channel < 3; ++channel) imageStore(table, ivec3(texel, channel), vec4(rgb[channel]));
  imageStore(table, ivec3(texel, 3), vec4(a));
}
