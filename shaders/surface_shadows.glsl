// Soft shadows of the opaque surfaces from the first light (render/passes/surface_shadow_pass.hpp:
// percentage-closer soft shadows sized by the light's disc). Fragment shaders only (the filter
// turns with gl_FragCoord). Include after surface_shadow_map.glsl.

// The taps spread evenly over the unit disc by Vogel's spiral: tap i of n at radius √((i + ½)/n),
// each turned by the golden angle from the last. The turn is carried from tap to tap as a unit
// vector rotated by this, rather than by a sine and a cosine a tap.
const float kGoldenAngle = 2.39996323;
const vec2 kGoldenTurn = vec2(cos(kGoldenAngle), sin(kGoldenAngle));

vec2 nextVogelTurn(vec2 turn) {
  return vec2(turn.x * kGoldenTurn.x - turn.y * kGoldenTurn.y, turn.x * kGoldenTurn.y + turn.y * kGoldenTurn.x);
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
//
// The loops' trip counts are the pixel's, 0 where it needs no lookups (no map, turned from the
// light, outside the map; no blocker found for the filter): lavapipe unrolls a loop of constant
// count and runs its lookups on every lane, masked or not, but skips a loop that no lane of a
// block enters (docs/lavapipe.md, "Branches run every lane").
float surfaceShadowVisibility(SurfaceShadow shadow, vec3 position, vec3 normal, vec3 towardLight) {
  float facing = dot(normal, towardLight);
  float cosine = max(facing, 0.05);
  vec4 light = shadow.map.lightFromWorld * vec4(position + normal * shadow.penumbra.w, 1.0);
  vec2 uv = light.xy * 0.5 + 0.5;
  bool mapped = shadow.map.scale.w != 0.0 && facing > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) &&
                all(lessThanEqual(uv, vec2(1.0))) && light.z < 1.0;
  float receiver = light.z;
  // A surface tilted from the light spans this much depth per map unit across the filter.
  float slope = min(sqrt(1.0 - cosine * cosine) / cosine, 8.0);
  float texel = shadow.map.scale.y;
  float angle = pixelTurn();
  vec2 firstTurn = vec2(cos(angle), sin(angle));

  // 1. Blockers: a blocker at depth b hides part of the disc from points within (receiver − b)·tan α.
  float search = clamp(receiver * shadow.penumbra.x, shadow.penumbra.z, shadow.penumbra.y);
  float bias = texel * (1.0 + slope * search / texel);
  float blockerSum = 0.0;
  int blockers = 0;
  const int kSearchTaps = 8;
  int searchTaps = mapped ? kSearchTaps : 0;
  vec2 turn = firstTurn;
  for (int i = 0; i < searchTaps; ++i) {
    vec2 tap = sqrt((float(i) + 0.5) / float(kSearchTaps)) * turn;
    float depth = textureLod(surfaceShadowDepth, uv + search * tap, 0.0).r;
    if (depth < receiver - bias) {
      blockerSum += depth;
      ++blockers;
    }
    turn = nextVogelTurn(turn);
  }

  // 2. The penumbra's half-width, and 3. the filter over it.
  float blocker = blockerSum / float(max(blockers, 1));
  float radius = clamp((receiver - blocker) * shadow.penumbra.x, shadow.penumbra.z, shadow.penumbra.y);
  bias = texel * (1.0 + slope * radius / texel);
  float visible = 0.0;
  const int kFilterTaps = 16;
  int filterTaps = blockers > 0 ? kFilterTaps : 0;
  turn = firstTurn;
  for (int i = 0; i < filterTaps; ++i) {
    vec2 tap = sqrt((float(i) + 0.5) / float(kFilterTaps)) * turn;
    visible += texture(surfaceShadowCompare, vec3(uv + radius * tap, receiver - bias));
    turn = nextVogelTurn(turn);
  }
  return blockers > 0 ? mix(1.0, visible / float(kFilterTaps), smoothstep(0.0, 0.2, facing)) : 1.0;
}
