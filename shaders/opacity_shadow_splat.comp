#version 450
#extension GL_GOOGLE_include_directive : require
// Opacity shadow map, compute builder, step 1 (render/passes/opacity_shadow_map_pass.hpp): one thread
// per segment walks its columns along the major axis (those whose centres lie in [start, end),
// as a line rasterizer does), covers in each the texels the graphics pass's lines would (see
// below), and adds their weight in 16.16 fixed point to the first slice at or beyond the depth
// there (k = ceil(16·z) − 1). One integer atomic per texel; step 2 (opacity_shadow_resolve.comp) sums
// the slices, so the result does not depend on the order the threads run in.
#include "opacity_shadow_build.glsl"

layout(local_size_x = 64) in;

// 16 slice increments per texel, texel after texel (row-major), 16.16 fixed point.
layout(set = 0, binding = 2, std430) buffer Increments {
  uint increments[];
};

const float kFixedOne = 65536.0;

// Adds `weight` to `slice`'s increment of `texel` in a map of size × size texels.
void add(ivec2 texel, int size, uint slice, uint weight) {
  atomicAdd(increments[(uint(texel.y) * uint(size) + uint(texel.x)) * 16u + slice], weight);
}

// The same positions as the storage buffer `positions`, read as a texel buffer: lavapipe loads a
// storage buffer lane by lane at per-lane addresses, where a texel fetch gathers them at once.
layout(set = 0, binding = 4) uniform samplerBuffer positionTexels;

void main() {
  uint segment = gl_GlobalInvocationID.x;
  if (segment >= build.counts.z) return;
  int vertex = int(segmentStart(segment));
  vec4 a = build.lightFromWorld * vec4(texelFetch(positionTexels, vertex).xyz, 1.0);
  vec4 b = build.lightFromWorld * vec4(texelFetch(positionTexels, vertex + 1).xyz, 1.0);
  float resolution = build.weights.z;
  vec3 pa = vec3((a.xy * 0.5 + 0.5) * resolution, a.z);
  vec3 pb = vec3((b.xy * 0.5 + 0.5) * resolution, b.z);
  vec3 delta = pb - pa;
  bool alongX = abs(delta.x) >= abs(delta.y);
  float major = alongX ? delta.x : delta.y;
  if (major == 0.0) return;  // a point: no column centre is crossed, as for the rasterizer
  // Rectangular lines (strictLines): the texels whose centres lie within half a texel of the
  // line, 1 to 2 per column, each α·2r/s; otherwise one texel per column carrying the length
  // |Δ|/|major| it stands for.
  bool rectangular = build.weights.y > 0.5;
  float length2d = length(delta.xy);
  float perTexel = rectangular ? build.weights.x : build.weights.x * (length2d / abs(major));
  float halfSpan = rectangular ? 0.5 * length2d / abs(major) : 0.0;  // across the columns, texels
  uint fixedWeight = uint(perTexel * kFixedOne + 0.5);
  float start = alongX ? pa.x : pa.y;
  float low = min(start, start + major), high = max(start, start + major);
  int size = int(resolution);
  int first = max(int(ceil(low - 0.5)), 0);
  int last = min(int(ceil(high - 0.5)) - 1, size - 1);
  // Tested at the end (`continue` goes there): lavapipe runs a loop's body once more, every lane
  // masked off, before a test at the top ends it.
  int column = first;
  if (first <= last) do {
    float t = (float(column) + 0.5 - start) / major;
    vec3 p = pa + t * delta;
    if (p.z < 0.0 || p.z > 1.0) continue;
    uint slice = uint(clamp(ceil(p.z * 16.0) - 1.0, 0.0, 15.0));
    float minor = alongX ? p.y : p.x;
    int rowLow = rectangular ? int(ceil(minor - halfSpan - 0.5)) : int(floor(minor));
    int rowHigh = rectangular ? int(floor(minor + halfSpan - 0.5)) : rowLow;
    // At most two rows, as the span across is 2·halfSpan ≤ √2 texels: two tests rather than a
    // loop, which lavapipe runs slower here (docs/lavapipe.md#loops-test-at-the-end).
    int row = max(rowLow, 0), lastRow = min(rowHigh, size - 1);
    if (row <= lastRow) add(alongX ? ivec2(column, row) : ivec2(row, column), size, slice, fixedWeight);
    if (row + 1 <= lastRow) add(alongX ? ivec2(column, row + 1) : ivec2(row + 1, column), size, slice, fixedWeight);
  } while (++column <= last);
}
