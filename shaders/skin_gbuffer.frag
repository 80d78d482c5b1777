#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred skin, step 1 (render/passes/deferred_skin_pass.hpp): what shaders/surface.frag
// computes of a skin fragment before its lights, written to four RGBA32F targets so that
// shaders/skin_deferred.frag finishes it, once per pixel, with the same bits. The parts that
// need screen derivatives (the normal map's frame, the textures' mip levels) are done here.
#include "frame_uniforms.glsl"
#include "cotangent_frame.glsl"

// rgb: sRGB, decoded by the sampler; a: the specular map, scales ρs
layout(set = 1, binding = 0) uniform sampler2D albedoMap;
layout(set = 1, binding = 1) uniform sampler2D normalMap;  // tangent space, +Y up (OpenGL convention)
#include "skin_lights.glsl"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in float inCurvature;  // 1/r, 1/mm
layout(location = 0) out vec4 outPosition;   // xyz: metres; w: curvature (1/mm)
layout(location = 1) out vec4 outGeometric;  // xyz: the geometric normal; w: ρs
layout(location = 2) out vec4 outDetail;     // xyz: the normal-mapped normal
layout(location = 3) out vec4 outAlbedo;     // rgb

void main() {
  vec3 normal = normalize(inWorldNormal);
  if (!gl_FrontFacing) normal = -normal;
  vec3 geometric = normal;
  // As surface.frag, but the normal map chosen by a select where surface.frag branches: lavapipe
  // compiles the shader again at every bind when a branch depends on few enough uniform values
  // alone (the material's flag is this shader's only one), to fold them in.
  vec3 mapped = texture(normalMap, inUv).xyz * 2.0 - 1.0;
  // The uv v axis runs down the image, so the map's +Y (up) is −v.
  mapped.y = -mapped.y;
  vec3 detail = normalize(cotangentFrame(normal, inWorldPosition, inUv) * mapped);
  normal = draw.flags.x != 0 ? detail : normal;
  outPosition = vec4(inWorldPosition, inCurvature);
  vec4 albedo = texture(albedoMap, inUv);
  outGeometric = vec4(geometric, draw.skin.y * albedo.a);
  outDetail = vec4(normal, 0.0);
  outAlbedo = vec4(albedo.rgb * draw.baseColor.rgb, 0.0);
}
