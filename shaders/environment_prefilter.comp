#version 450
#extension GL_GOOGLE_include_directive : require
// One level of the environment's specular chain (render/environment/specular_chain.hpp): the
// radiance pre-filtered for GGX roughness r around each texel's direction n, with the view along
// n (Karis's split sum): Σ L(l)·(n·l) / Σ (n·l) over half vectors h importance-sampled from
// D(h)·(n·h), l = 2(n·h)h − n, each L(l) read from the source's mip whose texels subtend the
// sample's solid angle 1/(N·pdf(l)), pdf(l) = D(h)/4 (Křivánek and Colbert).

#include "cube_directions.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform samplerCube source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2DArray level;

// Mirrors PrefilterConstants in render/environment/specular_chain.cpp.
layout(push_constant) uniform Prefilter {
  uvec4 sizes;     // x: this level's size, y: samples, z: the source's size
  vec4 roughness;  // x
} prefilter;

const float kPi = 3.14159265358979;

// Point i of n of the Hammersley set: (i/n, the radical inverse of i in base 2).
vec2 hammersley(uint i, uint n) { return vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10); }

void main() {
  uint size = prefilter.sizes.x;
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= size || id.y >= size) return;
  vec3 n = cubeDirection(id.z, (vec2(id.xy) + 0.5) / float(size));
  float r = prefilter.roughness.x;
  vec3 radiance;
  if (r == 0.0) {
    radiance = textureLod(source, n, 0.0).rgb;
  } else {
    float alpha2 = r * r * r * r;
    vec3 helper = abs(n.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent = normalize(cross(helper, n));
    vec3 bitangent = cross(n, tangent);
    uint samples = prefilter.sizes.y;
    float texelSolidAngle = 4.0 * kPi / (6.0 * float(prefilter.sizes.z * prefilter.sizes.z));
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < samples; ++i) {
      vec2 xi = hammersley(i, samples);
      // GGX's inverse CDF in cos θ_h (Walter et al. 2007, eq. 35 and 36).
      float cosH = sqrt((1.0 - xi.y) / (1.0 + (alpha2 - 1.0) * xi.y));
      float sinH = sqrt(max(1.0 - cosH * cosH, 0.0));
      float phi = 2.0 * kPi * xi.x;
      vec3 h = (cos(phi) * sinH) * tangent + (sin(phi) * sinH) * bitangent + cosH * n;
      vec3 l = 2.0 * dot(n, h) * h - n;
      float cosL = dot(n, l);
      if (cosL <= 0.0) continue;
      float d = cosH * cosH * (alpha2 - 1.0) + 1.0;
      float pdf = alpha2 / (kPi * d * d) * 0.25;
      float sampleSolidAngle = 1.0 / (float(samples) * pdf);
      float lod = max(0.5 * log2(sampleSolidAngle / texelSolidAngle), 0.0);
      sum += textureLod(source, l, lod).rgb * cosL;
      weight += cosL;
    }
    radiance = sum / max(weight, 1e-6);
  }
  imageStore(level, ivec3(id), vec4(radiance, 1.0));
}
