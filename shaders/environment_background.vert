#version 450
// One triangle over the screen at the far plane (render/passes/environment_pass.hpp), behind
// anything drawn before it; passes the NDC position on, from which the fragment finds its ray.
layout(location = 0) out vec2 outNdc;
void main() {
  outNdc = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2) * 2.0 - 1.0;
  gl_Position = vec4(outNdc, 1.0, 1.0);
}
