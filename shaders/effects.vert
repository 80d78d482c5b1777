#version 450
#extension GL_GOOGLE_include_directive : require
// Six vertices per effect (render/passes/effects_pass.hpp), made from its record: a disc facing
// the eye, a line's quad turned to the eye, or a triangle and a degenerate one. Discs and lines
// keep at least a pixel's width, their opacity scaled by what they would have covered.
//
// Each vertex is lit here, by the frame's lights, ambient and environment, and the fragments
// only blend between them: spray and smoke cover the screen many times over, and a fragment that
// evaluated the environment's harmonics would cost more than all the rest of the effect.
#include "frame_uniforms.glsl"

struct Record {
  vec4 a;       // xyz: a disc's centre, a line's start, a triangle's first corner; w: radius or half width
  vec4 b;       // xyz: a line's end, a triangle's second corner; w: the kind (0 disc, 1 line, 2 triangle)
  vec4 c;       // xyz: a triangle's third corner, a line's middle; w: a disc's underside darkening
  vec4 colour;  // rgb albedo, a opacity
};
layout(set = 1, binding = 0, std430) readonly buffer Records { Record records[]; };
layout(push_constant) uniform Constants { vec4 pixel; } constants;  // x: radians a pixel spans

layout(location = 0) out vec2 outLocal;        // a disc's (x, y) in [−1, 1]; a line's y: pixels from its axis
layout(location = 1) out vec4 outColour;       // lit colour, opacity
layout(location = 2) out float outHalfPixels;  // a line's half width in pixels
layout(location = 3) flat out float outKind;   // 0 disc, 1 line, 2 triangle

const vec2 kCorners[6] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, -1.0), vec2(1.0, 1.0),
                                vec2(-1.0, 1.0));

// Light on a surface of normal n, Lambert's cosine wrapped by `wrap` (0: none). Every light slot
// is summed, the absent ones selected away: a loop counted by the frame's uniform would make
// lavapipe compile the shader again at every bind (docs/lavapipe.md).
vec3 lightOn(vec3 n, float wrap) {
  vec3 light = frame.ambient.rgb + environmentLight(n);
  for (int i = 0; i < kMaxLights; ++i) {
    vec3 lit = frame.lightRadiance[i].rgb * max((dot(n, frame.lightDirection[i].xyz) + wrap) / (1.0 + wrap), 0.0);
    light += mix(vec3(0.0), lit, bvec3(i < frame.lightCount.x));
  }
  return light;
}

void main() {
  Record r = records[gl_VertexIndex / 6];
  int corner = gl_VertexIndex % 6;
  vec2 q = kCorners[corner];
  vec3 eye = frame.cameraPosition.xyz;
  vec4 colour = r.colour;
  vec3 world;
  outLocal = q;
  outHalfPixels = 1.0;
  outKind = r.b.w;
  if (r.b.w < 0.5) {
    vec3 toEye = eye - r.a.xyz;
    float distance = max(length(toEye), 1e-6);
    vec3 f = toEye / distance;
    vec3 right = normalize(cross(abs(f.y) > 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0), f));
    vec3 up = cross(f, right);
    float radius = max(r.a.w, constants.pixel.x * distance);
    colour.a *= (r.a.w / radius) * (r.a.w / radius);
    world = r.a.xyz + (right * q.x + up * q.y) * radius;
    // A rounded puff: at each corner the normal of a ball's rim bent towards the eye, the light
    // wrapped round it as through a cloud, and its lower edge darker where asked (smoke).
    vec3 n = normalize(right * q.x + up * q.y + f);
    colour.rgb *= lightOn(n, 0.6) * mix(1.0 - r.c.w, 1.0, 0.5 + 0.5 * q.y);
  } else if (r.b.w < 1.5) {
    vec3 end = q.y < 0.0 ? r.a.xyz : r.b.xyz;
    vec3 toEye = eye - end;
    float distance = max(length(toEye), 1e-6);
    vec3 axis = r.b.xyz - r.a.xyz;
    // Seen end on, a rope has no side of its own: any square to it will do.
    vec3 across = cross(axis, toEye);
    if (dot(across, across) < 1e-12 * dot(axis, axis) * dot(toEye, toEye))
      across = cross(axis, abs(axis.y) < 0.9 * length(axis) ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0));
    vec3 side = normalize(across);
    // One pixel wide at least, fainter by as much; drawn half a pixel wider each side for the
    // ramp of its edge.
    float pixelSize = constants.pixel.x * distance;
    float halfWidth = max(r.a.w, 0.5 * pixelSize);
    colour.a *= r.a.w / halfWidth;
    float halfPixels = halfWidth / pixelSize;
    world = end + side * (q.x * (halfWidth + 0.5 * pixelSize));
    outLocal = vec2(0.0, q.x * (halfPixels + 0.5));
    outHalfPixels = halfPixels;
    // A rope: lit on its sides as a cylinder is.
    vec3 facing = normalize(cross(side, axis));
    if (dot(facing, toEye) < 0.0) facing = -facing;
    colour.rgb *= lightOn(normalize(side * q.x + facing), 0.0);
  } else {
    world = corner == 1 ? r.b.xyz : corner == 2 ? r.c.xyz : r.a.xyz;
    vec3 n = normalize(cross(r.b.xyz - r.a.xyz, r.c.xyz - r.a.xyz));
    colour.rgb *= lightOn(dot(n, eye - r.a.xyz) < 0.0 ? -n : n, 0.0);
  }
  outColour = colour;
  gl_Position = frame.viewProjection * vec4(world, 1.0);
}
