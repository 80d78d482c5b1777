// What shaders/skin_irradiance.{vert,frag} share: the uniforms of one mesh instance's irradiance
// in texture space; mirrors IrradianceUniforms in render/passes/skin_diffusion_pass.cpp.
// Include after `#extension GL_GOOGLE_include_directive : require`.

const int kSkinIrradianceMaxLights = 4;  // SkinDiffusionPass::kMaxLights

#define HAIR_SHADOW_SET 0
#define HAIR_SHADOW_BINDING 2
#include "hair_shadows.glsl"
#include "light_depth_uniforms.glsl"
#define SURFACE_SHADOW_SET 0
#define SURFACE_SHADOW_BINDING 10
#include "surface_shadow_map.glsl"

layout(set = 0, binding = 0, std140) uniform SkinIrradiance {
  mat4 model;         // object → world
  mat4 normalMatrix;  // the inverse transpose of model's 3×3, in the upper left
  vec4 ambient;       // rgb, linear
  vec4 lightDirection[kSkinIrradianceMaxLights];  // xyz unit, towards the light
  vec4 lightRadiance[kSkinIrradianceMaxLights];   // rgb colour × intensity
  ivec4 counts;       // x lights, y 1 with a normal map
  vec4 scales;        // x millimetres per world unit
  HairShadowUniforms hairShadows;  // cast by light 0
  SurfaceShadow surfaceShadow;     // cast by light 0
} irradiance;
