#version 450
#extension GL_GOOGLE_include_directive : require
// Lambert surface with an albedo texture and a tangent-space normal map; the first light is
// attenuated by the hair shadows.
#include "frame_uniforms.glsl"

layout(set = 1, binding = 0) uniform sampler2D albedoMap;  // sRGB, decoded by the sampler
layout(set = 1, binding = 1) uniform sampler2D normalMap;  // tangent space, +Y up (OpenGL convention)

layout(push_constant) uniform Draw {
  mat4 model;
  vec4 baseColor;
  ivec4 flags;
} draw;

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec4 outColor;

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
  if (draw.flags.x != 0) {
    vec3 mapped = texture(normalMap, inUv).xyz * 2.0 - 1.0;
    // The uv v axis runs down the image, so the map's +Y (up) is −v.
    mapped.y = -mapped.y;
    normal = normalize(cotangentFrame(normal, inWorldPosition, inUv) * mapped);
  }
  vec3 albedo = texture(albedoMap, inUv).rgb * draw.baseColor.rgb;
  vec3 irradiance = frame.ambient.rgb;
  float hairShadow = hairShadowTransmittance(frame.hairShadows, inWorldPosition);
  for (int i = 0; i < frame.lightCount.x; ++i)
    irradiance += frame.lightRadiance[i].rgb * max(dot(normal, frame.lightDirection[i].xyz), 0.0) *
                  (i == 0 ? hairShadow : 1.0);
  outColor = vec4(albedo * irradiance, 1.0);
}
