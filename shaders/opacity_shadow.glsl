// Hair self-shadowing lookup (render/passes/opacity_shadow_map_pass.hpp): the transmittance
// exp(−κ·opacity) towards the light at a world position (Kim & Neumann 2001, eq. 1), from an
// opacity shadow map (16 slices, linear between slices: Kim & Neumann 2001 §3.3) or a deep
// opacity map (first-hair depth + 4 layers: Yuksel & Keyser 2008 §3.3), or, as a cost baseline,
// a binary depth shadow map of the first hair (lit or not, no opacity). Bind the pass's
// opacityView() as a sampler2DArray and firstDepthView() as a sampler2D, both with its sampler(),
// and its uniforms() as an OpacityShadow, e.g.
//   layout(set = 1, binding = 0) uniform sampler2DArray hairOpacity;
//   layout(set = 1, binding = 1) uniform sampler2D hairFirstDepth;
//   ... float t = opacityShadowTransmittance(hairOpacity, hairFirstDepth, frame.hairShadow, p);

// Mirrors OpacityShadowUniforms (std140 and std430 alike).
struct OpacityShadow {
  mat4 lightFromWorld;  // world → (x, y ∈ [−1, 1] across the map, z = depth/2R ∈ [0, 1])
  vec4 depth;           // x slices or layers (16, 4, 1), y their spacing in z (or the depth shadow map's
                        // bias), z κ, w mode (0 OSM, 1 DOM, 2 depth shadow map)
  vec4 texels;          // x resolution, y 1/resolution, z 2R (metres), w texel size (metres)
};

// Channel k (0..15) of an opacity map: layer k/4, component k%4.
float opacityShadowSlice(sampler2DArray map, vec2 uv, int k) {
  return texture(map, vec3(uv, float(k >> 2)))[k & 3];
}

// Opacity shadow map: slice k holds the opacity in front of z = (k + 1)/16, the plane z = 0 holds
// none; the opacity at z is linear between the two planes around it, and 16 slices' worth
// beyond the last. Bilinear across texels (the sampler).
float opacityShadowMapOpacity(sampler2DArray slices, OpacityShadow osm, vec3 world) {
  vec3 p = (osm.lightFromWorld * vec4(world, 1.0)).xyz;
  float s = clamp(p.z, 0.0, 1.0) * osm.depth.x;  // in slice spacings from the light-side plane
  int below = int(floor(s));                      // planes `below` and `below + 1`
  vec2 uv = p.xy * 0.5 + 0.5;
  // Both lookups at every point, the cases chosen after: no lookup inside a branch, which lavapipe
  // runs slower.
  int last = int(osm.depth.x) - 1;
  int farSlice = min(below, last);
  float far = opacityShadowSlice(slices, uv, farSlice);
  float near = opacityShadowSlice(slices, uv, max(farSlice - 1, 0));
  float between = mix(below == 0 ? 0.0 : near, far, s - float(below));
  return below > last ? far : between;
}

// One texel of a deep opacity map at depth z: 0 at the texel's first hair z0, layer k at
// z0 + (k + 1)·Δ for k = 0..2, linear in between. The last layer holds all the hair beyond
// z0 + 3Δ without saying where it ends, so it is spread evenly to the far side of the bounding
// sphere (z = 1): points behind the hair get all of it.
float deepOpacityTexel(sampler2DArray layers, sampler2D firstDepth, OpacityShadow osm, ivec2 texel, float z) {
  int size = int(osm.texels.x);
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(size)))) return 0.0;
  float z0 = texelFetch(firstDepth, texel, 0).r;
  float r = (z - z0) / osm.depth.y;  // in layer spacings
  if (r <= 0.0) return 0.0;
  vec4 values = texelFetch(layers, ivec3(texel, 0), 0);
  if (r >= 3.0) {
    float start = z0 + 3.0 * osm.depth.y;
    return mix(values.z, values.w, start < 1.0 ? clamp((z - start) / (1.0 - start), 0.0, 1.0) : 1.0);
  }
  int below = int(floor(r));
  float near = below == 0 ? 0.0 : values[below - 1];
  return mix(near, values[below], r - float(below));
}

