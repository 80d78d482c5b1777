// The first light's depth map of the translucent surfaces (render/passes/light_depth_pass.hpp),
// in the frame set. Include after `#extension GL_GOOGLE_include_directive : require`.

#include "light_depth_uniforms.glsl"

layout(set = 0, binding = 9) uniform sampler2D lightDepthMap;
