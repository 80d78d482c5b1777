#version 450
// The first light's depth map of the translucent surfaces (render/passes/light_depth_pass.hpp):
// positions only, orthographic, z = depth behind the bounds' light-side plane in [0, 1].

layout(location = 0) in vec3 inPosition;

layout(push_constant) uniform Draw {
  mat4 lightFromObject;
} draw;

void main() {
  gl_Position = draw.lightFromObject * vec4(inPosition, 1.0);
}
