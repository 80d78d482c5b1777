// A light's orthographic depth map's frame (render/passes/light_depth_pass.hpp): mirrors
// LightDepthUniforms (std140).
struct LightDepth {
  mat4 lightFromWorld;  // world → x, y ∈ [−1, 1] across the map, z ∈ [0, 1] behind its light-side plane
  vec4 scale;           // x: metres per unit of z; y: 1/resolution; z: texel size, metres; w: 1 when drawn
};
