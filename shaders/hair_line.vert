#version 450
// Lines of the minimum width standing in for the ribbons (render/passes/hair_pass.hpp, "Lines"):
// gl_VertexIndex = s × Nd + i is vertex i of strand s. hair_primitive.comp has already placed the
// vertex and found its coverage, for every vertex, so this shader only passes them on: on
// lavapipe, vertex shading runs on one thread, where reading the strands a second time is
// expensive (docs/lavapipe.md#vertex-shading-is-single-threaded).
layout(location = 0) in vec4 inClip;       // the strand's centre, clip space
layout(location = 1) in float inCoverage;  // true width / drawn width × the strand's opacity factor, ≤ 1
layout(location = 2) in vec4 inRadiance;   // rgb towards the eye (render/passes/hair_lighting_pass.hpp)

layout(location = 0) out vec3 outRadiance;
layout(location = 1) out float outCoverage;

void main() {
  outRadiance = inRadiance.rgb;
  outCoverage = inCoverage;
  gl_Position = inClip;
}
