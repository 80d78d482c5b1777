#version 450
#extension GL_GOOGLE_include_directive : require
// The projected grid's vertices (render/passes/ocean_pass.hpp), once each: every vertex where its
// eye ray meets the sea at rest, displaced by the waves, with its normal, Jacobian and spacing.
// shaders/ocean.vert draws them. (A vertex shader would evaluate the waves again for every
// triangle batch that shares a vertex.)
layout(local_size_x = 64) in;
#define OCEAN_SET 0
#include "ocean_uniforms.glsl"
#include "ocean_waves.glsl"
#include "ocean_grid.glsl"

layout(set = 0, binding = 1, std430) writeonly buffer Grid { OceanGridVertex vertices[]; };

// The grid overhangs the screen by a tenth on each side, and its border vertices rest farther out
// by as far as the waves can move water sideways, so that waves that move its edge keep the
// screen covered. Each frame computes only the rows that hold sea (ocean.gridRows).
const float kOverhang = 1.1;  // kOceanGridOverhang (render/passes/ocean_pass.hpp)

// Where the eye ray through `ndc` meets the sea at rest, (x, z): rays at or above the horizon,
// and those that would meet the sea beyond the grid's reach, end at the reach.
vec2 restPoint(vec2 ndc) {
  vec4 near = ocean.clipToWorld * vec4(ndc, 0.0, 1.0);
  vec4 far = ocean.clipToWorld * vec4(ndc, 1.0, 1.0);
  vec3 direction = far.xyz / far.w - near.xyz / near.w;
  vec2 across = direction.xz;
  float acrossLength = max(length(across), 1e-9);
  float reach = ocean.eye.w;
  // Horizontal distance to the sea: eye height × |across| / −dy, where the ray goes down.
  float distance = direction.y < 0.0 ? min(ocean.eye.y * acrossLength / -direction.y, reach) : reach;
  return ocean.eye.xz + across / acrossLength * distance;
}

void main() {
  int across = int(ocean.shape.z) + 1;
  int index = int(gl_GlobalInvocationID.x);
  if (index >= across * (int(ocean.gridRows.y) + 1)) return;
  ivec2 cell = ivec2(index % across, index / across + int(ocean.gridRows.x));
  vec2 step = 2.0 * kOverhang / ocean.shape.zw;
  vec2 ndc = vec2(cell) * step - kOverhang;
  vec2 rest = restPoint(ndc);
  ivec2 last = ivec2(ocean.shape.zw);
  ivec2 outward = ivec2(cell.x == 0 ? -1 : cell.x == last.x ? 1 : 0, cell.y == 0 ? -1 : cell.y == last.y ? 1 : 0);
  if (outward != ivec2(0)) {
    vec2 away = rest - restPoint(ndc - vec2(outward) * step);
    float length = length(away);
    if (length > 0.0) rest += away / length * ocean.reachOfWaves.x;
  }
  // The grid's spacing here: the larger of the distances to the next vertices across and down.
  float footprint = max(distance(rest, restPoint(ndc + vec2(step.x, 0.0))),
                        distance(rest, restPoint(ndc + vec2(0.0, step.y))));
  OceanPoint point = oceanWaves(rest, footprint);
  OceanGridVertex vertex;
  vertex.world = vec4(vec3(rest.x, 0.0, rest.y) + point.displacement, point.jacobian);
  vertex.normal = vec4(point.normal, footprint);
  vertex.rest = vec4(rest, 0.0, 0.0);
  vertices[index] = vertex;
}
