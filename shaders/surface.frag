#version 450
#extension GL_GOOGLE_include_directive : require
// Surfaces with an albedo texture and a tangent-space normal map, Lambert or skin (see
// render/passes/surface_pass.hpp); the first light is attenuated by the hair shadows.
#include "frame_uniforms.glsl"
#include "preintegrated_skin.glsl"

layout(set = 1, binding = 0) uniform sampler2D albedoMap;  // sRGB, decoded by the sampler
layout(set = 1, binding = 1) uniform sampler2D normalMap;  // tangent space, +Y up (OpenGL convention)
layout(set = 1, binding = 2) uniform sampler2D specularMap;  // skin: red scales ρs
layout(set = 1, binding = 3) uniform sampler2DArray skinTable;  // skin: pre-integrated diffuse + Beckmann
layout(set = 1, binding = 4) uniform sampler2D diffusedIrradiance;  // texture-space skin: blurred E at the uv

// Mirrors MaterialUniforms in render/passes/surface_pass.cpp.
layout(set = 1, binding = 5, std140) uniform Material {
  vec4 baseColor;
  ivec4 flags;       // x: has normal map
  vec4 skin;         // x: roughness, y: ρs, z: the skin table's maxCurvature (1/mm)
  vec4 blur;         // rgb: skin, per channel, the weight of the geometric normal (blurred normals)
  vec4 extinction;   // rgb: σ, 1/m (translucency of materials other than skin)
  vec4 profile[6];   // skin: d'Eon's Gaussians, rgb weight, a variance (mm²)
} draw;
#include "translucency.glsl"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in float inCurvature;  // 1/r, 1/mm
layout(location = 4) in vec3 inObjectPosition;  // mesh units
layout(location = 5) flat in vec4 inObjectTowardLight;  // xyz: light 0's direction, mesh units per metre; w: metres per unit
layout(location = 0) out vec4 outColor;

layout(constant_id = 2) const bool kSkin = false;  // the pipeline's shading: skin or Lambert
// Skin's diffuse light from texture-space diffusion (ambient and lights already in it, blurred;
// render/passes/skin_diffusion.hpp) rather than from the pre-integrated table.
layout(constant_id = 3) const bool kTextureSpaceDiffusion = false;

// Diffuse (per RGB, to multiply by the albedo) and specular radiance of skin under the lights.
// Of light that crossed `thickness` metres: skin's diffusion profile summed over the plane of
// entry points, Σ w_i·exp(−d²/2v_i) (render/luts/skin_profile.hpp, SkinProfile::transmittance);
// any other material exp(−σ·d) per channel (Beer–Lambert, the seed method's I = I0·exp(−σd)).
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

void shadeSkin(vec3 geometric, vec3 detail, float hairShadow, out vec3 diffuse, out vec3 specular) {
  vec3 toEye = normalize(frame.cameraPosition.xyz - inWorldPosition);
  vec3 normalR = normalize(mix(detail, geometric, draw.blur.r));
  vec3 normalG = normalize(mix(detail, geometric, draw.blur.g));
  vec3 normalB = normalize(mix(detail, geometric, draw.blur.b));
  float rhoS = draw.skin.y * texture(specularMap, inUv).r;
  diffuse = (kTextureSpaceDiffusion ? texture(diffusedIrradiance, inUv).rgb : frame.ambient.rgb) +
            translucency(geometric);
  specular = vec3(0.0);
  for (int i = 0; i < frame.lightCount.x; ++i) {
    vec3 toLight = frame.lightDirection[i].xyz;
    vec3 radiance = frame.lightRadiance[i].rgb * (i == 0 ? hairShadow : 1.0);
    if (!kTextureSpaceDiffusion) {
      vec3 scattered = vec3(preintegratedSkinDiffuse(skinTable, 0, dot(normalR, toLight), inCurvature, draw.skin.z),
                            preintegratedSkinDiffuse(skinTable, 1, dot(normalG, toLight), inCurvature, draw.skin.z),
                            preintegratedSkinDiffuse(skinTable, 2, dot(normalB, toLight), inCurvature, draw.skin.z));
      diffuse += radiance * scattered;
    }
    specular += radiance * kelemenSzirmayKalos(skinTable, detail, toLight, toEye, draw.skin.x, rhoS) *
                max(dot(detail, toLight), 0.0);
  }
}

// Tangent frame from screen-space derivatives of position and uv, so meshes need no stored
// tangents (Schüler, "Normal Mapping Without Precomputed Tangents", 2013, after ShaderX5).
mat3 cotangentFrame(vec3 normal, vec3 position, vec2 uv) {
  vec3 dp1 = dFdx(position);
  vec3 dp2 = dFdy(position);
  vec2 duv1 = dFdx(uv);
  vec2 duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, normal);
  vec3 dp1perp = cross(normal, dp1);
  vec3 tangent = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 bitangent = dp2perp * duv1.y + dp1perp * duv2.y;
  // The exact gradients divide by det = dp1·dp2perp; only its sign matters once we normalise.
  // It is negative under Vulkan's downward framebuffer Y, so it cannot be dropped.
  float det = dot(dp1, dp2perp);
  float scale = (det < 0.0 ? -1.0 : 1.0) *
                inversesqrt(max(max(dot(tangent, tangent), dot(bitangent, bitangent)), 1e-20));
  return mat3(tangent * scale, bitangent * scale, normal);
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
  vec3 albedo = texture(albedoMap, inUv).rgb * draw.baseColor.rgb;
  float hairShadow = hairShadowTransmittance(frame.hairShadows, inWorldPosition);
  if (kSkin) {
    vec3 diffuse, specular;
    shadeSkin(geometric, normal, hairShadow, diffuse, specular);
    outColor = vec4(albedo * diffuse + specular, 1.0);
    return;
  }
  vec3 irradiance = frame.ambient.rgb + translucency(geometric);
  for (int i = 0; i < frame.lightCount.x; ++i)
    irradiance += frame.lightRadiance[i].rgb * max(dot(normal, frame.lightDirection[i].xyz), 0.0) *
                  (i == 0 ? hairShadow : 1.0);
  outColor = vec4(albedo * irradiance, 1.0);
}
