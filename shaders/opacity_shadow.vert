#version 450
#extension GL_GOOGLE_include_directive : require
// Opacity map line segments (render/passes/opacity_shadow_map_pass.hpp): vertex 2i and 2i + 1 are the
// ends of segment i; no vertex or index buffer. The weight is the opacity one fragment stands
// for: α·2r/s per texel of line length, times the texels of length a fragment covers
// (1 for rectangular lines; |Δ|/max(|Δx|, |Δy|) when one fragment is made per major-axis column).
#include "opacity_shadow_build.glsl"

layout(location = 0) flat out float weight;

void main() {
  vec4 a, b;
  segmentEnds(uint(gl_VertexIndex) >> 1u, a, b);
  vec2 delta = (b.xy - a.xy) * (0.5 * build.weights.z);
  float major = max(abs(delta.x), abs(delta.y));
  float perFragment = (build.weights.y > 0.5 || major == 0.0) ? 1.0 : length(delta) / major;
  weight = build.weights.x * perFragment;
  gl_Position = (gl_VertexIndex & 1) == 0 ? a : b;
}
