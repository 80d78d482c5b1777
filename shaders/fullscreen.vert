#version 450
// One triangle that covers the screen; uv runs 0..1 over the visible part.
layout(location = 0) out vec2 outUv;
void main() {
  vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  outUv = uv;
  gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
