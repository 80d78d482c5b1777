#version 450
// Opacity shadow map slices (Kim & Neumann 2001 §3): the fragment adds its weight to every slice
// k whose far boundary z_k = (k + 1)/16 is at or beyond its depth, i.e. k ≥ ceil(16·z) − 1.
// Additive blending sums the fragments; slice k lives in target k/4, channel k%4.
layout(location = 0) flat in float weight;
layout(location = 0) out vec4 slices0;
layout(location = 1) out vec4 slices1;
layout(location = 2) out vec4 slices2;
layout(location = 3) out vec4 slices3;

void main() {
  vec4 first = vec4(ceil(gl_FragCoord.z * 16.0) - 1.0);
  const vec4 k = vec4(0.0, 1.0, 2.0, 3.0);
  slices0 = weight * step(first, k);
  slices1 = weight * step(first, k + 4.0);
  slices2 = weight * step(first, k + 8.0);
  slices3 = weight * step(first, k + 12.0);
}
