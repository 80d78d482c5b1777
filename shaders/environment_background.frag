#version 450
// The environment seen behind the scene (render/passes/environment_pass.hpp): its radiance along
// the pixel's ray.
layout(set = 0, binding = 0) uniform samplerCube environment;  // linear RGB radiance
layout(push_constant) uniform Background {
  mat4 ndcToDirection;  // NDC → a direction from the eye: the inverse of projection × the view's rotation
} background;

layout(location = 0) in vec2 inNdc;
layout(location = 0) out vec4 outColor;

void main() {
  vec4 far = background.ndcToDirection * vec4(inNdc, 1.0, 1.0);
  outColor = vec4(textureLod(environment, far.xyz / far.w, 0.0).rgb, 1.0);
}
