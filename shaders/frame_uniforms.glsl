// Per-frame data shared by the surface shaders; mirrors FrameUniforms in
// render/passes/surface_scene.cpp.
// Include after `#extension GL_GOOGLE_include_directive : require`.
#define HAIR_SHADOW_SET 0
#define HAIR_SHADOW_BINDING 1
#include "hair_shadows.glsl"
#include "light_depth.glsl"

const int kMaxLights = 4;

layout(set = 0, binding = 0, std140) uniform FrameUniforms {
  mat4 viewProjection;
  vec4 cameraPosition;        // xyz metres
  vec4 ambient;               // rgb linear
  vec4 lightDirection[kMaxLights];  // xyz towards the light
  vec4 lightRadiance[kMaxLights];   // rgb colour × intensity
  ivec4 lightCount;           // x
  HairShadowUniforms hairShadows;  // cast by light 0
  LightDepth lightDepth;           // of light 0
} frame;
