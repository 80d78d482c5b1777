#version 450
#extension GL_GOOGLE_include_directive : require
// A lens's front surface as a polar grid over its elliptical outline, made from the vertex index
// alone: kRings rings of kSegments quads, the outermost ring widened so that its polygon holds the
// whole ellipse (glasses_lens.frag cuts the exact outline).
#include "frame_uniforms.glsl"
#include "glasses_lens.glsl"

const int kRings = 8;
const int kSegments = 48;

layout(location = 0) out vec3 outLensPosition;  // lens frame, metres

void main() {
  // Two triangles a quad, each corner one ring or segment further on or not.
  const int ringStep[6] = int[6](0, 1, 1, 0, 1, 0);
  const int segmentStep[6] = int[6](0, 0, 1, 0, 1, 1);
  int quad = gl_VertexIndex / 6;
  int corner = gl_VertexIndex - quad * 6;
  int ring = quad / kSegments + ringStep[corner];
  int segment = quad % kSegments + segmentStep[corner];
  float radial = float(ring) / float(kRings) / cos(kPi / float(kSegments));
  float angle = 2.0 * kPi * float(segment) / float(kSegments);
  vec2 xy = lens.outline.xy * radial * vec2(cos(angle), sin(angle));
  vec3 position = vec3(xy, -lensSag(lens.surfaces.x, dot(xy, xy)));
  outLensPosition = position;
  gl_Position = frame.viewProjection * (lens.model * vec4(position, 1.0));
}
