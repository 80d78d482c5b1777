#version 450
#extension GL_GOOGLE_include_directive : require
// Marschner shading of every dense hair vertex (render/passes/hair_lighting_pass.hpp): the radiance
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
// the block is bound: every frame (docs/lavapipe.md#shader-recompiles-on-bind). Not a storage
// buffer either: lavapipe gathers a texel buffer's lanes at once
// (docs/lavapipe.md#texel-buffers-gather-storage-buffers-loop).
layout(set = 0, binding = 0) uniform usamplerBuffer lightingTexels;
const int kEyeTexel = 0;      // w = 1: eye position (metres); w = 0: unit direction towards the eye
const int kAmbientTexel = 1;  // rgb: ambient radiance × the groom's white-furnace albedo
const int kLightDirectionTexel = 2;                          // + light i: xyz unit vector towards it
const int kLightRadianceTexel = 2 + kHairLightingMaxLights;  // + light i: rgb perpendicular irradiance
const int kCountsTexel = 2 + 2 * kHairLightingMaxLights;     // x: lights, y: vertices per strand
const int kShadowsTexel = kCountsTexel + 1;                  // HairShadowUniforms: 6 per map, then the count
const int kShadowCountTexel = kShadowsTexel + 6 * 4;
const int kEnvironmentTexel = kShadowCountTexel + 1;  // 9: the environment's radiance as harmonics
// Then per θr sample k and band l, texel kEnvironmentBandsTexel + 3k + l: rgb = the TT and TRT
// lobes' weight of band l, a = the R lobe's (render/luts/hair_environment.hpp).
const int kEnvironmentBandsTexel = kEnvironmentTexel + 9;
const int kEnvironmentSamples = 65;  // kHairEnvironmentSamples, at θr = −π/2 + πk/64
// The hair's occlusion volume's origin and scale (HairVisibilityPlacement; w = 0: none).
const int kHairVisibilityTexel = kEnvironmentBandsTexel + 3 * kEnvironmentSamples;
#define HAIR_VISIBILITY_SET 0
#define HAIR_VISIBILITY_BINDING 16
#include "hair_visibility.glsl"

vec4 lightingVector(int texel) {
  return uintBitsToFloat(texelFetch(lightingTexels, texel));
}

#include "spherical_harmonics.glsl"

// The environment scattered towards the eye by the three lobes: each band of its radiance at the
// tangent, weighted by the lobes' band weights at the eye's θr, interpolated between samples.
vec3 environmentScattered(vec3 tangent, float sinThetaR, vec3 bodyColour) {
  vec4 harmonics[9];
  for (int k = 0; k < 9; ++k) harmonics[k] = lightingVector(kEnvironmentTexel + k);
  vec3 bands[3];
  harmonicBands(harmonics, tangent, bands[0], bands[1], bands[2]);
  float x = (asin(clamp(sinThetaR, -1.0, 1.0)) / kHairPi + 0.5) * float(kEnvironmentSamples - 1);
  int sample0 = clamp(int(x), 0, kEnvironmentSamples - 2);
  float f = clamp(x - float(sample0), 0.0, 1.0);
  vec3 result = vec3(0.0);
  for (int l = 0; l < 3; ++l) {
    int texel = kEnvironmentBandsTexel + 3 * sample0 + l;
    vec4 weights = mix(lightingVector(texel), lightingVector(texel + 3), f);
    result += (weights.rgb * bodyColour + weights.a) * bands[l];
  }
  return result;
}

// The maps that exist (kHairShadowMaps, a specialisation constant): hairShadowTransmittance looks
// up no slot after them.
HairShadowUniforms readShadows() {
  HairShadowUniforms shadows;
  for (uint m = 0u; m < kHairShadowMaps; ++m) {
    int texel = kShadowsTexel + 6 * int(m);
    shadows.maps[m].lightFromWorld =
        mat4(lightingVector(texel), lightingVector(texel + 1), lightingVector(texel + 2), lightingVector(texel + 3));
    shadows.maps[m].depth = lightingVector(texel + 4);
    shadows.maps[m].texels = lightingVector(texel + 5);
  }
  shadows.count = texelFetch(lightingTexels, kShadowCountTexel);
  return shadows;
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
layout(set = 0, binding = 15) uniform samplerBuffer hairStrandLooks;
#include "hair_strand_look.glsl"

// Half the angle between `tangent` and the tangent at vertex `other`.
float halfTurn(vec3 tangent, uint other) {
  return 0.5 * acos(clamp(dot(tangent, texelFetch(tangents, int(other)).xyz), -1.0, 1.0));
}

layout(local_size_x = 64) in;

void main() {
  if (gl_GlobalInvocationID.x >= texelFetch(shadeList, 3).x) return;
  uint vertex = texelFetch(shadeList, 4 + int(gl_GlobalInvocationID.x)).x;
  vec3 position = texelFetch(positions, int(vertex)).xyz;
  vec3 tangent = texelFetch(tangents, int(vertex)).xyz;
  uvec4 counts = texelFetch(lightingTexels, kCountsTexel);
  // The angle the tangent turns over this vertex's share of the strand, half a segment each way.
  uint along = vertex % counts.y;
  vec3 bodyColour = hairStrandColour(vertex / counts.y);
  float spread = 0.0;
  if (along > 0u) spread += halfTurn(tangent, vertex - 1u);
  if (along + 1u < counts.y) spread += halfTurn(tangent, vertex + 1u);

  vec4 eye = lightingVector(kEyeTexel);
  vec3 toEye = normalize(eye.xyz - eye.w * position);
  float shadow = hairShadowTransmittance(readShadows(), position);
  // The ambient term stands for light scattered many times inside the hair: all of it has
  // crossed fibres, so the strand's colour multiplies it whole.
  vec3 result = lightingVector(kAmbientTexel).rgb * bodyColour;
  if (counts.z != 0u)
    result += environmentScattered(tangent, dot(toEye, tangent), bodyColour) *
              hairFibreVisibility(lightingVector(kHairVisibilityTexel), lightingVector(kHairVisibilityTexel + 1), position);
  // Each light's vectors fetched where they are used: indexing an array of them by the loop's
  // counter made lavapipe load them lane by lane. And the test at the end of the loop: lavapipe
  // (Mesa 22.3) runs the body once more, every lane masked off, lookups and all, before a test at
  // the top ends the loop (docs/lavapipe.md#loops-test-at-the-end); the selection keeps a frame
  // without lights unlit.
  uint i = 0u;
  do {
    vec3 toLight = lightingVector(kLightDirectionTexel + int(i)).xyz;
    vec3 scattered = hairScattering(longitudinalLut, azimuthalLut, toLight, toEye, tangent, spread, bodyColour);
    vec3 lit = result + scattered * lightingVector(kLightRadianceTexel + int(i)).rgb * (i == 0u ? shadow : 1.0);
    result = i < counts.x ? lit : result;
    ++i;
  } while (i < counts.x);
  radiance[vertex] = vec4(result, shadow);
}
