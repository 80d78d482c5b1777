// A spectacle lens seen through by screen-space refraction (render/passes/glasses_pass.hpp). Each
// pixel's ray from the eye is traced through the lens's two spherical surfaces by Snell's law;
// the ray that leaves it finds the scene in a copy of the frame's colour and depth taken before the
// lenses were drawn. Fresnel's equations split the light between what passes (twice: in and out)
// and the environment the front surface reflects, with the lights' glints.
// Before including, define GLASSES_MULTISAMPLED_DEPTH where the frame's depth is multisampled.
#include "frame_uniforms.glsl"
#include "glasses_lens.glsl"

layout(set = 1, binding = 0) uniform sampler2D sceneBehind;  // the frame's colour before the lenses
#ifdef GLASSES_MULTISAMPLED_DEPTH
layout(set = 1, binding = 1) uniform sampler2DMS sceneDepth;
ivec2 depthSize() { return textureSize(sceneDepth); }
#else
layout(set = 1, binding = 1) uniform sampler2D sceneDepth;
ivec2 depthSize() { return textureSize(sceneDepth, 0); }
#endif
layout(set = 1, binding = 2, std140) uniform GlassesView {
  mat4 clipToWorld;   // the inverse of frame.viewProjection
  vec4 viewForward;   // xyz: the camera's unit forward axis
  vec4 background;    // rgb: the frame's flat background, where it has no environment
} view;

layout(location = 0) in vec3 inLensPosition;
layout(location = 0) out vec4 outColor;

