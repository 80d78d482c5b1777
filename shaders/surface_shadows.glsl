// Soft shadows of the opaque surfaces from the first light (render/passes/surface_shadow_pass.hpp:
// percentage-closer soft shadows sized by the light's disc). Fragment shaders only (the filter
// turns with gl_FragCoord). Include after surface_shadow_map.glsl.

// Tap i of n spread evenly over the unit disc (Vogel's spiral: radius √((i + ½)/n), each turned
// by the golden angle from the last), turned by `turn` radians.
vec2 vogelDiscTap(int i, int n, float turn) {
  const float kGoldenAngle = 2.39996323;
  float radius = sqrt((float(i) + 0.5) / float(n));
  float angle = float(i) * kGoldenAngle + turn;
  return radius * vec2(cos(angle), sin(angle));
}

// Jimenez's interleaved gradient noise ("Next Generation Post Processing in Call of Duty:
// Advanced Warfare", SIGGRAPH 2014): a different turn of the taps at each pixel, in [0, 2π).
float pixelTurn() {
  return 6.28318531 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
}

// The share of light 0's disc, which lies towards `towardLight` (unit), that the surfaces leave
// visible from `position` (metres, world), whose geometric normal is `normal` (unit): 1 where the
// map holds nothing or the point lies outside it. Towards the terminator the shadow fades out
// (from N·L = 0.2 down to 0): there a surface shadows itself, where skin's pre-integrated diffuse
// still carries light scattered from its lit side, and the map's depth runs parallel to the light.
float surfaceShadowVisibility(SurfaceShadow shadow, vec3 position, vec3 normal, vec3 towardLight) {
  float facing = dot(normal, towardLight);
  if (shadow.map.scale.w == 0.0 || facing <= 0.0) return 1.0;
  float cosine = max(facing, 0.05);
  vec4 light = shadow.map.lightFromWorld * vec4(position + normal * shadow.penumbra.w, 1.0);
  vec2 uv = light.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || light.z >= 1.0) return 1.0;
  float receiver = light.z;
  // A surface tilted from the light spans this much depth per map unit across the filter.
  float slope = min(sqrt(1.0 - cosine * cosine) / cosine, 8.0);
  float texel = shadow.map.scale.y;
  float turn = pixelTurn();

  // 1. Blockers: a blocker at depth b hides part of the disc from points within (receiver − b)·tan α.
  float search = clamp(receiver * shadow.penumbra.x, shadow.penumbra.z, shadow.penumbra.y);
  float bias = texel * (1.0 + slope * search / texel);
  float blockerSum = 0.0;
  int blockers = 0;
  const int kSearchTaps = 8;
  for (int i = 0; i < kSearchTaps; ++i) {
    float depth = textureLod(surfaceShadowDepth, uv + search * vogelDiscTap(i, kSearchTaps, turn), 0.0).r;
    if (depth < receiver - bias) {
      blockerSum += depth;
      ++blockers;
    }
  }
  if (blockers == 0) return 1.0;

  // 2. The penumbra's half-width, and 3. the filter over it.
  float blocker = blockerSum / float(blockers);
  float radius = clamp((receiver - blocker) * shadow.penumbra.x, shadow.penumbra.z, shadow.penumbra.y);
  bias = texel * (1.0 + slope * radius / texel);
  float visible = 0.0;
  const int kFilterTaps = 16;
  for (int i = 0; i < kFilterTaps; ++i)
    visible += texture(surfaceShadowCompare, vec3(uv + radius * vogelDiscTap(i, kFilterTaps, turn), receiver - bias));
  return mix(1.0, visible / float(kFilterTaps), smoothstep(0.0, 0.2, facing));
}
