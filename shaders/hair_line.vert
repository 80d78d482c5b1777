#version 450
#extension GL_GOOGLE_include_directive : require
// Lines standing in for the ribbons (render/passes/hair_pass.hpp, "Lines"): gl_VertexIndex =
// s × Nd + i is vertex i of strand s. hair_primitive.comp has already placed the vertex and found
// its coverage or width, for every vertex, so this shader only passes them on: on lavapipe, vertex shading
// runs on one thread, where reading the strands a second time is expensive
// (docs/lavapipe.md#vertex-shading-is-single-threaded).
#include "hair_uniforms.glsl"

layout(constant_id = 0) const bool kAnalyticCoverage = false;

layout(location = 0) in vec4 inClip;  // the strand's centre, clip space
// With MSAA, x: true width / line width × the strand's opacity factor, ≤ 1. With analytic
// coverage, x: the strand's half width (pixels), yz: the unit direction on screen of the segment
// that starts here, w: the strand's opacity factor.
layout(location = 1) in vec4 inWidth;
layout(location = 2) in vec4 inRadiance;  // rgb towards the eye (render/passes/hair_lighting_pass.hpp)

layout(location = 0) out vec3 outRadiance;
layout(location = 1) out float outCoverage;
// Analytic coverage only: the centre (pixels), the half width (pixels), and the line's unit
// normal on screen, from the vertex that starts the line.
layout(location = 2) noperspective out vec2 outCentre;
layout(location = 3) out float outHalfWidth;
layout(location = 4) flat out vec2 outNormal;

void main() {
  outRadiance = inRadiance.rgb;
  outCoverage = kAnalyticCoverage ? inWidth.w : inWidth.x;
  outCentre = (inClip.xy / inClip.w * 0.5 + 0.5) * hair.viewport.xy;
  outHalfWidth = inWidth.x;
  outNormal = vec2(-inWidth.z, inWidth.y);
  gl_Position = inClip;
}
