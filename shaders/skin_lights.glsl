// Skin under the frame's lights (render/passes/skin_shading.hpp), shared by the forward
// pass (shaders/surface.frag) and the deferred one (shaders/skin_gbuffer.frag, then
// shaders/skin_deferred.frag), so that both give a shaded point the same bits. Declares the skin
// table and the material block of set 1. Include after frame_uniforms.glsl.
#include "preintegrated_skin.glsl"

layout(set = 1, binding = 2) uniform sampler2DArray skinTable;  // skin: pre-integrated diffuse + Beckmann

// Mirrors MaterialUniforms in render/passes/surface_scene.cpp.
layout(set = 1, binding = 4, std140) uniform Material {
  vec4 baseColor;
  ivec4 flags;       // x: has normal map
  vec4 skin;         // x: roughness, y: ρs, z: the skin table's maxCurvature (1/mm)
  vec4 blur;         // rgb: skin, per channel, the weight of the geometric normal (blurred normals)
  vec4 extinction;   // rgb: σ, 1/m (translucency of materials other than skin); w: a Lambert sheet's transmission
  vec4 profile[6];   // skin: d'Eon's Gaussians, rgb weight, a variance (mm²)
  vec4 specularAlbedo[2];  // skin: the specular's albedo with ρs = 1 at N·V = 0, 1/7, …, 1
  // skin: rgb, the factor of the environment's band ℓ at curvature maxCurvature·(i/15)², at [16ℓ + i]
  vec4 ambientBands[48];
} draw;

// Skin's diffuse light from texture-space diffusion (ambient and lights already in it, blurred;
// render/passes/skin_diffusion_pass.hpp) rather than from the pre-integrated table.
layout(constant_id = 3) const bool kTextureSpaceDiffusion = false;

// The frame's ambient light and the environment's on skin of curvature 1/r (1/mm), per RGB, to
// multiply by the albedo: each band of the irradiance scaled as the pre-integrated profile
// scatters it at that curvature (render/luts/preintegrated_skin.hpp, preintegratedAmbientBands),
// and each channel looking up the environment with its own blurred normal, as the lights'
// pre-integrated diffuse does, so that red light wraps further round the skin's curves than blue.
// `visibility` is the share of the environment the hair leaves (environmentVisibility).
vec3 skinAmbient(vec3 geometric, vec3 detail, float curvature, float visibility) {
  float at = sqrt(clamp(curvature / draw.skin.z, 0.0, 1.0)) * 15.0;
  int below = min(int(at), 14);
  float t = at - float(below);
  vec3 scale[3];
  for (int l = 0; l < 3; ++l)
    scale[l] = mix(draw.ambientBands[16 * l + below].rgb, draw.ambientBands[16 * l + below + 1].rgb, t);
  vec3 ambient = frame.ambient.rgb * scale[0];
  if (frame.lightCount.y == 0) return ambient;
  vec3 lit;
  for (int c = 0; c < 3; ++c) {
    vec3 band0, band1, band2;
    environmentLightBands(normalize(mix(detail, geometric, draw.blur[c])), band0, band1, band2);
    lit[c] = scale[0][c] * band0[c] + scale[1][c] * band1[c] + scale[2][c] * band2[c];
  }
  return ambient + lit * visibility;
}

// Skin's specular reflection of the environment (a split sum): the radiance pre-filtered for its
// roughness in the mirror direction, times the BRDF's albedo at N·V, times the share `visibility`
// the hair leaves of the environment (its diffuse share: the lobe is broad); 0 without one.
vec3 skinEnvironmentSpecular(vec3 detail, vec3 toEye, float rhoS, float visibility) {
  if (frame.lightCount.y == 0) return vec3(0.0);
  float cosView = clamp(dot(detail, toEye), 0.0, 1.0);
  float at = cosView * 7.0;
  int below = min(int(at), 6);
  float albedo = mix(draw.specularAlbedo[below / 4][below % 4], draw.specularAlbedo[(below + 1) / 4][(below + 1) % 4],
                     at - float(below));
  // GGX of α = m stands in for Beckmann's m; the chain's level ℓ holds roughness ℓ/7, α = roughness².
  float level = sqrt(draw.skin.x) * (kEnvironmentSpecularLevels - 1.0);
  return rhoS * albedo * textureLod(environmentSpecular, reflect(-toEye, detail), level).rgb * visibility;
}

// Adds the lights' diffuse light (per RGB, to multiply by the albedo) to `diffuse` and sets
// `specular` to their specular radiance, at `position` (metres) with the geometric and the detail
// (normal-mapped) normals, ρs scaled by the specular map, and curvature 1/r in 1/mm. The first
// light is attenuated by `shadow` (the hair's and the surfaces' shadows), the environment's
// reflection by `visibility` (environmentVisibility).
void skinLights(vec3 position, vec3 geometric, vec3 detail, float rhoS, float curvature, float shadow,
                float visibility, inout vec3 diffuse, out vec3 specular) {
  vec3 toEye = normalize(frame.cameraPosition.xyz - position);
  vec3 normalR = normalize(mix(detail, geometric, draw.blur.r));
  vec3 normalG = normalize(mix(detail, geometric, draw.blur.g));
  vec3 normalB = normalize(mix(detail, geometric, draw.blur.b));
  specular = vec3(0.0);
  // The test at the end: lavapipe (Mesa 22.3) runs a loop's body once more, every lane masked off,
  // lookups and all, before a test at the top ends the loop
  // (docs/lavapipe.md#loops-test-at-the-end). The selections keep a frame without lights unlit.
  int i = 0;
  do {
    vec3 toLight = frame.lightDirection[i].xyz;
    vec3 radiance = frame.lightRadiance[i].rgb * (i == 0 ? shadow : 1.0);
    vec3 lit = diffuse;
    if (!kTextureSpaceDiffusion) {
      vec3 scattered = vec3(preintegratedSkinDiffuse(skinTable, 0, dot(normalR, toLight), curvature, draw.skin.z),
                            preintegratedSkinDiffuse(skinTable, 1, dot(normalG, toLight), curvature, draw.skin.z),
                            preintegratedSkinDiffuse(skinTable, 2, dot(normalB, toLight), curvature, draw.skin.z));
      lit += radiance * scattered;
    }
    vec3 shone = specular + radiance * kelemenSzirmayKalos(skinTable, detail, toLight, toEye, draw.skin.x, rhoS) *
                                max(dot(detail, toLight), 0.0);
    bool on = i < frame.lightCount.x;
    diffuse = on ? lit : diffuse;
    specular = on ? shone : specular;
    ++i;
  } while (i < frame.lightCount.x);
  specular += skinEnvironmentSpecular(detail, toEye, rhoS, visibility);
}
