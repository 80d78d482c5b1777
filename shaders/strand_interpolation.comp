#version 460
// Dense strands interpolated from guide strands: the GPU twin of the CPU reference
// physics::interpolateDenseStrands. It implements the formula at the top of
// physics/interpolation.hpp operation for operation, in the same order and in float.
//
// Every arithmetic result is held in a `precise` variable, so glslang decorates the operations
// that produce it NoContraction: the driver may not fuse a*b + c into an fma nor reassociate,
// and each product and sum is rounded as on the CPU (built with -ffp-contract=off). Only sqrt
// and division may differ from IEEE by a few ulp on some GPUs (Vulkan's precision rules).
//
// One invocation per dense strand: the frame (two normalisations) is built once per strand,
// every position is computed once, and the tangent of vertex i, which needs positions i − 1
// and i + 1, comes from a sliding window of three positions held in registers — no second
// dispatch, no barrier and no re-read of the positions.
//
// Buffers (std430), see render/passes/strand_interpolation_pass.hpp:
//   0 guide positions   vec4 per guide vertex, guide after guide, root first: xyz metres, w unused
//   1 guide frames      uvec2 per guide (partner A, partner B)
//   2 dense strands     80-byte DenseStrand per strand
//   3 positions         vec4 per dense vertex, strand-major: xyz metres, w = t (0 root, 1 tip)
//   4 tangents          vec4 per dense vertex, strand-major: xyz unit tangent root → tip, w = 0

layout(local_size_x = 64) in;

struct DenseStrand {
  uvec4 guides;      // xyz: guide indices g[k]; w: K, the number of guides used (1 to 3)
  vec4 weights;      // xyz: w[k]; w: vertexScale (guide vertices per dense vertex)
  vec4 rootOffset;   // xyz: o, metres, in the primary guide's frame; w: clump c
  vec4 tipJitter;    // xyz: j, metres, in the primary guide's frame; w: length scale (unused)
  vec4 curl;         // x: curl radius r, metres; y: turns T; z: phase φ, turns; w: frizz f, metres
};

