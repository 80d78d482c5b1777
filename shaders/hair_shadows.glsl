// The hair shadows a shader receives (render/passes/hair_shadow_pass.hpp): up to 4 grooms' opacity
// or deep opacity maps, all cast by the frame's first light. Before including, declare
//   #define HAIR_SHADOW_SET <set> and HAIR_SHADOW_BINDING <first binding>
// and put a `HairShadowUniforms` member in a uniform block; then
//   hairShadowTransmittance(block.shadows, worldPosition)
// is the fraction of the first light that reaches the point through all the hair. The pipeline
// sets specialization constants 0 and 1 (HairShadowPass::shaderConstants): how many maps exist and
// their mode, so the lookups of absent maps and of the other mode are compiled out.
#include "opacity_shadow.glsl"

layout(constant_id = 0) const uint kHairShadowMaps = 0u;  // maps that exist, 0 to 4
layout(constant_id = 1) const uint kHairShadowMode = 0u;  // 0: 16-slice opacity shadow maps, 1: deep opacity maps

// Mirrors HairShadowUniforms (std140).
struct HairShadowUniforms {
  OpacityShadow maps[4];
  uvec4 count;  // x: slots in use; unused slots have κ = 0
};

layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 0) uniform sampler2DArray hairShadowOpacity0;
layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 1) uniform sampler2DArray hairShadowOpacity1;
layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 2) uniform sampler2DArray hairShadowOpacity2;
layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 3) uniform sampler2DArray hairShadowOpacity3;
layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 4) uniform sampler2D hairShadowFirstDepth0;
layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 5) uniform sampler2D hairShadowFirstDepth1;
layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 6) uniform sampler2D hairShadowFirstDepth2;
layout(set = HAIR_SHADOW_SET, binding = HAIR_SHADOW_BINDING + 7) uniform sampler2D hairShadowFirstDepth3;

// κ_g·opacity_g of one map at `world`, in the pipeline's mode.
float hairShadowExtinction(sampler2DArray opacity, sampler2D firstDepth, OpacityShadow map, vec3 world) {
  float o = kHairShadowMode == 1u ? deepOpacityMapOpacity(opacity, firstDepth, map, world)
                                  : opacityShadowMapOpacity(opacity, map, world);
  return map.depth.z * o;
}

// Product of the grooms' transmittances: exp(−Σ κ_g·opacity_g). Separate bindings rather than
// an array, so no descriptor-indexing feature is needed. Slots beyond shadows.count (grooms whose
// guides have not arrived yet) are looked up and then dropped by a select, not skipped by a
// branch: lavapipe compiles a shader again at every bind for a branch that only uniform values
// decide (docs/lavapipe.md), and the fur's vertex shader calls this.
float hairShadowTransmittance(HairShadowUniforms shadows, vec3 world) {
  uint count = shadows.count.x;
  float extinction = 0.0;
  if (kHairShadowMaps > 0u) {
    float e = hairShadowExtinction(hairShadowOpacity0, hairShadowFirstDepth0, shadows.maps[0], world);
    extinction += count > 0u ? e : 0.0;
  }
  if (kHairShadowMaps > 1u) {
    float e = hairShadowExtinction(hairShadowOpacity1, hairShadowFirstDepth1, shadows.maps[1], world);
    extinction += count > 1u ? e : 0.0;
  }
  if (kHairShadowMaps > 2u) {
    float e = hairShadowExtinction(hairShadowOpacity2, hairShadowFirstDepth2, shadows.maps[2], world);
    extinction += count > 2u ? e : 0.0;
  }
  if (kHairShadowMaps > 3u) {
    float e = hairShadowExtinction(hairShadowOpacity3, hairShadowFirstDepth3, shadows.maps[3], world);
    extinction += count > 3u ? e : 0.0;
  }
  return exp(-extinction);
}
