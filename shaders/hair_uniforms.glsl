// Per-frame data of the hair ribbon pass; mirrors HairUniforms in render/passes/hair_pass.cpp (std140).
// Include after `#extension GL_GOOGLE_include_directive : require`.
layout(set = 0, binding = 0, std140) uniform HairUniforms {
  mat4 viewProjection;  // world (metres) → clip
  vec4 eye;             // w = 1: eye position (metres); w = 0: unit direction towards the eye
  vec4 groom;           // x: root width (m), y: tip width scale, z: opacity, w: min width (px)
  vec4 viewport;        // xy: extent in pixels, z: the line draw's width (pixels)
  uvec4 counts;         // x: strands, y: vertices per strand, z: 1 when lines may stand in for ribbons,
                        // w: the line draw's first index
  uvec4 occlusion;      // x, y: tiles across and down of the opaque depth's maxima; z: tile size (pixels)
  vec4 levelOfDetail;   // x: the share f of the strands drawn, y: 1 / f (render/strand_lod.hpp)
} hair;

// Whether dense strand `strand` is drawn at this level of detail: its rank, the bit reversal of
// its index over 2³², below the share kept (render/strand_lod.hpp).
bool hairStrandKept(uint strand) {
  return hair.levelOfDetail.x >= 1.0 || float(bitfieldReverse(strand)) * exp2(-32.0) < hair.levelOfDetail.x;
}

// Unit vector from `position` (world, metres) towards the eye.
vec3 hairToEye(vec3 position) {
  return normalize(hair.eye.xyz - hair.eye.w * position);
}

// A strand vertex's ribbon (render/passes/hair_pass.hpp): the unit vector it is widened along,
// perpendicular to the strand and to the view, and that vector on screen (unit, pixels); the
// strand's half width there and half the minimum drawn width there (both metres); and the pixels
// per metre along `side` there. With MSAA the ribbon is drawn max(halfWidth, minimumHalfWidth)
// to each side. `shape` is the strand's hairStrandShape (hair_strand_look.glsl): its factors of
// the groom's root width and tip width scale.
struct HairRibbon {
  vec3 side;
  vec2 screenSide;
  float halfWidth;
  float minimumHalfWidth;
  float pixelsPerMetre;
};

HairRibbon hairRibbon(vec4 point, vec3 tangent, vec4 shape) {
  HairRibbon ribbon;
  vec3 toEye = hairToEye(point.xyz);
  // Any perpendicular to the view where the strand points at the eye (or its tangent is zero:
  // coincident neighbours).
  vec3 side = cross(tangent, toEye);
  if (dot(side, side) < 1e-12) side = cross(abs(toEye.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0), toEye);
  ribbon.side = normalize(side);

  // Pixels per metre along `side` here, from projecting the root half-width offset (exact for any
  // projection, including the obliquity of off-axis strands under perspective).
  float rootHalfWidth = 0.5 * hair.groom.x * shape.x;
  vec4 centre = hair.viewProjection * vec4(point.xyz, 1.0);
  vec4 edge = hair.viewProjection * vec4(point.xyz + ribbon.side * rootHalfWidth, 1.0);
  vec2 offsetPixels = (edge.xy / edge.w - centre.xy / centre.w) * 0.5 * hair.viewport.xy;
  float pixelsPerMetre = length(offsetPixels) / rootHalfWidth;
  ribbon.pixelsPerMetre = max(pixelsPerMetre, 1e-6);
  ribbon.screenSide = pixelsPerMetre > 0.0 ? offsetPixels / length(offsetPixels) : vec2(1.0, 0.0);

  ribbon.halfWidth = rootHalfWidth * mix(1.0, hair.groom.y * shape.y, point.w);
  ribbon.halfWidth *= hair.levelOfDetail.y;  // 1 / f as wide where a share f is drawn (render/strand_lod.hpp)
  ribbon.minimumHalfWidth = 0.5 * hair.groom.w / ribbon.pixelsPerMetre;
  return ribbon;
}