// Deep opacity map: each of the 4 texels around the point is interpolated in depth with its own
// z0, then the four are blended bilinearly (a hardware bilinear fetch would mix layers that
// start at different depths).
float deepOpacityMapOpacity(sampler2DArray layers, sampler2D firstDepth, OpacityShadow osm, vec3 world) {
  vec3 p = (osm.lightFromWorld * vec4(world, 1.0)).xyz;
  vec2 position = (p.xy * 0.5 + 0.5) * osm.texels.x - 0.5;  // texel centres on integers
  vec2 base = floor(position);
  vec2 f = position - base;
  ivec2 i = ivec2(base);
  float z = clamp(p.z, 0.0, 1.0);
  return mix(mix(deepOpacityTexel(layers, firstDepth, osm, i, z),
                 deepOpacityTexel(layers, firstDepth, osm, i + ivec2(1, 0), z), f.x),
             mix(deepOpacityTexel(layers, firstDepth, osm, i + ivec2(0, 1), z),
                 deepOpacityTexel(layers, firstDepth, osm, i + ivec2(1, 1), z), f.x),
             f.y);
}

// Depth shadow map: 1 (lit) where z is at most the bias (osm.depth.y) behind the texel's first
// hair z0, else 0; outside the map, lit. 2×2 PCF: the 4 texels around the point, each compared
// on its own, blended bilinearly.
float depthShadowTexel(sampler2D firstDepth, OpacityShadow osm, ivec2 texel, float z) {
  int size = int(osm.texels.x);
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(size)))) return 1.0;
  return z <= texelFetch(firstDepth, texel, 0).r + osm.depth.y ? 1.0 : 0.0;
}

float depthShadowMapTransmittance(sampler2D firstDepth, OpacityShadow osm, vec3 world) {
  vec3 p = (osm.lightFromWorld * vec4(world, 1.0)).xyz;
  vec2 position = (p.xy * 0.5 + 0.5) * osm.texels.x - 0.5;  // texel centres on integers
  vec2 base = floor(position);
  vec2 f = position - base;
  ivec2 i = ivec2(base);
  float z = clamp(p.z, 0.0, 1.0);
  return mix(mix(depthShadowTexel(firstDepth, osm, i, z), depthShadowTexel(firstDepth, osm, i + ivec2(1, 0), z), f.x),
             mix(depthShadowTexel(firstDepth, osm, i + ivec2(0, 1), z),
                 depthShadowTexel(firstDepth, osm, i + ivec2(1, 1), z), f.x),
             f.y);
}

// Opacity towards the light at `world`, in the map's mode. A depth shadow map holds no opacity:
// it gives the shadowed fraction 1 − T of its 2×2 taps instead (0 lit, 1 in full shadow).
float opacityShadowOpacity(sampler2DArray opacity, sampler2D firstDepth, OpacityShadow osm, vec3 world) {
  if (osm.depth.w > 1.5) return 1.0 - depthShadowMapTransmittance(firstDepth, osm, world);
  return osm.depth.w > 0.5 ? deepOpacityMapOpacity(opacity, firstDepth, osm, world)
                           : opacityShadowMapOpacity(opacity, osm, world);
}

// Transmittance towards the light at `world`: exp(−κ·opacity), 1 in front of all hair; for a
// depth shadow map 1 in front of the first hair (plus the bias) and 0 behind it.
float opacityShadowTransmittance(sampler2DArray opacity, sampler2D firstDepth, OpacityShadow osm, vec3 world) {
  if (osm.depth.w > 1.5) return depthShadowMapTransmittance(firstDepth, osm, world);
  return exp(-osm.depth.z * opacityShadowOpacity(opacity, firstDepth, osm, world));
}
