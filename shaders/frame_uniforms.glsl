// Per-frame data shared by the surface shaders; mirrors FrameUniforms in
// render/passes/surface_scene.cpp.
// Include after `#extension GL_GOOGLE_include_directive : require`.
#define HAIR_SHADOW_SET 0
#define HAIR_SHADOW_BINDING 1
#include "hair_shadows.glsl"
#include "light_depth.glsl"
#define SURFACE_SHADOW_SET 0
#define SURFACE_SHADOW_BINDING 11
#include "surface_shadow_map.glsl"
#define HAIR_VISIBILITY_SET 0
#define HAIR_VISIBILITY_BINDING 13
#include "hair_visibility.glsl"

const int kMaxLights = 4;

layout(set = 0, binding = 0, std140) uniform FrameUniforms {
  mat4 viewProjection;
  vec4 cameraPosition;        // xyz metres
  vec4 ambient;               // rgb linear
  vec4 lightDirection[kMaxLights];  // xyz towards the light
  vec4 lightRadiance[kMaxLights];   // rgb colour × intensity
  ivec4 lightCount;           // x: lights; y: 1 where an environment lights the scene
  HairShadowUniforms hairShadows;  // cast by light 0
  LightDepth lightDepth;           // of light 0
  // The environment's irradiance over π as nine spherical harmonics (rgb), in the order of
  // render/environment/spherical_harmonics.hpp.
  vec4 environmentIrradiance[9];
  SurfaceShadow surfaceShadow;  // cast by light 0
  // Where the hair's occlusion volume lies (HairVisibilityPlacement): w = 0 without one.
  vec4 hairVisibilityOrigin;
  vec4 hairVisibilityScale;
} frame;

// The environment's radiance pre-filtered for GGX roughness level/7 at each mip level
// (render/environment/specular_chain.hpp); black without an environment.
layout(set = 0, binding = 10) uniform samplerCube environmentSpecular;
const float kEnvironmentSpecularLevels = 8.0;

// What a white Lambertian surface facing `normal` (unit) shows of the environment, band by band
// (ℓ = 0, 1, 2): 0 without one.
void environmentLightBands(vec3 normal, out vec3 band0, out vec3 band1, out vec3 band2) {
  vec3 n = normal;
  // The real harmonics' normalisations, as on the CPU.
  band0 = frame.environmentIrradiance[0].rgb * 0.282094792;
  band1 = (frame.environmentIrradiance[1].rgb * n.y + frame.environmentIrradiance[2].rgb * n.z +
           frame.environmentIrradiance[3].rgb * n.x) * 0.488602512;
  band2 = (frame.environmentIrradiance[4].rgb * (n.x * n.y) + frame.environmentIrradiance[5].rgb * (n.y * n.z) +
           frame.environmentIrradiance[7].rgb * (n.x * n.z)) * 1.092548431 +
          frame.environmentIrradiance[6].rgb * (0.315391565 * (3.0 * n.z * n.z - 1.0)) +
          frame.environmentIrradiance[8].rgb * (0.546274215 * (n.x * n.x - n.y * n.y));
  // Selected, not branched on: lavapipe compiles a shader again at every bind where a branch
  // depends on a uniform alone (docs/lavapipe.md, "Shader recompiles on bind").
  bvec3 lit = bvec3(frame.lightCount.y != 0);
  band0 = mix(vec3(0.0), band0, lit);
  band1 = mix(vec3(0.0), band1, lit);
  band2 = mix(vec3(0.0), band2, lit);
}

// The share of the environment's diffuse light the hair leaves to a surface at `position` facing
// `normal` (render/passes/hair_density_pass.hpp).
float environmentVisibility(vec3 position, vec3 normal) {
  return hairSurfaceVisibility(frame.hairVisibilityOrigin, frame.hairVisibilityScale, position, normal);
}

vec3 environmentLight(vec3 normal) {
  vec3 band0, band1, band2;
  environmentLightBands(normal, band0, band1, band2);
  return band0 + band1 + band2;
}
