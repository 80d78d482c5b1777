#version 450
#extension GL_GOOGLE_include_directive : require
// Chooses the hair pass's primitive for the frame (render/passes/hair_pass.hpp, "Lines").
// kWriteDraws false, one invocation per dense strand: sums the strand's widths on screen at its
// vertices and the part of them lines of the minimum width would not cover, and counts the
// vertices wider than that. kWriteDraws true, one invocation: enables the line draw when lines
// may be drawn and lose at most kLineCoverageLoss of the width, the ribbon draw otherwise, and
// zeroes the sums for the next frame.
#include "hair_uniforms.glsl"

layout(constant_id = 0) const bool kWriteDraws = false;

// The share of the strands' summed width that lines may leave uncovered (HairPass's file comment).
const float kLineCoverageLoss = 0.01;
// Widths are summed in units of 1/4096 of the line width, each capped at 1024 line widths, into
// 64-bit sums (two words): exact, so they do not depend on the order the strands add in.
const float kWidthUnits = 4096.0;
const float kLargestWidth = 1024.0;

layout(set = 0, binding = 1, std430) readonly buffer Positions {
  vec4 positions[];  // xyz metres, w = t along the strand
};
layout(set = 0, binding = 2, std430) readonly buffer Tangents {
  vec4 tangents[];  // xyz unit tangent root → tip
};

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
};

// Mirrors PrimitiveDraws in render/passes/hair_pass.cpp.
layout(set = 0, binding = 5, std430) buffer Primitives {
  IndexedDraw ribbons;
  IndexedDraw lines;
  Sums sums;    // added to by the strands; zeroed by the choice, for the next frame
  Sums chosen;  // what the last choice was made from
} primitives;

layout(local_size_x = 64) in;

float sum64(uint low, uint high) {
  return float(high) * 4294967296.0 + float(low);
}

void add64(inout uvec2 sum, uint value) {
  uint carry;
  sum.x = uaddCarry(sum.x, value, carry);
  sum.y += carry;
}

void main() {
  if (kWriteDraws) {
    if (gl_LocalInvocationIndex != 0u) return;  // one invocation reads the sums and zeroes them
    Sums sums = primitives.sums;
    bool lines = hair.counts.z != 0u && sum64(sums.lostLow, sums.lostHigh) <=
                                            kLineCoverageLoss * sum64(sums.widthLow, sums.widthHigh);
    primitives.ribbons.instanceCount = lines ? 0u : 1u;
    primitives.lines.instanceCount = lines ? 1u : 0u;
    primitives.chosen = sums;
    primitives.sums = Sums(0u, 0u, 0u, 0u, 0u);
    return;
  }
  // Rows of workgroups past the 65,535 one dimension is sure to allow.
  uint strand = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
  if (strand >= hair.counts.x) return;
  // One strand per invocation keeps the sums in registers: three atomic adds per strand, not per vertex.
  uint wide = 0u;
  uvec2 width = uvec2(0u), lost = uvec2(0u);
  for (uint vertex = strand * hair.counts.y; vertex < (strand + 1u) * hair.counts.y; ++vertex) {
    HairRibbon ribbon = hairRibbon(positions[vertex], tangents[vertex].xyz);
    float lineWidths = min(ribbon.halfWidth / ribbon.minimumHalfWidth, kLargestWidth);
    add64(width, uint(round(lineWidths * kWidthUnits)));
    if (lineWidths > 1.0) {
      ++wide;
      add64(lost, uint(round((lineWidths - 1.0) * kWidthUnits)));
    }
  }
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
