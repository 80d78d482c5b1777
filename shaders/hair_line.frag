#version 450
#extension GL_GOOGLE_include_directive : require
// Hair lines, premultiplied alpha, as hair.frag draws ribbons. With one sample per pixel the
// fragment's distance from the line is measured along the line's normal, which holds however the
// rasterizer interpolates along a wide line.
#include "hair_uniforms.glsl"
#include "hair_coverage.glsl"

layout(constant_id = 0) const bool kAnalyticCoverage = false;

layout(location = 0) in vec3 inRadiance;
layout(location = 1) in float inCoverage;
layout(location = 2) noperspective in vec2 inCentre;
layout(location = 3) in float inHalfWidth;
layout(location = 4) flat in vec2 inNormal;
layout(location = 0) out vec4 outColor;

void main() {
  float coverage = clamp(inCoverage, 0.0, 1.0);
  if (kAnalyticCoverage) {
    float distance = abs(dot(gl_FragCoord.xy - inCentre, inNormal));
    coverage *= hairPixelCoverage(distance, inHalfWidth, inNormal);
  }
  float alpha = hair.groom.z * coverage;
  outColor = vec4(inRadiance * alpha, alpha);
}
