#version 450
#extension GL_GOOGLE_include_directive : require
// A shell keeps the photo's pixels whose luminance lies in its layer's range (Ukaji et al.
// §3.3: only the photo and the thresholds I(n − 1), I(n) reach the shader) and discards the
// rest; kept fragments are opaque, so depth testing composites the layers in any order.
#include "fur_common.glsl"

// 1: the pipeline draws only the skin layer, which keeps every pixel: no discard in the shader,
// so depth can be tested before it runs.
layout(constant_id = 3) const uint kSkinLayer = 0u;

layout(location = 0) in vec3 inDiffuse;  // FurLight, from the vertices
layout(location = 1) in vec3 inSpecular;
layout(location = 2) in vec2 inUv;
layout(location = 3) flat in uint inLayer;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 albedo = texture(photo, inUv).rgb;
  float intensity = luminance(albedo);
  uint layers = layerCount();
  // Layer N is the skin: opaque, so nothing shows through the body. Above it, bands keep
  // I(n) ≤ I < I(n − 1) (layer 1 also anything brighter than I_max); strands keep I ≥ I(n), every
  // pixel whose fur reaches this high.
  bool skin = inLayer == layers;
  bool aboveLower = intensity >= threshold(inLayer);
  bool belowUpper = kCoverage == 1u || inLayer == 1u || intensity < threshold(inLayer - 1u);
  if (kSkinLayer == 0u && !skin && !(aboveLower && belowUpper)) discard;
  outColor = vec4(albedo * inDiffuse + inSpecular, 1.0);
}