layout(std430, set = 0, binding = 0) readonly buffer GuidePositions { vec4 guidePositions[]; };
layout(std430, set = 0, binding = 1) readonly buffer GuideFrames { uvec2 guideFrames[]; };
layout(std430, set = 0, binding = 2) readonly buffer Strands { DenseStrand strands[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Positions { vec4 positions[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Tangents { vec4 tangents[]; };

layout(push_constant) uniform Counts {
  uint strandCount;       // dense strands
  uint guideVertexCount;  // Ng, vertices per guide (≥ 2)
  uint vertexCount;       // Nd, vertices per dense strand (≥ 2)
  uint curve;             // 0: linear, 1: Catmull-Rom (common/strand_layout.hpp's StrandCurve)
} counts;

vec3 guidePoint(uint guide, uint vertex) {
  return guidePositions[guide * counts.guideVertexCount + vertex].xyz;
}

// dot, cross and normalize exactly as the header defines them (not GLSL's built-ins, whose
// order of operations is unspecified).
float dot3(vec3 a, vec3 b) {
  precise float result = a.x * b.x + a.y * b.y + a.z * b.z;
  return result;
}

vec3 cross3(vec3 a, vec3 b) {
  precise float x = a.y * b.z - a.z * b.y;
  precise float y = a.z * b.x - a.x * b.z;
  precise float z = a.x * b.y - a.y * b.x;
  return vec3(x, y, z);
}

vec3 normalize3(vec3 a) {
  precise float length = sqrt(dot3(a, a));
  precise float x = a.x / length;
  precise float y = a.y / length;
  precise float z = a.z / length;
  return vec3(x, y, z);
}

// The formula's vertex beyond a guide's end `end`, from the vertex `next` inwards from it and,
// on guides of three or more vertices, the one after, vertex `third` of `guide`.
vec3 beyondEnd(vec3 end, vec3 next, uint guide, uint third) {
  if (counts.guideVertexCount < 3u) {
    precise vec3 line = end + (end - next);
    return line;
  }
  precise vec3 parabola = 3.0 * (end - next) + guidePoint(guide, third);
  return parabola;
}

// The formula's weights of the four guide vertices around a dense vertex at fraction f of its
// segment: (1 − f, f) on the straight segment, (a, b, c, d) on the curve. They depend on f only,
// so a dense vertex computes them once for all its guides.
vec4 curveWeights(float f) {
  if (counts.curve == 0u) {
    precise float rf = 1.0 - f;
    return vec4(0.0, rf, f, 0.0);
  }
  precise float f2 = f * f;
  precise float f3 = f2 * f;
  precise float a = 0.5 * ((2.0 * f2 - f3) - f);
  precise float b = 0.5 * ((3.0 * f3 - 5.0 * f2) + 2.0);
  precise float c = 0.5 * ((4.0 * f2 - 3.0 * f3) + f);
  precise float d = 0.5 * (f3 - f2);
  return vec4(a, b, c, d);
}

// The point at segment v along one guide with the weights `w`, by the formula's curve.
vec3 alongGuide(uint guide, uint v, vec4 w) {
  const uint last = counts.guideVertexCount - 1u;
  const vec3 p1 = guidePoint(guide, v);
  const vec3 p2 = guidePoint(guide, v + 1u);
  if (counts.curve == 0u) {
    precise vec3 linear = w.y * p1 + w.z * p2;
    return linear;
  }
  precise vec3 p0 = v > 0u ? guidePoint(guide, v - 1u) : beyondEnd(p1, p2, guide, 2u);
  precise vec3 p3 = v + 1u < last ? guidePoint(guide, v + 2u) : beyondEnd(p2, p1, guide, last - 2u);
  precise vec3 spline = ((w.x * p0 + w.y * p1) + w.z * p2) + w.w * p3;
  return spline;
}

// The formula's hash: Wellons' lowbias32.
uint lowbias32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// The formula's cosSinTurns: cos and sin of 2π·w, from a Taylor series on a quarter turn.
vec2 cosSinTurns(float w) {
  precise float turn = w - floor(w);
  precise float y = 4.0 * turn;
  const float k = floor(y + 0.5);
  precise float x = (y - k) * 1.57079637;
  precise float x2 = x * x;
  precise float sine =
      x * (1.0 + x2 * (-0.166666672 + x2 * (0.00833333377 + x2 * (-0.000198412701 + x2 * 2.75573188e-06))));
  precise float cosine = 1.0 + x2 * (-0.5 + x2 * (0.0416666679 + x2 * (-0.00138888892 + x2 * 2.48015876e-05)));
  const uint quadrant = uint(k) & 3u;
  if (quadrant == 0u) return vec2(cosine, sine);
  if (quadrant == 1u) return vec2(-sine, cosine);
  if (quadrant == 2u) return vec2(-cosine, -sine);
  return vec2(sine, -cosine);
}

// The formula's T_k: the primary guide's way at its vertex k.
vec3 wayAt(uint guide, uint k) {
  precise vec3 way = guidePoint(guide, min(k + 1u, counts.guideVertexCount - 1u)) - guidePoint(guide, max(k, 1u) - 1u);
  return way;
}

// The curl's side carried down a strand: the primary guide's point, way and side at the last
// vertex (the formula's x', d', a').
struct CurlSide {
  vec3 x;
  vec3 d;
  vec3 a;
};

// The formula's v − (2·dot(v1, v) / c1)·v1.
vec3 reflect3(vec3 v, vec3 v1, float c1) {
  precise float scale = (2.0 * dot3(v1, v)) / c1;
  precise vec3 reflected = v - scale * v1;
  return reflected;
}

// The formula's W + F: the curl and frizz of dense vertex i (`vertex` = s·Nd + i) at t, fraction f
// of segment v of the primary guide, whose point there is `l0`, in the frame (e1, e2, n); `side`
// holds vertex i − 1's and takes vertex i's.
vec3 curlAndFrizz(DenseStrand strand, uint v, float f, float t, vec3 l0, uint i, uint vertex, vec3 e1, vec3 e2,
                  vec3 n, inout CurlSide side) {
  precise vec3 along = (1.0 - f) * wayAt(strand.guides.x, v) + f * wayAt(strand.guides.x, v + 1u);
  const vec3 d = dot3(along, along) > 0.0 ? normalize3(along) : n;
  vec3 a;
  if (i == 0u) {
    const vec3 across = cross3(d, n);
    a = dot3(across, across) > 0.0 ? normalize3(across) : e1;
  } else {
    precise vec3 v1 = l0 - side.x;
    const float c1 = dot3(v1, v1);
    const vec3 aL = c1 > 0.0 ? reflect3(side.a, v1, c1) : side.a;
    const vec3 dL = c1 > 0.0 ? reflect3(side.d, v1, c1) : side.d;
    precise vec3 v2 = d - dL;
    const float c2 = dot3(v2, v2);
    const vec3 r = c2 > 0.0 ? reflect3(aL, v2, c2) : aL;
    precise vec3 across = r - dot3(r, d) * d;
    a = dot3(across, across) > 0.0 ? normalize3(across) : side.a;
  }
  side = CurlSide(l0, d, a);
  const vec3 b = cross3(d, a);
  precise float w = strand.curl.z + strand.curl.y * t;
  const vec2 cs = cosSinTurns(w);
  precise float radius = strand.curl.x * min(4.0 * t, 1.0);
  precise vec3 curl = (cs.x * radius) * a + (cs.y * radius) * b;
  precise float x0 = float(lowbias32(3u * vertex) >> 8) * 1.1920929e-07 - 1.0;
  precise float x1 = float(lowbias32(3u * vertex + 1u) >> 8) * 1.1920929e-07 - 1.0;
  precise float x2 = float(lowbias32(3u * vertex + 2u) >> 8) * 1.1920929e-07 - 1.0;
  precise vec3 frizz = (strand.curl.w * t) * ((x0 * e1 + x1 * e2) + x2 * n);
  precise vec3 sum = curl + frizz;
  return sum;
}

// Step 2 of the formula for dense vertex i; `offset` = O and `jitter` = J from step 1, `first`
// the strand's first vertex s·Nd.
vec3 densePoint(DenseStrand strand, uint i, vec3 offset, vec3 jitter, uint first, vec3 e1, vec3 e2, vec3 n,
                inout CurlSide side) {
  precise float u = float(i) * strand.weights.w;
  const uint v = min(uint(u), counts.guideVertexCount - 2u);
  precise float f = u - float(v);
  const vec4 w = curveWeights(f);
  precise vec3 l0 = alongGuide(strand.guides.x, v, w);
  precise vec3 b = strand.weights.x * l0;
  if (strand.guides.w > 1u) b = b + strand.weights.y * alongGuide(strand.guides.y, v, w);
  if (strand.guides.w > 2u) b = b + strand.weights.z * alongGuide(strand.guides.z, v, w);
  precise float t = float(i) / float(counts.vertexCount - 1u);
  precise float h = strand.rootOffset.w * t;
  precise float q = 1.0 - h;
  precise vec3 p = (b + h * (l0 - b)) + q * (offset + t * jitter);
  if (strand.curl.x > 0.0 || strand.curl.w > 0.0) p = p + curlAndFrizz(strand, v, f, t, l0, i, first + i, e1, e2, n, side);
  return p;
}

void main() {
  const uint s = gl_GlobalInvocationID.x;
  if (s >= counts.strandCount) return;
  const DenseStrand strand = strands[s];

  // Step 1: the primary guide's frame from the roots of the guide and its two partners.
  const uint primary = strand.guides.x;
  const uvec2 partners = guideFrames[primary];
  precise vec3 e1 = vec3(1.0, 0.0, 0.0);
  precise vec3 e2 = vec3(0.0, 1.0, 0.0);
  precise vec3 n = vec3(0.0, 0.0, 1.0);
  if (partners.x != primary || partners.y != primary) {
    const vec3 root = guidePoint(primary, 0u);
    precise vec3 toA = guidePoint(partners.x, 0u) - root;
    precise vec3 toB = guidePoint(partners.y, 0u) - root;
    e1 = normalize3(toA);
    n = normalize3(cross3(e1, toB));
    e2 = cross3(n, e1);
  }
  const vec3 o = strand.rootOffset.xyz;
  const vec3 j = strand.tipJitter.xyz;
  precise vec3 offset = (o.x * e1 + o.y * e2) + o.z * n;
  precise vec3 jitter = (j.x * e1 + j.y * e2) + j.z * n;

  // Steps 2 and 3 over a sliding window (previous, current, next) with P[−1] := P[0] and
  // P[Nd] := P[Nd − 1].
  const uint nd = counts.vertexCount;
  const uint first = s * nd;
  // Vertices are placed in order, root to tip: the curl's side is carried from each to the next.
  CurlSide side = CurlSide(vec3(0.0), vec3(0.0), vec3(0.0));
  vec3 current = densePoint(strand, 0u, offset, jitter, first, e1, e2, n, side);
  vec3 previous = current;
  for (uint i = 0u; i < nd; ++i) {
    const vec3 next = i + 1u < nd ? densePoint(strand, i + 1u, offset, jitter, first, e1, e2, n, side) : current;
    precise vec3 delta = next - previous;
    const vec3 tangent = dot3(delta, delta) > 0.0 ? normalize3(delta) : vec3(0.0);
    precise float t = float(i) / float(nd - 1u);
    positions[first + i] = vec4(current, t);
    tangents[first + i] = vec4(tangent, 0.0);
    previous = current;
    current = next;
  }
}
