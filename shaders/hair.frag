#version 450
#extension GL_GOOGLE_include_directive : require
// Hair ribbons, premultiplied alpha (see render/passes/hair_pass.hpp): the radiance shaded at the
// strand's vertices (render/passes/hair_lighting_pass.hpp), interpolated along the segment.
#include "hair_uniforms.glsl"

layout(location = 0) in vec3 inRadiance;
layout(location = 1) in float inCoverage;
layout(location = 0) out vec4 outColor;

void main() {
  float alpha = hair.groom.z * clamp(inCoverage, 0.0, 1.0);
  outColor = vec4(inRadiance * alpha, alpha);
}
