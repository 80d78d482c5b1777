#version 450
// Effects with premultiplied alpha, their colour lit at the vertices (shaders/effects.vert):
// discs fade as (1 − r²)² to their edge, lines by the share of the pixel they cover, triangles
// are opaque.

layout(location = 0) in vec2 inLocal;
layout(location = 1) in vec4 inColour;
layout(location = 2) in float inHalfPixels;
layout(location = 3) flat in float inKind;
layout(location = 0) out vec4 outColor;

void main() {
  float alpha = inColour.a;
  if (inKind < 0.5) {
    float r2 = dot(inLocal, inLocal);
    if (r2 >= 1.0) discard;
    alpha *= (1.0 - r2) * (1.0 - r2);
  } else if (inKind < 1.5) {
    // The share of the pixel the line covers, as a box filter sees it: its integral across the
    // line is the line's width in pixels.
    alpha *= clamp(inHalfPixels + 0.5 - abs(inLocal.y), 0.0, 1.0);
  }
  outColor = vec4(inColour.rgb * alpha, alpha);
}
