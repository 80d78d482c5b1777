#version 450
#extension GL_GOOGLE_include_directive : require
// The hair pass's per-frame choices (render/passes/hair_pass.hpp): the primitive ("Lines") and
// the segments left out because the opaque scene hides them ("Hidden strands"), in three steps.
// kStep 0, one invocation per dense strand: sums the strand's widths on screen at its vertices and
//   the part of them lines of the minimum width would not cover, counts the vertices wider than
//   that; marks its segments visible or hidden, and counts its vertices hidden, those whose
//   segments both are. It also writes each vertex as hair_line.vert draws it: its clip
//   position and its coverage or, with analytic coverage, its width and direction on screen.
// kStep 1, one workgroup: enables the line draw when lines may be drawn and lose at most
//   kLineCoverageLoss of the width, the ribbon draw otherwise, and zeroes the sums for the next
//   frame; adds up the visible segments in drawing order (each strand's first index) and sets
//   both draws' index counts.
// kStep 2, one invocation per strand in drawing order: writes the chosen draw's indices of its
//   visible segments. Integer sums in a fixed order throughout: the frame does not depend on the
//   order the invocations run in.
#include "hair_uniforms.glsl"
#include "hair_coverage.glsl"

layout(constant_id = 0) const uint kStep = 0u;
// One sample per pixel: the ribbons are drawn a pixel's reach wider, and the lines carry what
// hair_line.frag needs to find each pixel's coverage (hair_coverage.glsl).
layout(constant_id = 1) const bool kAnalyticCoverage = false;

// The share of the strands' summed width that lines may leave uncovered (HairPass's file comment).
const float kLineCoverageLoss = 0.01;
// Widths are summed in units of 1/4096 of the line width, each capped at 1024 line widths, into
// 64-bit sums (two words): exact, so they do not depend on the order the strands add in.
const float kWidthUnits = 4096.0;
const float kLargestWidth = 1024.0;

// The strands as texel buffers, not storage buffers: lavapipe loads a storage buffer lane by lane
// (render/passes/hair_pass.hpp, "Lines").
layout(set = 0, binding = 14) uniform samplerBuffer positionTexels;  // xyz metres, w = t along the strand
layout(set = 0, binding = 15) uniform samplerBuffer tangentTexels;   // xyz unit tangent root → tip
layout(set = 0, binding = 16) uniform samplerBuffer hairStrandLooks;
#include "hair_strand_look.glsl"

// VkDrawIndexedIndirectCommand.
struct IndexedDraw {
  uint indexCount;
  uint instanceCount;
  uint firstIndex;
  int vertexOffset;
  uint firstInstance;
};

// The vertices wider than the line width, and two 64-bit sums in kWidthUnits: Σ width on screen and
// Σ max(width − line width, 0), what lines leave uncovered. Words only, so that the layout is the
// same in C++.
struct Sums {
  uint wideVertices;
  uint widthLow;
  uint widthHigh;
  uint lostLow;
  uint lostHigh;
  uint hiddenVertices;
};

// Mirrors PrimitiveDraws in render/passes/hair_pass.cpp.
layout(set = 0, binding = 5, std430) buffer Primitives {
  IndexedDraw ribbons;
  IndexedDraw lines;
  Sums sums;    // added to by the strands; zeroed by the choice, for the next frame
  Sums chosen;  // what the last choice was made from
} primitives;

// The farthest depth of the opaque scene in each tile of hair.occlusion.z² pixels, row-major.
layout(set = 0, binding = 6, std430) readonly buffer OpaqueDepth {
  float tileMaxDepth[];
};
// Per strand: its visible segments (low 16 bits) and vertices to shade, those with a visible
// segment (high 16 bits; Nd ≤ 4096), and a bit per segment (set: visible), segmentWords() words.
layout(set = 0, binding = 7, std430) buffer VisibleSegments {
  uint visibleCounts[];
};
layout(set = 0, binding = 8, std430) buffer SegmentBits {
  uint visibleBits[];
};
// Per strand in drawing order: the visible segments (x) and the vertices to shade (y) of the
// strands drawn before it.
layout(set = 0, binding = 9, std430) buffer FirstSegments {
  uvec2 firstSegments[];
};
// The draws' index buffer: the ribbons' indices from 0, the lines' from hair.counts.w.
layout(set = 0, binding = 10, std430) writeonly buffer Indices {
  uint indices[];
};
// The vertices HairLightingPass shades, after its indirect dispatch (xyz) and their count (w).
layout(set = 0, binding = 11, std430) buffer ShadeList {
  uvec4 dispatch;
  uint shaded[];
} shadeList;
layout(set = 0, binding = 4, std430) readonly buffer DrawOrder {
  uint order[];  // strand indices in the order they are drawn
};
// The line draw's vertex attributes (hair_line.vert), per dense vertex.
layout(set = 0, binding = 12, std430) writeonly buffer LineClips {
  vec4 lineClips[];
};
layout(set = 0, binding = 13, std430) writeonly buffer LineWidths {
  vec4 lineWidths[];  // hair_line.vert's inWidth
};

