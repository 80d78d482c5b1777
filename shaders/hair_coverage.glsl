// The share of a pixel a strand covers, for drawing with one sample per pixel
// (render/passes/hair_pass.hpp, "Anti-aliasing"). Locally a strand on screen is a band of
// half width w about its centre line, and a pixel is a unit square whose centre lies a distance
// d from that line. Only the square's extent across the band matters: projected on the band's
// unit normal n, the square spreads as the sum of two uniform variables of widths |n.x| and
// |n.y|, a trapezoid of unit area. The covered share is that trapezoid's mass within [−w, w]
// about d: exact for a straight band, and its sum over the pixels is the band's area.

// Half the width of a pixel's projection on the unit normal `normal` (pixels): how far past a
// strand's edge a pixel centre can lie and still be touched by it.
float hairPixelReach(vec2 normal) {
  return 0.5 * (abs(normal.x) + abs(normal.y));
}

// The cumulative distribution of a pixel's projection on a unit normal whose absolute
// components, larger first, are a and b: linear in the middle, quadratic where only one of the
// two uniform variables still spans.
float hairPixelProjectionCdf(float x, float a, float b) {
  float reach = 0.5 * (a + b), inner = 0.5 * (a - b);
  if (x <= -reach) return 0.0;
  if (x >= reach) return 1.0;
  if (x < -inner) return (x + reach) * (x + reach) / (2.0 * a * b);
  if (x > inner) return 1.0 - (reach - x) * (reach - x) / (2.0 * a * b);
  return x / a + 0.5;
}

// The share of the pixel whose centre lies `distance` pixels from the centre line of a strand
// `halfWidth` pixels wide to each side, whose unit normal on screen is `normal`.
float hairPixelCoverage(float distance, float halfWidth, vec2 normal) {
  vec2 spread = abs(normal);
  float a = max(spread.x, spread.y), b = min(spread.x, spread.y);
  return hairPixelProjectionCdf(distance + halfWidth, a, b) - hairPixelProjectionCdf(distance - halfWidth, a, b);
}

// How far to each side of its centre a strand vertex's ribbon is drawn (metres): with analytic
// coverage, its half width plus a pixel's reach, so that every pixel it touches has its centre
// inside; with MSAA, its half width or half the minimum width, whichever is larger. Include
// after hair_uniforms.glsl.
float hairDrawnHalfWidth(HairRibbon ribbon, bool analyticCoverage) {
  if (analyticCoverage) return ribbon.halfWidth + hairPixelReach(ribbon.screenSide) / ribbon.pixelsPerMetre;
  return max(ribbon.halfWidth, ribbon.minimumHalfWidth);
}
