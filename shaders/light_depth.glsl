// The first light's depth map of the translucent surfaces (render/passes/light_depth_pass.hpp),
// in the frame set. Include after `#extension GL_GOOGLE_include_directive : require`.

// Mirrors LightDepthUniforms (std140).
struct LightDepth {
  mat4 lightFromWorld;  // world → x, y ∈ [−1, 1] across the map, z ∈ [0, 1] behind its light-side plane
  vec4 scale;           // x: metres per unit of z; y: 1/resolution; z: texel size, metres; w: 1 when drawn
};

layout(set = 0, binding = 9) uniform sampler2D lightDepthMap;
