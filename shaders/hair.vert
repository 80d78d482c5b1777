#version 450
#extension GL_GOOGLE_include_directive : require
// Camera-facing ribbons pulled from the dense-strand storage buffers (render/passes/hair_pass.hpp).
// gl_VertexIndex = 2 × (s × Nd + i) + side is vertex i of strand s pushed to side 0 (−) or 1 (+).
// The index buffer joins them into two triangles per segment, so each ribbon vertex is shaded
// once, not six times. Lines, where the pass chose them, are drawn by hair_line.vert.
#include "hair_uniforms.glsl"
#include "hair_coverage.glsl"

// One sample per pixel: hair.frag computes each pixel's coverage (hair_coverage.glsl).
layout(constant_id = 0) const bool kAnalyticCoverage = false;

layout(set = 0, binding = 1, std430) readonly buffer Positions {
  vec4 positions[];  // xyz metres, w = t along the strand
};
layout(set = 0, binding = 2, std430) readonly buffer Tangents {
  vec4 tangents[];  // xyz unit tangent root → tip
};

layout(set = 0, binding = 3, std430) readonly buffer Radiance {
  vec4 radiance[];  // rgb towards the eye, shaded per vertex (render/passes/hair_lighting_pass.hpp)
};

layout(set = 0, binding = 16) uniform samplerBuffer hairStrandLooks;
#include "hair_strand_look.glsl"

layout(location = 0) out vec3 outRadiance;
// With MSAA: true width / drawn width × the strand's opacity factor, ≤ 1. With analytic
// coverage: the opacity factor alone.
layout(location = 1) out float outCoverage;
// Analytic coverage only: the signed distance from the centre line, the strand's half width (both
// pixels) and its unit normal on screen, in absolute values.
layout(location = 2) noperspective out float outAcross;
layout(location = 3) out float outHalfWidth;
layout(location = 4) out vec2 outNormal;

void main() {
  uint vertex = uint(gl_VertexIndex) >> 1u;
  float sideSign = (gl_VertexIndex & 1) == 0 ? -1.0 : 1.0;

  vec4 point = positions[vertex];
  vec4 shape = hairStrandShape(vertex / hair.counts.y);
  HairRibbon ribbon = hairRibbon(point, tangents[vertex].xyz, shape);
  float drawnHalfWidth = hairDrawnHalfWidth(ribbon, kAnalyticCoverage);
  outCoverage = kAnalyticCoverage ? shape.z : ribbon.halfWidth / drawnHalfWidth * shape.z;
  outAcross = sideSign * drawnHalfWidth * ribbon.pixelsPerMetre;
  outHalfWidth = ribbon.halfWidth * ribbon.pixelsPerMetre;
  outNormal = abs(ribbon.screenSide);

  vec3 world = point.xyz + ribbon.side * (sideSign * drawnHalfWidth);
  outRadiance = radiance[vertex].rgb;
  gl_Position = hair.viewProjection * vec4(world, 1.0);
}
