#version 450
// The screen rectangle that holds a light's disc (render/passes/light_disc_pass.hpp), drawn as a
// 4-vertex triangle strip; passes the NDC position on, from which the fragment finds its ray.

#extension GL_GOOGLE_include_directive : require
#include "light_disc.glsl"

layout(location = 0) out vec2 outNdc;

void main() {
  vec2 corner = vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1);
  outNdc = mix(disc.bounds.xy, disc.bounds.zw, corner);
  gl_Position = vec4(outNdc, 1.0, 1.0);  // the far plane: behind anything drawn before it
}
