#version 450
#extension GL_GOOGLE_include_directive : require
// Surfaces with an albedo texture and a tangent-space normal map, Lambert or skin (see
// render/passes/surface_pass.hpp); the first light is attenuated by the hair's shadows and the
// surfaces' own.
#include "frame_uniforms.glsl"
#include "cotangent_frame.glsl"

// rgb: sRGB, decoded by the sampler; a: the specular map (skin: scales ρs)
layout(set = 1, binding = 0) uniform sampler2D albedoMap;
layout(set = 1, binding = 1) uniform sampler2D normalMap;  // tangent space, +Y up (OpenGL convention)
layout(set = 1, binding = 3) uniform sampler2D diffusedIrradiance;  // texture-space skin: blurred E at the uv
#include "skin_lights.glsl"
#include "translucency.glsl"
#include "surface_shadows.glsl"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in float inCurvature;  // 1/r, 1/mm
layout(location = 4) in vec3 inObjectPosition;  // mesh units
layout(location = 5) flat in vec4 inObjectTowardLight;  // xyz: light 0's direction, mesh units per metre; w: metres per unit
layout(location = 0) out vec4 outColor;

layout(constant_id = 2) const bool kSkin = false;  // the pipeline's shading: skin or Lambert

// Of light that crossed `thickness` metres: skin's diffusion profile summed over the plane of entry
// points, Σ w_i·exp(−d²/2v_i) (render/luts/skin_profile.hpp, SkinProfile::transmittance); any other
// material exp(−σ·d) per channel (Beer–Lambert, the voxelized-translucency paper's
// I = I0·exp(−σd)).
vec3 transmittance(float thickness) {
  if (!kSkin) return exp(-draw.extinction.rgb * thickness);
  float mm2 = thickness * thickness * 1e6;
  vec3 sum = vec3(0.0);
  for (int i = 0; i < 6; ++i) sum += draw.profile[i].rgb * exp(-mm2 / (2.0 * draw.profile[i].a));
  return sum;
}

// Light 0 through the surface: nothing without translucency (compiled out).
vec3 translucency(vec3 geometric) {
  if (kTranslucency == 0u || frame.lightCount.x == 0 || frame.lightDepth.scale.w == 0.0) return vec3(0.0);
  float thickness = translucentThickness(inWorldPosition, inObjectPosition, inObjectTowardLight.xyz,
                                         inObjectTowardLight.w);
  return translucentLight(transmittance(thickness), geometric);
}

// Diffuse (per RGB, to multiply by the albedo) and specular radiance of skin under the lights,
// with ρs scaled by the specular map.
void shadeSkin(vec3 geometric, vec3 detail, float specularMap, float shadow, out vec3 diffuse,
               out vec3 specular) {
  float rhoS = draw.skin.y * specularMap;
  float visibility = environmentVisibility(inWorldPosition, geometric);
  diffuse = (kTextureSpaceDiffusion ? texture(diffusedIrradiance, inUv).rgb
                                   : skinAmbient(geometric, detail, inCurvature, visibility)) +
            translucency(geometric);
  skinLights(inWorldPosition, geometric, detail, rhoS, inCurvature, shadow, visibility, diffuse, specular);
}

void main() {
  vec3 normal = normalize(inWorldNormal);
  if (!gl_FrontFacing) normal = -normal;
  vec3 geometric = normal;
  if (draw.flags.x != 0) {
    vec3 mapped = texture(normalMap, inUv).xyz * 2.0 - 1.0;
    // The uv v axis runs down the image, so the map's +Y (up) is −v.
    mapped.y = -mapped.y;
    normal = normalize(cotangentFrame(normal, inWorldPosition, inUv) * mapped);
  }
  vec4 albedoTexel = texture(albedoMap, inUv);
  vec3 albedo = albedoTexel.rgb * draw.baseColor.rgb;
  float shadow = hairShadowTransmittance(frame.hairShadows, inWorldPosition) *
                 surfaceShadowVisibility(frame.surfaceShadow, inWorldPosition, geometric, frame.lightDirection[0].xyz);
  if (kSkin) {
    vec3 diffuse, specular;
    shadeSkin(geometric, normal, albedoTexel.a, shadow, diffuse, specular);
    outColor = vec4(albedo * diffuse + specular, 1.0);
    return;
  }
  vec3 irradiance = frame.ambient.rgb + environmentLight(normal) * environmentVisibility(inWorldPosition, geometric) +
                    translucency(geometric);
  // A thin sheet passes `transmission` of the light from behind it and reflects the rest.
  float transmission = draw.extinction.w;
  for (int i = 0; i < frame.lightCount.x; ++i) {
    float cosine = dot(normal, frame.lightDirection[i].xyz);
    irradiance += frame.lightRadiance[i].rgb *
                  ((1.0 - transmission) * max(cosine, 0.0) + transmission * max(-cosine, 0.0)) *
                  (i == 0 ? shadow : 1.0);
  }
  outColor = vec4(albedo * irradiance, 1.0);
}
