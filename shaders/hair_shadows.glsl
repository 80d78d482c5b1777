// The hair shadows a shader receives (render/passes/hair_shadows.hpp): up to 4 grooms' opacity
// or deep opacity maps, all cast by the frame's first light. Before including, declare
//   #define HAIR_SHADOW_SET <set> and HAIR_SHADOW_BINDING <first binding>
// and put a `HairShadowUniforms` member in a uniform block; then
//   hairShadowTransmittance(block.shadows, worldPosition)
// is the fraction of the first light that reaches the point through all the hair.
#include "opacity_shadow.glsl"

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

// Product of the grooms' transmittances: exp(−Σ κ_g·opacity_g). Separate bindings rather than
// an array, so no descriptor-indexing feature is needed.
float hairShadowTransmittance(HairShadowUniforms shadows, vec3 world) {
  float transmittance = 1.0;
  uint count = shadows.count.x;
  if (count > 0u)
    transmittance *= opacityShadowTransmittance(hairShadowOpacity0, hairShadowFirstDepth0, shadows.maps[0], world);
  if (count > 1u)
    transmittance *= opacityShadowTransmittance(hairShadowOpacity1, hairShadowFirstDepth1, shadows.maps[1], world);
  if (count > 2u)
    transmittance *= opacityShadowTransmittance(hairShadowOpacity2, hairShadowFirstDepth2, shadows.maps[2], world);
  if (count > 3u)
    transmittance *= opacityShadowTransmittance(hairShadowOpacity3, hairShadowFirstDepth3, shadows.maps[3], world);
  return transmittance;
}
