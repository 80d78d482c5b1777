#version 450
#extension GL_GOOGLE_include_directive : require
// Camera-facing ribbons pulled from the dense-strand storage buffers, or lines of the minimum width
// standing in for them where the pass chose lines (render/passes/hair_pass.hpp, "Lines").
// Ribbons (indexed): gl_VertexIndex = 2 × (k × Nd + i) + side is vertex i of strand order[k], the
// k-th strand in drawing order (back to front), pushed to side 0 (−) or 1 (+). The index buffer
// joins them into two triangles per segment, so each ribbon vertex is shaded once, not six times.
// Lines (indexed): gl_VertexIndex = k × Nd + i, the same vertex on the strand itself; the line
// width is the minimum width.
#include "hair_uniforms.glsl"

layout(constant_id = 0) const bool kLines = false;

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
  uint ribbonPoint = kLines ? uint(gl_VertexIndex) : uint(gl_VertexIndex) >> 1u;
  float sideSign = kLines ? 0.0 : ((gl_VertexIndex & 1) == 0 ? -1.0 : 1.0);
  uint vertex = order[ribbonPoint / verticesPerStrand] * verticesPerStrand + ribbonPoint % verticesPerStrand;

  vec4 point = positions[vertex];
  HairRibbon ribbon = hairRibbon(point, tangents[vertex].xyz);
  float drawnHalfWidth = max(ribbon.halfWidth, ribbon.minimumHalfWidth);
  outCoverage = ribbon.halfWidth / drawnHalfWidth;

  vec3 world = point.xyz + ribbon.side * (sideSign * drawnHalfWidth);
  outRadiance = radiance[vertex].rgb;
  gl_Position = hair.viewProjection * vec4(world, 1.0);
}
