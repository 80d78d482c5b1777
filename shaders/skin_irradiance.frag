#version 450
#extension GL_GOOGLE_include_directive : require
// Irradiance and stretch in texture space (render/passes/skin_diffusion_pass.hpp): per texel
// E = ambient + Σ max(N·L, 0)·radiance (light 0 through the hair's and the surfaces' shadows) with coverage 1, and the millimetres of surface one texel
// spans along u and along v (the stretch map of d'Eon & Luebke, GPU Gems 3 §14.4.2, here as
// lengths rather than their inverses, so that texels off the mesh can hold 0).
#include "skin_irradiance.glsl"
#include "cotangent_frame.glsl"
#include "surface_shadows.glsl"

layout(set = 0, binding = 1) uniform sampler2D normalMap;  // tangent space, +Y up (OpenGL convention)

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec4 outIrradiance;  // rgb irradiance, a coverage
layout(location = 1) out vec2 outStretch;     // mm per texel along u, v

void main() {
  // One pixel is one texel, so dFdx(P) = ∂P/∂u / size: the world length of a texel along u. P is
  // affine over a triangle (w = 1, no perspective), so the derivative is exact and constant per
  // triangle, helper pixels included.
  outStretch = vec2(length(dFdx(inWorldPosition)), length(dFdy(inWorldPosition))) * irradiance.scales.x;

  vec3 normal = normalize(inWorldNormal);
  vec3 geometric = normal;
  if (irradiance.counts.y != 0) {
    vec3 mapped = texture(normalMap, inUv).xyz * 2.0 - 1.0;
    // The uv v axis runs down the image, so the map's +Y (up) is −v (as in shaders/surface.frag).
    mapped.y = -mapped.y;
    normal = normalize(cotangentFrame(normal, inWorldPosition, inUv) * mapped);
  }
  vec3 sum = irradiance.ambient.rgb;
  float shadow = hairShadowTransmittance(irradiance.hairShadows, inWorldPosition) *
                 surfaceShadowVisibility(irradiance.surfaceShadow, inWorldPosition, geometric,
                                         irradiance.lightDirection[0].xyz);
  for (int i = 0; i < irradiance.counts.x; ++i)
    sum += irradiance.lightRadiance[i].rgb * max(dot(normal, irradiance.lightDirection[i].xyz), 0.0) *
           (i == 0 ? shadow : 1.0);
  outIrradiance = vec4(sum, 1.0);
}