shared uvec2 partialSums[64];

// A strand's visible segments (x) and vertices to shade (y) from their packed word.
uvec2 unpackCounts(uint packed) {
  return uvec2(packed & 0xffffu, packed >> 16u);
}

uint segmentWords() {
  return (hair.counts.y + 30u) / 32u;  // Nd − 1 bits
}

layout(local_size_x = 64) in;

// Pixels added around a segment's box: half the line width and a pixel for the rasterizer's
// rounding. Depths are compared with a margin for the float rounding of the interpolated depth.
float boxMargin() {
  return 0.5 * hair.viewport.z + 1.0;
}
const float kDepthMargin = 1e-6;
// A box over more tiles than this is taken as visible rather than searched.
const int kMostTiles = 64;

// Where a ribbon point lands: its centre and its two drawn edges.
struct ScreenPoint {
  vec2 low, high;  // pixel box of the three
  float nearest;   // smallest depth z/w of the three
  bool inFront;    // all three in front of the eye (w > 0)
  vec4 centre;     // clip position of the centre, as hair.vert computes a ribbon edge
  vec2 centrePixel;  // and its pixel
};

ScreenPoint screenPoint(vec3 centre, HairRibbon ribbon) {
  float drawn = hairDrawnHalfWidth(ribbon, kAnalyticCoverage);
  ScreenPoint point;
  point.low = vec2(1e30);
  point.high = vec2(-1e30);
  point.nearest = 1e30;
  point.inFront = true;
  for (int side = -1; side <= 1; ++side) {
    vec4 clip = hair.viewProjection * vec4(centre + ribbon.side * (float(side) * drawn), 1.0);
    point.inFront = point.inFront && clip.w > 0.0;
    vec2 pixel = (clip.xy / clip.w * 0.5 + 0.5) * hair.viewport.xy;
    if (side == 0) {
      point.centre = clip;
      point.centrePixel = pixel;
    }
    point.low = min(point.low, pixel);
    point.high = max(point.high, pixel);
    point.nearest = min(point.nearest, clip.z / clip.w);
  }
  return point;
}

// Whether every pixel the segment between a and b can touch (ribbon or line) has opaque surface
// nearer than any fragment of it. Depth is affine along a segment and across a ribbon's triangles
// on screen, so a triangle's fragments are no nearer than its corners; but a line's samples may
// lie past its ends (lavapipe draws multisampled lines as non-strict lines), where the depth is
// extrapolated: by less than the segment's whole depth range for a segment a pixel or longer.
bool segmentHidden(ScreenPoint a, ScreenPoint b) {
  if (!a.inFront || !b.inFront) return false;
  vec2 low = max(min(a.low, b.low) - boxMargin(), vec2(0.0));
  vec2 high = min(max(a.high, b.high) + boxMargin(), hair.viewport.xy - 1.0);
  if (any(greaterThan(low, high))) return true;  // off the screen: no fragments at all
  float nearest = min(a.nearest, b.nearest) - abs(a.nearest - b.nearest) - kDepthMargin;
  ivec2 first = ivec2(low) / int(hair.occlusion.z);
  ivec2 last = ivec2(high) / int(hair.occlusion.z);
  if ((last.x - first.x + 1) * (last.y - first.y + 1) > kMostTiles) return false;
  // The box holds a tile. Loops that test at the end: lavapipe (Mesa 22.3) runs a loop's body
  // once more, every lane masked off, before a test at the top ends it.
  int y = first.y;
  do {
    int x = first.x;
    do {
      if (tileMaxDepth[uint(y) * hair.occlusion.x + uint(x)] >= nearest) return false;
      ++x;
    } while (x <= last.x);
    ++y;
  } while (y <= last.y);
  return true;
}

