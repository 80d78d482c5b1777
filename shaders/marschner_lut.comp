#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the Marschner lookup tables of render/luts/marschner_lut.hpp: the longitudinal table
// M_p(θi, θr) (bake.table == 0) or the azimuthal table N_p(θr, φ) (bake.table == 1). The maths
// mirrors the CPU reference render/luts/marschner.cpp, whose file comment has the equations
// and sources; the texel layout is the one shaders/hair_shading.glsl reads.
#include "hair_shading.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform writeonly image2D longitudinalTable;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray azimuthalTable;

// Mirrors BakeConstants in render/luts/marschner_lut.cpp.
layout(push_constant) uniform Bake {
  vec4 absorption;  // xyz σa per RGB (1/fibre radius), w refractive index η
  vec4 shifts;      // xyz α_R, α_TT, α_TRT (radians), w azimuthal width β_N (radians)
  vec4 widths;      // xyz β_R, β_TT, β_TRT (radians)
  uvec4 sizes;      // x M size, y N width (φ), z N height (cos θr), w nodes of the h integral
  uvec4 table;      // x: 0 = M, 1 = N
} bake;

// log I0(x), x ≥ 0: power series below 20, asymptotic series of e^−x I0(x) above (A&S 9.7.1).
float logBesselI0(float x) {
  if (x < 20.0) {
    float q = 0.25 * x * x;
    float term = 1.0;
    float sum = 1.0;
    for (int k = 1; k < 80 && term > 1e-8 * sum; ++k) {
      term *= q / float(k * k);
      sum += term;
    }
    return log(sum);
  }
  float y = 1.0 / (8.0 * x);
  float series = 1.0 + y * (1.0 + y * (4.5 + y * (37.5 + y * 459.375)));
  return x - 0.5 * log(2.0 * kHairPi * x) + log(series);
}

// d'Eon et al. 2011 eq. 7 for variance v = β², with θ' = θr − 2α already applied.
float longitudinalLobe(float variance, float thetaI, float shiftedThetaR) {
  float kappa = 1.0 / variance;
  float a = kappa * cos(thetaI) * abs(cos(shiftedThetaR));
  float b = kappa * sin(thetaI) * sin(shiftedThetaR);
  // κ/(2 sinh κ) in logs, finite for large κ. log1p is not in GLSL; 1 − e^−2κ only loses
  // digits for κ ≪ 1, i.e. β ≫ 1 rad, which validate() excludes.
  float logNorm = log(kappa) - kappa - log(1.0 - exp(-2.0 * kappa));
  return exp(logNorm - b + logBesselI0(a));
}

// Unpolarised Fresnel reflectance entering a dielectric of index η at cos(incidence) ≥ 0.
float fresnelDielectric(float eta, float cosIncidence) {
  float sin2T = (1.0 - cosIncidence * cosIncidence) / (eta * eta);
  if (sin2T >= 1.0) return 1.0;
  float cosT = sqrt(1.0 - sin2T);
  float rs = (cosIncidence - eta * cosT) / (cosIncidence + eta * cosT);
  float rp = (eta * cosIncidence - cosT) / (eta * cosIncidence + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// asin to float precision for |x| ≤ 1/η: drivers may implement asin with errors of ~1e-4 rad
// (Vulkan allows 4096 ULP; Mesa's lavapipe uses a short polynomial), which would shift TRT's
// caustic by a visible fraction of β_N. One Newton step on sin(a) = x squares the error; sin and
// cos are accurate, and cos a ≥ sqrt(1 − 1/η²) here.
float accurateAsin(float x) {
  float a = asin(x);
  return a - (sin(a) - x) / cos(a);
}

// Normal density of standard deviation `sigma` wrapped onto the circle (three images).
float wrappedGaussian(float x, float sigma) {
  x -= 2.0 * kHairPi * round(x / (2.0 * kHairPi));
  float s2 = 2.0 * sigma * sigma;
  float xm = x - 2.0 * kHairPi;
  float xp = x + 2.0 * kHairPi;
  return (exp(-x * x / s2) + exp(-xm * xm / s2) + exp(-xp * xp / s2)) / (sqrt(2.0 * kHairPi) * sigma);
}

void bakeLongitudinal(uvec2 texel) {
  vec2 theta = (hairLutParameter(texel, uvec2(bake.sizes.x)) - 0.5) * kHairPi;
  vec3 m;
  for (int p = 0; p < 3; ++p)
    m[p] = longitudinalLobe(bake.widths[p] * bake.widths[p], theta.x, theta.y - 2.0 * bake.shifts[p]);
  imageStore(longitudinalTable, ivec2(texel), vec4(m, 0.0));
}

void bakeAzimuthal(uvec2 texel) {
  vec2 x = hairLutParameter(texel, bake.sizes.yz);
  float phi = x.x * kHairPi;
  float cosThetaR = x.y;
  float eta = bake.absorption.w;
  float sigmaN = bake.shifts.w;
  float sin2ThetaR = 1.0 - cosThetaR * cosThetaR;
  float inverseEtaPrime = cosThetaR / sqrt(eta * eta - sin2ThetaR);  // 1/η'(θr), Bravais
  float cosThetaT = sqrt(max(1.0 - sin2ThetaR / (eta * eta), 0.0));
  uint nodes = bake.sizes.w;
  float step = 0.5 * kHairPi / float(nodes);
  float nR = 0.0;
  vec3 nTT = vec3(0.0);
  vec3 nTRT = vec3(0.0);
  for (uint j = 0u; j < nodes; ++j) {
    float gammaI = (float(j) + 0.5) * step;
    float h = sin(gammaI);
    float cosGammaI = cos(gammaI);
    float sinGammaT = h * inverseEtaPrime;
    float gammaT = accurateAsin(sinGammaT);
    float cosGammaT = sqrt(max(1.0 - sinGammaT * sinGammaT, 0.0));
    float f = fresnelDielectric(eta, cosThetaR * cosGammaI);
    vec3 t = exp(-bake.absorption.xyz * (2.0 * cosGammaT / cosThetaT));
    float g = 1.0 - f;
    float weight = 0.5 * step * cosGammaI;
    vec3 exits = vec3(-2.0 * gammaI, 2.0 * gammaT - 2.0 * gammaI + kHairPi, 4.0 * gammaT - 2.0 * gammaI + 2.0 * kHairPi);
    vec3 d;
    for (int p = 0; p < 3; ++p)
      d[p] = weight * (wrappedGaussian(phi - exits[p], sigmaN) + wrappedGaussian(phi + exits[p], sigmaN));
    nR += f * d[0];
    nTT += g * g * t * d[1];
    nTRT += g * g * f * t * t * d[2];
  }
  imageStore(azimuthalTable, ivec3(texel, 0), vec4(nTT, nR));
  imageStore(azimuthalTable, ivec3(texel, 1), vec4(nTRT, 0.0));
}

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  uvec2 size = bake.table.x == 0u ? bake.sizes.xx : bake.sizes.yz;
  if (any(greaterThanEqual(texel, size))) return;
  if (bake.table.x == 0u)
    bakeLongitudinal(texel);
  else
    bakeAzimuthal(texel);
}
