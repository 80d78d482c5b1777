// Shared by the fur shell and fin shaders (render/passes/fur_pass.hpp): the pass's uniform
// block, the photo, the shell thresholds of Ukaji et al. (render/luts/fur_shells.hpp) and
// Kajiya-Kay lighting along the fur.

// The hair shadows the fur receives: constants 0 and 1, images from binding 5 (FurPass).
#define HAIR_SHADOW_SET 0
#define HAIR_SHADOW_BINDING 5
#include "hair_shadows.glsl"

// Which pixels a shell shows (FurCoverage): 0 bands, 1 strands.
layout(constant_id = 2) const uint kCoverage = 1u;

// std140 mirror of FurUniforms in render/passes/fur_pass.cpp.
layout(set = 0, binding = 0) uniform FurUniforms {
  mat4 model;           // object → world
  mat4 normalMatrix;    // inverse transpose of model's linear part (upper 3×3 used)
  mat4 viewProjection;  // world → clip
  vec4 eye;             // world; w = 1 a point (perspective), w = 0 the direction towards the viewer
  vec4 lightDirection;  // xyz: unit, towards the light
  vec4 lightRadiance;   // rgb
  vec4 ambient;         // rgb
  vec4 shells;          // x: h_b (metres), y: N, z: Kajiya-Kay exponent, w: specular strength
  vec4 lay;             // x: cos, y: sin of the fur's tilt away from its direction, z: the model's scale
  vec4 layField;        // xyz: the fur-direction field (model space), w: photo repeats per metre (0: by uvs)
  vec4 tint;            // rgb: multiplies the photo's colour
  vec4 comb;            // xyz: world lean of the tips (units of h_b) before projection on the surface
  vec4 environment[9];  // rgb: the environment's E/π as nine harmonics; 0 without one
  vec4 thresholds[17];  // I(0 … 64), four to a vec4
  HairShadowUniforms shadows;
} fur;

layout(set = 0, binding = 1) uniform sampler2D photo;  // sRGB: sampled values are linear

#include "environment_fibre.glsl"

// Rec. 709 relative luminance of linear RGB, as photoLuminance on the CPU.
float luminance(vec3 rgb) {
  return dot(rgb, vec3(0.2126, 0.7152, 0.0722));
}

// I(n), eq. 4 of Ukaji et al., as FurShellModel::threshold computed it.
float threshold(uint n) {
  return fur.thresholds[n / 4u][n % 4u];
}

// The fur's lean at a vertex of world normal n: the comb on the tangent plane plus the vertex's
// own (FurPass::setLeans), units of h_b.
vec3 furLean(vec3 n, vec3 vertexLean) {
  return fur.comb.xyz - dot(fur.comb.xyz, n) * n + vertexLean;
}

// A fibre's point at height fraction s (0 skin … 1 top): it leaves the skin along n and bends
// towards the lean, p + h_b·(s·n + s²·lean); its direction there is n + 2s·lean.
vec3 furOffset(vec3 n, vec3 lean, float s) {
  return fur.shells.x * (s * n + s * s * lean);
}
vec3 furDirection(vec3 n, vec3 lean, float s) {
  return normalize(n + 2.0 * s * lean);
}

// Where a vertex samples the photo (FurPass, "Lay"): its uv, or with a fur-direction field the
// point's coordinates in the frame (n × f, f) of the field f projected on the surface.
// `position` and `normal` in model space.
// Both are computed and one selected, without a branch on the uniform: lavapipe (Mesa 22.3)
// compiles a vertex shader again, every frame, for a branch that only uniforms decide.
vec2 photoCoordinates(vec2 uv, vec3 position, vec3 normal) {
  vec3 n = normalize(normal);
  vec3 f = fur.layField.xyz - dot(fur.layField.xyz, n) * n;
  if (dot(f, f) < 1e-6) f = abs(n.x) < 0.9 ? cross(n, vec3(1, 0, 0)) : cross(n, vec3(0, 1, 0));
  f = normalize(f);
  vec2 alongField = vec2(dot(position, cross(n, f)), dot(position, f)) * (fur.layField.w * fur.lay.z);
  return fur.layField.w > 0.0 ? alongField : uv;
}

uint layerCount() {
  return uint(fur.shells.y + 0.5);
}

vec3 towardEye(vec3 world) {
  return normalize(fur.eye.xyz - fur.eye.w * world);
}

// Kajiya & Kay 1989 for fibres along t: diffuse sin(t, l); specular
// (sin(t,l)·sin(t,e) − (t·l)(t·e))^p, largest where e lies on the cone of mirror directions of l
// about t (t·e = −t·l). Returned as (diffuse, specular).
vec2 kajiyaKay(vec3 t, vec3 l, vec3 e) {
  float tl = dot(t, l);
  float te = dot(t, e);
  float sinTl = sqrt(max(1.0 - tl * tl, 0.0));
  float sinTe = sqrt(max(1.0 - te * te, 0.0));
  return vec2(sinTl, pow(max(sinTl * sinTe - tl * te, 0.0), fur.shells.z));
}

// The light fur growing along `d` from a surface of normal `n` sends back, apart from its
// colour: radiance = photo colour × diffuse + specular. Real hairs lean away from that direction:
// the fibre is d tilted by the lay angle, averaged over four azimuths (a fibre straight along n
// would be black under a light along n, which the photo, taken lit from above, contradicts). The
// diffuse term is divided by its value for light along n, so the photo's own colour comes back
// under the light it was taken in; the fur's body shades it as it turns away from the light
// (half-Lambert wrap: fur scatters light past the terminator). The environment lights each fibre
// as it does a hair: its irradiance averaged round the fibre's side.
struct FurLight {
  vec3 diffuse;   // multiplies the photo's colour
  vec3 specular;  // added
};

FurLight furLight(vec3 n, vec3 d, vec3 world) {
  vec3 l = fur.lightDirection.xyz;
  vec3 e = towardEye(world);
  vec3 b1 = normalize(abs(d.x) < 0.9 ? cross(d, vec3(1, 0, 0)) : cross(d, vec3(0, 1, 0)));
  vec3 b2 = cross(d, b1);
  vec2 sum = vec2(0.0);
  for (int k = 0; k < 4; ++k) {
    vec3 b = (k == 0) ? b1 : (k == 1) ? b2 : (k == 2) ? -b1 : -b2;
    sum += kajiyaKay(fur.lay.x * d + fur.lay.y * b, l, e);
  }
  sum *= 0.25;
  float diffuseUnderTopLight = max(fur.lay.y, 1e-3);  // sin(t, n) of every tilted fibre
  float body = clamp(0.5 * dot(n, l) + 0.5, 0.0, 1.0);
  vec3 light = fur.lightRadiance.rgb * body * hairShadowTransmittance(fur.shadows, world);
  vec3 ambient = fur.ambient.rgb + environmentAroundFibre(fur.environment, d);
  return FurLight(fur.tint.rgb * (ambient + light * (sum.x / diffuseUnderTopLight)),
                  light * fur.shells.w * sum.y);
}

// Radiance of fur of colour `photoColour` (furLight, per fragment).
vec3 shadeFur(vec3 photoColour, vec3 n, vec3 d, vec3 world) {
  FurLight lit = furLight(n, d, world);
  return photoColour * lit.diffuse + lit.specular;
}
