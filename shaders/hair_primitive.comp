#version 450
#extension GL_GOOGLE_include_directive : require
// Chooses the hair pass's primitive for the frame (render/passes/hair_pass.hpp, "Lines").
// kWriteDraws false, one invocation per dense vertex: sums the strands' widths on screen and the
// part of them lines of the minimum width would not cover, and counts the vertices wider than
// that. kWriteDraws true, one invocation: enables the line draw when lines may be drawn and lose
// at most kLineCoverageLoss of the width, the ribbon draw otherwise.
#include "hair_uniforms.glsl"

layout(constant_id = 0) const bool kWriteDraws = false;

// The share of the strands' summed width that lines may leave uncovered (HairPass's file comment).
const float kLineCoverageLoss = 0.01;
// Widths are summed in units of 1/4096 of the line width, each capped at 1024 line widths, so that
// a workgroup's sum fits 32 bits; the frame's sums are 64-bit (two words) and exact, so they do
// not depend on the order the workgroups add in.
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

// Mirrors PrimitiveDraws in render/passes/hair_pass.cpp; everything after `lines` is zeroed before
// the sums.
layout(set = 0, binding = 5, std430) buffer Primitives {
  IndexedDraw ribbons;
  IndexedDraw lines;
  uint wideVertices;
  uvec2 width;      // Σ width on screen, kWidthUnits per line width: low, high word
  uvec2 lostWidth;  // Σ max(width − line width, 0), the same units
} primitives;

layout(local_size_x = 64) in;

shared uint groupWide;
shared uint groupWidth;
shared uint groupLost;

float sum64(uvec2 words) {
  return float(words.y) * 4294967296.0 + float(words.x);
}

void main() {
  if (kWriteDraws) {
    bool lines = hair.counts.z != 0u &&
                 sum64(primitives.lostWidth) <= kLineCoverageLoss * sum64(primitives.width);
    primitives.ribbons.instanceCount = lines ? 0u : 1u;
    primitives.lines.instanceCount = lines ? 1u : 0u;
    return;
  }
  if (gl_LocalInvocationIndex == 0u) {
    groupWide = 0u;
    groupWidth = 0u;
    groupLost = 0u;
  }
  barrier();
  // Rows of workgroups past the 65,535 one dimension is sure to allow.
  uint vertex = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
  if (vertex < hair.counts.x * hair.counts.y) {
    HairRibbon ribbon = hairRibbon(positions[vertex], tangents[vertex].xyz);
    float width = min(ribbon.halfWidth / ribbon.minimumHalfWidth, kLargestWidth);  // in line widths
    atomicAdd(groupWidth, uint(round(width * kWidthUnits)));
    if (width > 1.0) {
      atomicAdd(groupWide, 1u);
      atomicAdd(groupLost, uint(round((width - 1.0) * kWidthUnits)));
    }
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    if (groupWide != 0u) atomicAdd(primitives.wideVertices, groupWide);
    // 64-bit sums: the add that wraps the low word carries one into the high word.
    uint before = atomicAdd(primitives.width.x, groupWidth);
    if (before + groupWidth < before) atomicAdd(primitives.width.y, 1u);
    before = atomicAdd(primitives.lostWidth.x, groupLost);
    if (before + groupLost < before) atomicAdd(primitives.lostWidth.y, 1u);
  }
}
