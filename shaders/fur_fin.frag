#version 450
#extension GL_GOOGLE_include_directive : require
// A fin shows the fur of the photo from the side: the hair at a photo pixel of luminance I
// reaches the depth h(I) = ln(I_max/I)/a below the top (Ukaji et al. eq. 1), so a fin fragment at
// height y above the skin is fur where some hair reaches that high. A fin stands for a strip of
// surface seen edge-on: it takes the tallest (brightest) of three photo samples across the edge,
// half an edge apart. Opaque, alpha-tested, like the shells.
#include "fur_common.glsl"

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in float inHeight;
layout(location = 4) flat in vec2 inAcross;
layout(location = 5) in vec3 inDirection;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 albedo = texture(photo, inUv).rgb;
  for (int k = -1; k <= 1; k += 2) {
    vec3 sampled = texture(photo, inUv + float(k) * inAcross).rgb;
    if (luminance(sampled) > luminance(albedo)) albedo = sampled;
  }
  // The fin spans the skin (depth fraction 1) to layer 1 (depth 1/N); eq. 4 at that depth.
  uint layers = layerCount();
  float depthFraction = 1.0 - inHeight * (1.0 - 1.0 / float(layers));
  float iMax = threshold(0u);
  float required = iMax * pow(threshold(layers) / iMax, depthFraction);
  if (luminance(albedo) < required) discard;
  outColor = vec4(shadeFur(albedo, normalize(inNormal), normalize(inDirection), inWorld), 1.0);
}
