#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred skin, step 2 (render/passes/deferred_skin_pass.hpp): a triangle over the
// screen at the far plane whose depth test (greater) passes only where shaders/skin_gbuffer.frag
// drew skin; lavapipe's fragment code tests the depth first and skips the shading of the 4 × 4
// blocks where it passes nowhere, so each skin pixel is lit once, as shaders/surface.frag lights
// a skin fragment (no translucency, pre-integrated diffuse). A compute pass would not do:
// lavapipe runs the lanes a branch masks off, so it would light every pixel of the screen.
#include "frame_uniforms.glsl"
#include "skin_lights.glsl"
#include "surface_shadows.glsl"

layout(set = 2, binding = 0) uniform sampler2D gPosition;   // xyz: metres; w: curvature (1/mm)
layout(set = 2, binding = 1) uniform sampler2D gGeometric;  // xyz: geometric normal; w: ρs
layout(set = 2, binding = 2) uniform sampler2D gDetail;     // xyz: normal-mapped normal
layout(set = 2, binding = 3) uniform sampler2D gAlbedo;     // rgb

layout(location = 0) out vec4 outColor;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position = texelFetch(gPosition, pixel, 0);
  vec4 geometric = texelFetch(gGeometric, pixel, 0);
  vec3 detail = texelFetch(gDetail, pixel, 0).xyz;
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  float shadow = hairShadowTransmittance(frame.hairShadows, position.xyz) *
                 surfaceShadowVisibility(frame.surfaceShadow, position.xyz, geometric.xyz, frame.lightDirection[0].xyz);
  float visibility = environmentVisibility(position.xyz, geometric.xyz);
  vec3 diffuse = skinAmbient(geometric.xyz, detail, position.w, visibility), specular;
  skinLights(position.xyz, geometric.xyz, detail, geometric.w, position.w, shadow, visibility, diffuse, specular);
  outColor = vec4(albedo * diffuse + specular, 1.0);
}
