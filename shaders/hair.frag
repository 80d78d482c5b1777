#version 450
#extension GL_GOOGLE_include_directive : require
// Hair ribbons, premultiplied alpha (see render/passes/hair_pass.hpp): the radiance shaded at the
// strand's vertices (render/passes/hair_lighting_pass.hpp), interpolated along the segment, and
// the coverage: with MSAA as hair.vert scaled it, with one sample the pixel's share of the strand.
#include "hair_uniforms.glsl"
#include "hair_coverage.glsl"

layout(constant_id = 0) const bool kAnalyticCoverage = false;

layout(location = 0) in vec3 inRadiance;
layout(location = 1) in float inCoverage;
layout(location = 2) noperspective in float inAcross;
layout(location = 3) in float inHalfWidth;
layout(location = 4) in vec2 inNormal;
layout(location = 0) out vec4 outColor;

void main() {
  float coverage = kAnalyticCoverage ? inCoverage * hairPixelCoverage(abs(inAcross), inHalfWidth, normalize(inNormal))
                                     : clamp(inCoverage, 0.0, 1.0);
  float alpha = hair.groom.z * coverage;
  outColor = vec4(inRadiance * alpha, alpha);
}
