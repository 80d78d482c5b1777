// Light 0's depth map of every surface (render/passes/surface_shadow_pass.hpp): its uniforms and
// its two samplers, at set SURFACE_SHADOW_SET, bindings SURFACE_SHADOW_BINDING and the next. Read
// by shaders/surface_shadows.glsl. Include after light_depth_uniforms.glsl.

#if !defined(SURFACE_SHADOW_SET) || !defined(SURFACE_SHADOW_BINDING)
#error "define SURFACE_SHADOW_SET and SURFACE_SHADOW_BINDING before including surface_shadow_map.glsl"
#endif

// Mirrors SurfaceShadowUniforms (std140).
struct SurfaceShadow {
  LightDepth map;  // lightFromWorld; scale.x: metres per map unit, z: texel metres, w: 1 when drawn
  vec4 penumbra;   // x: tan α; y: widest search, map units; z: smallest filter radius, map units; w: normal offset, m
};

layout(set = SURFACE_SHADOW_SET, binding = SURFACE_SHADOW_BINDING) uniform sampler2D surfaceShadowDepth;  // nearest
layout(set = SURFACE_SHADOW_SET, binding = SURFACE_SHADOW_BINDING + 1) uniform sampler2DShadow surfaceShadowCompare;
