#version 450
#extension GL_GOOGLE_include_directive : require
// Marschner shading of every dense hair vertex (render/passes/hair_lighting.hpp): the radiance
// towards the eye under the frame's directional lights, the first one attenuated by the hair
// shadows, plus the ambient term. The ribbons interpolate it along each segment.
#include "hair_shading.glsl"
#define HAIR_SHADOW_SET 0
#define HAIR_SHADOW_BINDING 6
#include "hair_shadows.glsl"

const int kHairLightingMaxLights = 4;

// The frame's lighting, read from a texel buffer of HairLightingPass's LightingUniforms (std140:
// every member a vec4 or made of them, so vec4 k is texel k). Not a uniform block: lavapipe
// (Mesa 22.3) folds uniform-block values that decide a branch or a loop's trip count (the light
// count, the shadow slots) into the shader, and does it again, with a full LLVM compile, each time
// the block is bound: every frame. Not a storage buffer either, as it was: read this way, nalu's
// hair lighting takes about 1 ms less on lavapipe.
layout(set = 0, binding = 0) uniform usamplerBuffer lightingTexels;

struct HairLighting {
  vec4 eye;                                     // w = 1: eye position (metres); w = 0: unit direction towards the eye
  vec4 ambient;                                 // rgb: ambient radiance × the groom's white-furnace albedo
  vec4 lightDirection[kHairLightingMaxLights];  // xyz: unit vector towards the light
  vec4 lightRadiance[kHairLightingMaxLights];   // rgb: perpendicular irradiance (colour × intensity)
  uvec4 counts;                                 // x: lights, y: vertices per strand
  HairShadowUniforms shadows;
};

vec4 lightingVector(int texel) {
  return uintBitsToFloat(texelFetch(lightingTexels, texel));
}

HairLighting readLighting() {
  HairLighting lighting;
  lighting.eye = lightingVector(0);
  lighting.ambient = lightingVector(1);
  for (int i = 0; i < kHairLightingMaxLights; ++i) {
    lighting.lightDirection[i] = lightingVector(2 + i);
    lighting.lightRadiance[i] = lightingVector(2 + kHairLightingMaxLights + i);
  }
  int texel = 2 + 2 * kHairLightingMaxLights;
  lighting.counts = texelFetch(lightingTexels, texel++);
  for (int m = 0; m < 4; ++m) {
    lighting.shadows.maps[m].lightFromWorld =
        mat4(lightingVector(texel), lightingVector(texel + 1), lightingVector(texel + 2), lightingVector(texel + 3));
    lighting.shadows.maps[m].depth = lightingVector(texel + 4);
    lighting.shadows.maps[m].texels = lightingVector(texel + 5);
    texel += 6;
  }
  lighting.shadows.count = texelFetch(lightingTexels, texel);
  return lighting;
}

layout(std430, set = 0, binding = 3) writeonly buffer Radiance { vec4 radiance[]; };   // rgb; a: shadow transmittance
layout(set = 0, binding = 4) uniform sampler2D longitudinalLut;
layout(set = 0, binding = 5) uniform sampler2DArray azimuthalLut;
// The strands and the shade list come in as texel buffers: lavapipe loads a storage buffer lane
// by lane at per-lane addresses, a texel fetch at once.
layout(set = 0, binding = 1) uniform samplerBuffer positions;  // xyz metres, w = t
layout(set = 0, binding = 2) uniform samplerBuffer tangents;   // xyz unit, root → tip
// The vertices to shade (HairPass: those with a segment that can be seen); the others keep
// whatever radiance they had, which no drawn segment uses. Words 0-2 are the indirect dispatch's
// workgroups, word 3 the vertices listed, then the list.
layout(set = 0, binding = 14) uniform usamplerBuffer shadeList;

// Half the angle between `tangent` and the tangent at vertex `other`.
float halfTurn(vec3 tangent, uint other) {
  return 0.5 * acos(clamp(dot(tangent, texelFetch(tangents, int(other)).xyz), -1.0, 1.0));
}

layout(local_size_x = 64) in;

void main() {
  if (gl_GlobalInvocationID.x >= texelFetch(shadeList, 3).x) return;
  uint vertex = texelFetch(shadeList, 4 + int(gl_GlobalInvocationID.x)).x;
  HairLighting lighting = readLighting();
  vec3 position = texelFetch(positions, int(vertex)).xyz;
  vec3 tangent = texelFetch(tangents, int(vertex)).xyz;
  // The angle the tangent turns over this vertex's share of the strand, half a segment each way.
  uint along = vertex % lighting.counts.y;
  float spread = 0.0;
  if (along > 0u) spread += halfTurn(tangent, vertex - 1u);
  if (along + 1u < lighting.counts.y) spread += halfTurn(tangent, vertex + 1u);

  vec3 toEye = normalize(lighting.eye.xyz - lighting.eye.w * position);
  float shadow = hairShadowTransmittance(lighting.shadows, position);
  vec3 result = lighting.ambient.rgb;
  for (uint i = 0u; i < lighting.counts.x; ++i) {
    vec3 scattered = hairScattering(longitudinalLut, azimuthalLut, lighting.lightDirection[i].xyz, toEye, tangent, spread);
    result += scattered * lighting.lightRadiance[i].rgb * (i == 0u ? shadow : 1.0);
  }
  radiance[vertex] = vec4(result, shadow);
}
