#version 450
#extension GL_GOOGLE_include_directive : require
// Camera-facing ribbons pulled from the dense-strand storage buffers (see render/passes/hair_pass.hpp).
// Indexed: gl_VertexIndex = 2 × (k × Nd + i) + side is vertex i of strand order[k], the k-th
// strand in drawing order (back to front), pushed to side 0 (−) or 1 (+). The index buffer joins
// them into two triangles per segment, so each ribbon vertex is shaded once, not six times.
#include "hair_uniforms.glsl"

layout(set = 0, binding = 1, std430) readonly buffer Positions {
  vec4 positions[];  // xyz metres, w = t along the strand
};
layout(set = 0, binding = 2, std430) readonly buffer Tangents {
  vec4 tangents[];  // xyz unit tangent root → tip
};

layout(set = 0, binding = 3, std430) readonly buffer Radiance {
  vec4 radiance[];  // rgb towards the eye, shaded per vertex (render/passes/hair_lighting.hpp)
};

layout(set = 0, binding = 4, std430) readonly buffer DrawOrder {
  uint order[];  // strand indices in the order they are drawn
};

layout(location = 0) out vec3 outRadiance;
layout(location = 1) out float outCoverage;  // true width / drawn width, ≤ 1

void main() {
  uint verticesPerStrand = hair.counts.y;
  uint ribbonPoint = uint(gl_VertexIndex) >> 1u;
  float sideSign = (gl_VertexIndex & 1) == 0 ? -1.0 : 1.0;
  uint vertex = order[ribbonPoint / verticesPerStrand] * verticesPerStrand + ribbonPoint % verticesPerStrand;

  vec4 point = positions[vertex];
  vec3 tangent = tangents[vertex].xyz;
  vec3 toEye = hairToEye(point.xyz);
  // Perpendicular to the strand and to the view; any perpendicular to the view where the strand
  // points at the eye (or its tangent is zero: coincident neighbours).
  vec3 side = cross(tangent, toEye);
  if (dot(side, side) < 1e-12) side = cross(abs(toEye.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0), toEye);
  side = normalize(side);

  // Pixels per metre along `side` here, from projecting the root half-width offset (exact for any
  // projection, including the obliquity of off-axis strands under perspective).
  float rootHalfWidth = 0.5 * hair.groom.x;
  vec4 centre = hair.viewProjection * vec4(point.xyz, 1.0);
  vec4 edge = hair.viewProjection * vec4(point.xyz + side * rootHalfWidth, 1.0);
  vec2 offsetPixels = (edge.xy / edge.w - centre.xy / centre.w) * 0.5 * hair.viewport.xy;
  float pixelsPerMetre = length(offsetPixels) / rootHalfWidth;

  float halfWidth = rootHalfWidth * mix(1.0, hair.groom.y, point.w);
  float drawnHalfWidth = max(halfWidth, 0.5 * hair.groom.w / max(pixelsPerMetre, 1e-6));
  outCoverage = halfWidth / drawnHalfWidth;

  vec3 world = point.xyz + side * (sideSign * drawnHalfWidth);
  outRadiance = radiance[vertex].rgb;
  gl_Position = hair.viewProjection * vec4(world, 1.0);
}