// The fraction a smooth dielectric reflects of unpolarised light meeting it at cosine cosI
// (Fresnel's equations), eta = n_incident / n_transmitted; 1 past the critical angle.
float dielectricReflectance(float cosI, float eta) {
  float sinT2 = eta * eta * max(1.0 - cosI * cosI, 0.0);
  if (sinT2 >= 1.0) return 1.0;
  float cosT = sqrt(1.0 - sinT2);
  float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
  float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

float depthAt(vec2 uv) {
  ivec2 size = depthSize();
  ivec2 texel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
  return texelFetch(sceneDepth, texel, 0).r;  // the first sample where multisampled
}

// Where a world point lies on the screen (uv in 0..1), and its clip w.
vec3 screenOf(vec3 world) {
  vec4 clip = frame.viewProjection * vec4(world, 1.0);
  return vec3(clip.xy / clip.w * 0.5 + 0.5, clip.w);
}

bool onScreen(vec2 uv) {
  return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

// The environment along a world direction, its sharpest pre-filtered level; without one, what
// `otherwise` says.
vec3 environmentAlong(vec3 direction, vec3 otherwise) {
  if (frame.lightCount.y == 0) return otherwise;
  return textureLod(environmentSpecular, direction, 0.0).rgb;
}

// What the ray from `origin` along `direction` (world, unit) meets, from the copy of the frame:
// from a guess of where it lands, the depth there puts the ray's end on a plane facing the camera
// (exact for one), and each step moves the guess to the depth where the ray then lands. The first
// guess is the pixel behind the ray's origin, right where what lies behind is near and the ray
// turns little; where that sees past everything, the pixel that shows what lies at infinity along
// the ray. A ray whose guesses both land on nothing the frame holds sees the background (the
// frame's shows what is in front of it).
vec3 sceneAlong(vec3 origin, vec3 direction) {
  vec3 background = environmentAlong(direction, view.background.rgb);
  vec3 eye = frame.cameraPosition.xyz;
  vec3 forward = view.viewForward.xyz;
  float originDepth = dot(origin - eye, forward);
  float approach = dot(direction, forward);
  if (approach <= 1e-4) return background;  // turned back towards the camera or across the view
  vec4 farClip = frame.viewProjection * vec4(direction, 0.0);
  vec2 guesses[2] = vec2[2](screenOf(origin).xy, farClip.xy / farClip.w * 0.5 + 0.5);
  for (int guess = 0; guess < 2; ++guess) {
    vec2 uv = guesses[guess];
    bool landed = onScreen(uv) && (guess == 0 || farClip.w > 0.0);
    for (int i = 0; i < 4 && landed; ++i) {
      float depth = depthAt(uv);
      landed = depth < 1.0;  // else past everything the frame holds
      vec4 scene = view.clipToWorld * vec4(uv * 2.0 - 1.0, depth, 1.0);
      float along = max((dot(scene.xyz / scene.w - eye, forward) - originDepth) / approach, 0.0);
      vec3 landing = screenOf(origin + direction * along);
      landed = landed && landing.z > 0.0 && onScreen(landing.xy);
      if (landed) uv = landing.xy;
    }
    if (landed) return textureLod(sceneBehind, uv, 0.0).rgb;
  }
  return background;
}

// GGX's distribution of polished glass's microfacets at the cosine to the normal.
float glintDistribution(float cosH) {
  const float alpha2 = 0.03 * 0.03;
  float d = cosH * cosH * (alpha2 - 1.0) + 1.0;
  return alpha2 / (kPi * d * d);
}

// Seen from behind, the lens is traced mirrored through its mid-plane, where its back surface is
// the front one, of the opposite curvature: z ↦ −thickness − z (an involution).
struct Tracing {
  bool fromBehind;
  float thickness;
};

vec3 tracedPoint(Tracing t, vec3 p) {
  return t.fromBehind ? vec3(p.xy, -t.thickness - p.z) : p;
}

vec3 tracedDirection(Tracing t, vec3 d) {
  return t.fromBehind ? vec3(d.xy, -d.z) : d;
}

void main() {
  mat3 rotation = mat3(lens.model);
  vec3 origin = lens.model[3].xyz;
  vec3 eye = transpose(rotation) * (frame.cameraPosition.xyz - origin);
  Tracing t = Tracing(eye.z < -0.5 * lens.surfaces.z, lens.surfaces.z);
  float firstCurvature = t.fromBehind ? -lens.surfaces.y : lens.surfaces.x;
  float secondCurvature = t.fromBehind ? -lens.surfaces.x : lens.surfaces.y;
  vec3 o = tracedPoint(t, eye);
  vec3 d = tracedDirection(t, normalize(inLensPosition - eye));

  float entry = lensSurfaceHit(o, d, firstCurvature, 0.0);
  if (entry < 0.0) discard;
  vec3 p1 = o + d * entry;
  vec2 across = p1.xy / lens.outline.xy;
  if (dot(across, across) > 1.0) discard;  // outside the outline
  // Behind what the frame's depth holds (the rims, the nose from the side): hidden.
  vec4 entryClip = frame.viewProjection * vec4(origin + rotation * tracedPoint(t, p1), 1.0);
  if (entryClip.z / entryClip.w > depthAt(gl_FragCoord.xy / vec2(depthSize())) + 1e-6) discard;

  float ior = lens.surfaces.w;
  vec3 n1 = lensSurfaceNormal(p1, firstCurvature, 0.0);
  float reflectance1 = dielectricReflectance(-dot(d, n1), 1.0 / ior);
  vec3 inside = refract(d, n1, 1.0 / ior);
  vec3 transmitted = vec3(0.0);
  float second = lensSurfaceHit(p1, inside, secondCurvature, -t.thickness);
  if (second > 0.0) {
    vec3 p2 = p1 + inside * second;
    vec3 n2 = lensSurfaceNormal(p2, secondCurvature, -t.thickness);
    float reflectance2 = dielectricReflectance(-dot(inside, n2), ior);
    if (reflectance2 < 1.0) {
      vec3 leaving = refract(inside, n2, ior);
      vec3 behind = sceneAlong(origin + rotation * tracedPoint(t, p2),
                               normalize(rotation * tracedDirection(t, leaving)));
      transmitted = (1.0 - reflectance1) * (1.0 - reflectance2) * lens.transmittance.rgb * behind;
    }
  }
  // The first surface's mirror image of the environment and the lights.
  vec3 normal = normalize(rotation * tracedDirection(t, n1));
  vec3 toEye = -normalize(rotation * tracedDirection(t, d));
  vec3 reflected = environmentAlong(reflect(-toEye, normal), frame.ambient.rgb);
  for (int i = 0; i < frame.lightCount.x; ++i) {
    vec3 toLight = frame.lightDirection[i].xyz;
    if (dot(normal, toLight) <= 0.0) continue;
    vec3 halfway = normalize(toLight + toEye);
    // GGX with Smith's masking left out (≈ 1 for so smooth a surface): D·E/(4·cos θ_eye).
    reflected += frame.lightRadiance[i].rgb * glintDistribution(dot(normal, halfway)) /
                 (4.0 * max(dot(normal, toEye), 1e-3));
  }
  outColor = vec4(transmitted + reflectance1 * reflected, 1.0);
}
