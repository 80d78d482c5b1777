#version 450
// A directional light's visible disc (render/passes/light_disc_pass.hpp): its radiance where the
// pixel's ray lies within the disc's angular radius, added to the background, with the edge
// spread over one pixel's angle so the disc is antialiased without sample shading.

#extension GL_GOOGLE_include_directive : require
#include "light_disc.glsl"

layout(location = 0) in vec2 inNdc;
layout(location = 0) out vec4 outColor;

void main() {
  vec4 far = disc.ndcToDirection * vec4(inNdc, 1.0, 1.0);
  vec3 ray = normalize(far.xyz / far.w);
  // The angle between two unit vectors from their chord: exact near 0, where acos of the dot
  // product has no precision left.
  float angle = 2.0 * asin(min(0.5 * length(ray - disc.towardLight.xyz), 1.0));
  float coverage = clamp((disc.towardLight.w - angle) / max(fwidth(angle), 1e-7) + 0.5, 0.0, 1.0);
  outColor = vec4(disc.radiance.rgb * coverage, 0.0);
}
