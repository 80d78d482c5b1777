#version 450
#extension GL_GOOGLE_include_directive : require
// Deep water (NVIDIA's "Clear Sailing", 2004): the sky's reflection (and the ship's, where it
// hides the sky) and the sun's, mixed by Fresnel with the light the water scatters up from below;
// foam where crests break; fog.
//
// Fresnel's factor is Schlick's form F₀ + (1 − F₀)(1 − n·v)^p with F₀ = 0.02 (water) and a
// lower exponent than Schlick's 5, as the demo found: at 5 the water looked right at grazing
// angles but flat looking down; p is the scene's. The sun's highlight is a normalised
// Blinn–Phong lobe ((e + 8)/8π, times π in the lights' units, where a white Lambert surface
// shows radiance × cos θ), shadowed by the surfaces' shadow map (the ship), and the
// reflection's normal gets a little per-pixel noise, finer than the waves the grid can carry.
#include "frame_uniforms.glsl"
#include "ocean_uniforms.glsl"

layout(set = 1, binding = 1) uniform sampler2D foamMap;  // at rest (x, z), linear

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec2 inRest;
layout(location = 2) in vec3 inNormal;
layout(location = 3) in float inJacobian;
layout(location = 4) in float inFootprint;
layout(location = 5) in vec3 inHorizon;
layout(location = 0) out vec4 outColor;

const float kWaterF0 = 0.02;
const float kSunExponent = 800.0;

// Value noise in [−1, 1] on a lattice of unit spacing; the lattice's values from an integer hash
// (a few multiplies and shifts: sines would cost more on lavapipe).
float hash(vec2 p) {
  uvec2 q = uvec2(ivec2(p) + 32768);
  uint h = q.x * 0x8da6b343u ^ q.y * 0xd8163841u;
  h = (h ^ (h >> 15)) * 0x2c1b3c6du;
  h ^= h >> 12;
  return float(h & 0xffffu) / 32767.5 - 1.0;
}
float valueNoise(vec2 p) {
  vec2 i = floor(p);
  vec2 f = p - i;
  vec2 u = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1.0, 0.0)), u.x), mix(hash(i + vec2(0.0, 1.0)), hash(i + vec2(1.0)), u.x), u.y);
}

// Light 0's share at `position`: one bilinear comparison with the surfaces' depth map, 1 off it.
float sunShadow(vec3 position) {
  SurfaceShadow shadow = frame.surfaceShadow;
  vec4 light = shadow.map.lightFromWorld * vec4(position, 1.0);
  vec2 uv = light.xy * 0.5 + 0.5;
  bool mapped = shadow.map.scale.w != 0.0 && all(greaterThanEqual(uv, vec2(0.0))) &&
                all(lessThanEqual(uv, vec2(1.0))) && light.z < 1.0;
  return mapped ? texture(surfaceShadowCompare, vec3(uv, light.z - 2.0 * shadow.map.scale.y)) : 1.0;
}

vec3 skyAlong(vec3 direction) {
  return frame.lightCount.y != 0 ? textureLod(environmentSpecular, direction, 1.0).rgb : ocean.sky.rgb;
}

void main() {
  vec3 toEye = ocean.eye.xyz - inWorld;
  float distance = length(toEye);
  vec3 v = toEye / distance;
  vec3 n = normalize(inNormal);
  // Ripples finer than the grid, fading where a pixel covers several of them.
  float ripple = 0.06 * clamp(1.0 - inFootprint / 2.0, 0.0, 1.0);
  vec2 p = inRest * 2.0;
  n = normalize(n + ripple * vec3(valueNoise(p), 0.0, valueNoise(p.yx + 17.0)));
  // Seen at a grazing angle, a normal may face away: bend it back towards the eye.
  float facing = dot(n, v);
  if (facing < 0.02) n = normalize(n + (0.02 - facing) * v);
  float nv = max(dot(n, v), 0.0);
  float fresnel = kWaterF0 + (1.0 - kWaterF0) * pow(1.0 - nv, ocean.water.a);

  vec3 r = reflect(-v, n);
  r.y = abs(r.y);
  vec3 reflected = skyAlong(r);
  // The ship hides the sky it stands in front of: the reflected ray against the ellipsoid round
  // its hull, whose side facing the water is lit by the sky across it.
  if (ocean.reflector.a > 0.0) {
    vec3 o = (ocean.reflectorFromWorld * vec4(inWorld, 1.0)).xyz;
    vec3 d = (ocean.reflectorFromWorld * vec4(r, 0.0)).xyz;
    float b = dot(o, d);
    float c = dot(o, o) - 1.0;
    float discriminant = b * b - dot(d, d) * c;
    if (discriminant > 0.0 && (c < 0.0 || b < 0.0))
      reflected = ocean.reflector.rgb * (frame.ambient.rgb + environmentLight(normalize(vec3(-r.x, 1e-3, -r.z))));
  }
  vec3 fromBelow = frame.ambient.rgb + environmentLight(vec3(0.0, 1.0, 0.0));
  vec3 foamLight = frame.ambient.rgb + environmentLight(n);
  if (frame.lightCount.x > 0) {
    vec3 l = frame.lightDirection[0].xyz;
    vec3 radiance = frame.lightRadiance[0].rgb;
    float shadow = sunShadow(inWorld);
    vec3 h = normalize(l + v);
    float highlight = (kSunExponent + 8.0) / 8.0 * pow(max(dot(n, h), 0.0), kSunExponent) * max(dot(n, l), 0.0);
    reflected += radiance * highlight * shadow;
    fromBelow += radiance * max(l.y, 0.0) * mix(0.5, 1.0, shadow);
    foamLight += radiance * max(dot(n, l), 0.0) * shadow;
  }
  vec3 color = fresnel * reflected + (1.0 - fresnel) * ocean.water.rgb * fromBelow;

  vec2 foamUv = (inRest - ocean.foamMap.xy) * ocean.foamMap.z;
  float crest = clamp((ocean.foam.a - inJacobian) / 0.2, 0.0, 1.0);
  float foam = max(crest, all(greaterThanEqual(foamUv, vec2(0.0))) && all(lessThanEqual(foamUv, vec2(1.0)))
                              ? texture(foamMap, foamUv).r : 0.0);
  color = mix(color, ocean.foam.rgb * foamLight, foam);

  color = mix(inHorizon, color, exp(-ocean.fog.a * distance));
  outColor = vec4(color, 1.0);
}