float sum64(uint low, uint high) {
  return float(high) * 4294967296.0 + float(low);
}

void add64(inout uvec2 sum, uint value) {
  uint carry;
  sum.x = uaddCarry(sum.x, value, carry);
  sum.y += carry;
}

void choose() {
  if (gl_LocalInvocationIndex == 0u) {
    Sums sums = primitives.sums;
    bool lines = hair.counts.z != 0u && sum64(sums.lostLow, sums.lostHigh) <=
                                            kLineCoverageLoss * sum64(sums.widthLow, sums.widthHigh);
    primitives.ribbons.instanceCount = lines ? 0u : 1u;
    primitives.lines.instanceCount = lines ? 1u : 0u;
    primitives.chosen = sums;
    primitives.sums = Sums(0u, 0u, 0u, 0u, 0u, 0u);
  }
  // Each invocation adds up a run of strands in drawing order; then the runs' sums are added up
  // in order, and each run writes its strands' first segments.
  uint strands = hair.counts.x;
  uint run = (strands + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
  uint begin = min(gl_LocalInvocationIndex * run, strands), end = min(begin + run, strands);
  uvec2 sum = uvec2(0u);
  for (uint k = begin; k < end; ++k) sum += unpackCounts(visibleCounts[order[k]]);
  partialSums[gl_LocalInvocationIndex] = sum;
  barrier();
  uvec2 first = uvec2(0u);
  for (uint i = 0u; i < gl_LocalInvocationIndex; ++i) first += partialSums[i];
  for (uint k = begin; k < end; ++k) {
    firstSegments[k] = first;
    first += unpackCounts(visibleCounts[order[k]]);
  }
  if (gl_LocalInvocationIndex == gl_WorkGroupSize.x - 1u) {
    primitives.ribbons.indexCount = 6u * first.x;
    primitives.lines.indexCount = 2u * first.x;
    shadeList.dispatch = uvec4((first.y + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x, 1u, 1u, first.y);
  }
}

// Rows of workgroups past the 65,535 one dimension is sure to allow.
uint invocation() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
}

void writeIndices() {
  uint k = invocation();
  if (k >= hair.counts.x) return;
  uint strand = order[k];
  bool lines = primitives.lines.instanceCount != 0u;
  uint next = firstSegments[k].x;
  uint words = segmentWords();
  // Its vertices that a visible segment uses, to be shaded: vertex i joins segments i − 1 and i.
  uint shadedNext = firstSegments[k].y;
  uint first = strand * hair.counts.y, end = first + hair.counts.y;
  bool previousVisible = false;  // the root has no segment before it
  for (uint vertex = first; vertex < end; ++vertex) {
    uint i = vertex - first;
    bool visible = vertex + 1u < end && (visibleBits[strand * words + i / 32u] & 1u << (i % 32u)) != 0u;
    if (previousVisible || visible) shadeList.shaded[shadedNext++] = vertex;
    previousVisible = visible;
  }
  for (uint word = 0u; word < words; ++word) {
    uint bits = visibleBits[strand * words + word];
    while (bits != 0u) {
      int bit = findLSB(bits);
      bits &= bits - 1u;
      uint vertex = first + word * 32u + uint(bit);  // the segment from this vertex to the next
      if (lines) {
        indices[hair.counts.w + 2u * next] = vertex;
        indices[hair.counts.w + 2u * next + 1u] = vertex + 1u;
      } else {
        // Two triangles over the ribbon vertices 2·vertex + side (HairPass, strandIndices).
        uint minus = 2u * vertex;
        uint base = 6u * next;
        indices[base] = minus;
        indices[base + 1u] = minus + 2u;
        indices[base + 2u] = minus + 3u;
        indices[base + 3u] = minus;
        indices[base + 4u] = minus + 3u;
        indices[base + 5u] = minus + 1u;
      }
      ++next;
    }
  }
}

void main() {
  if (kStep == 1u) {
    choose();
    return;
  }
  if (kStep == 2u) {
    writeIndices();
    return;
  }
  uint strand = invocation();
  if (strand >= hair.counts.x) return;
  // One strand per invocation keeps the sums in registers: three atomic adds per strand, not per vertex.
  uint wide = 0u, hiddenCount = 0u, visible = 0u, bits = 0u;
  uvec2 width = uvec2(0u), lost = uvec2(0u);
  uint first = strand * hair.counts.y, end = first + hair.counts.y;
  uint words = segmentWords();
  ScreenPoint previous;
  float previousHalfPixels = 0.0;
  bool previousSegmentHidden = true;  // the root has no segment before it
  vec4 shape = hairStrandShape(strand);
  // A strand the level of detail leaves out is hidden whole, and adds nothing to the widths.
  bool kept = hairStrandKept(strand);
  uint vertex = first;
  do {  // a strand has at least two vertices; tested at the end, as segmentHidden's loops
    vec4 position = texelFetch(positionTexels, int(vertex));
    HairRibbon ribbon = hairRibbon(position, texelFetch(tangentTexels, int(vertex)).xyz, shape);
    // A vertex is hidden when both segments it joins are.
    ScreenPoint point = screenPoint(position.xyz, ribbon);
    // Written whichever draw is chosen: a branch on the uniforms alone would make lavapipe compile
    // this shader again every frame (tests/support/jit_compile_counter.hpp).
    lineClips[vertex] = point.centre;
    if (kAnalyticCoverage) {
      // A line's normal is that of the vertex starting it (hair_line.vert), written once the
      // segment's end is known; the tip takes its segment's.
      float halfPixels = ribbon.halfWidth * ribbon.pixelsPerMetre;
      if (vertex > first) {
        vec2 along = point.centrePixel - previous.centrePixel;
        vec2 direction = dot(along, along) > 1e-12 ? normalize(along) : vec2(ribbon.screenSide.y, -ribbon.screenSide.x);
        lineWidths[vertex - 1u] = vec4(previousHalfPixels, direction, shape.z);
        if (vertex + 1u == end) lineWidths[vertex] = vec4(halfPixels, direction, shape.z);
      }
      previousHalfPixels = halfPixels;
    } else {
      lineWidths[vertex] = vec4(ribbon.halfWidth / max(ribbon.halfWidth, ribbon.minimumHalfWidth) * shape.z, 0.0, 0.0, 0.0);
    }
    if (vertex > first) {
      uint segment = vertex - 1u - first;
      bool segmentIsHidden = !kept || segmentHidden(previous, point);
      hiddenCount += previousSegmentHidden && segmentIsHidden ? 1u : 0u;
      previousSegmentHidden = segmentIsHidden;
      visible += segmentIsHidden ? 0u : 1u;
      bits |= segmentIsHidden ? 0u : 1u << (segment % 32u);
      if (segment % 32u == 31u || vertex + 1u == end) {
        visibleBits[strand * words + segment / 32u] = bits;
        bits = 0u;
      }
    }
    previous = point;
    float lineWidths = kept ? min(ribbon.halfWidth / ribbon.minimumHalfWidth, kLargestWidth) : 0.0;
    add64(width, uint(round(lineWidths * kWidthUnits)));
    if (lineWidths > 1.0) {
      ++wide;
      add64(lost, uint(round((lineWidths - 1.0) * kWidthUnits)));
    }
    ++vertex;
  } while (vertex < end);
  hiddenCount += previousSegmentHidden ? 1u : 0u;  // the tip has no segment after it
  if (hiddenCount != 0u) atomicAdd(primitives.sums.hiddenVertices, hiddenCount);
  visibleCounts[strand] = visible | (hair.counts.y - hiddenCount) << 16u;
  // The add that wraps the low word carries one into the high word.
  uint before = atomicAdd(primitives.sums.widthLow, width.x);
  uint high = width.y + (before + width.x < before ? 1u : 0u);
  if (high != 0u) atomicAdd(primitives.sums.widthHigh, high);
  if (wide != 0u) {
    atomicAdd(primitives.sums.wideVertices, wide);
    before = atomicAdd(primitives.sums.lostLow, lost.x);
    high = lost.y + (before + lost.x < before ? 1u : 0u);
    if (high != 0u) atomicAdd(primitives.sums.lostHigh, high);
  }
}
