#version 450
// Hair density, the splat (render/passes/hair_density_pass.hpp): one invocation per dense segment
// cuts it into pieces no longer than half a voxel and adds each piece's optical depth across a
// voxel, in 1/2²⁰ units, to the voxel holding the piece's middle. Integer atomics: the sums do not
// depend on the order the invocations run in.

layout(local_size_x = 64) in;

// The strands as the interpolation wrote them (xyz metres, strand-major), read as a texel buffer:
// lavapipe gathers a texel fetch's lanes at once.
layout(set = 0, binding = 0) uniform samplerBuffer positions;
layout(set = 0, binding = 1, std430) buffer Density {
  uint density[];  // voxel (x, y, z) at (z·ny + y)·nx + x
};

layout(push_constant) uniform Splat {
  vec4 grid;     // xyz: the grid's lowest corner, metres; w: voxels per metre
  uvec4 voxels;  // xyz: voxels along each axis (nx, ny, nz)
  uvec4 counts;  // x: segments, y: vertices per strand
  vec4 depth;    // x: fixed-point units of optical depth across a voxel per metre of fibre
} splat;

// A segment longer than this many pieces (32 voxels) is not hair the strands interpolate.
const int kMaxPieces = 64;

void main() {
  uint segment = gl_GlobalInvocationID.x;
  if (segment >= splat.counts.x) return;
  uint segmentsPerStrand = splat.counts.y - 1u;
  int first = int((segment / segmentsPerStrand) * splat.counts.y + segment % segmentsPerStrand);
  vec3 a = (texelFetch(positions, first).xyz - splat.grid.xyz) * splat.grid.w;  // voxels
  vec3 b = (texelFetch(positions, first + 1).xyz - splat.grid.xyz) * splat.grid.w;
  float span = distance(a, b);  // voxels
  int pieces = clamp(int(ceil(2.0 * span)), 1, kMaxPieces);
  uint weight = uint(splat.depth.x * (span / splat.grid.w) / float(pieces) + 0.5);
  ivec3 voxels = ivec3(splat.voxels.xyz);
  // Tested at the end: lavapipe runs a loop's body once more, every lane masked off, before a test
  // at the top ends it (docs/lavapipe.md#loops-test-at-the-end).
  int piece = 0;
  do {
    ivec3 voxel = ivec3(floor(mix(a, b, (float(piece) + 0.5) / float(pieces))));
    if (all(greaterThanEqual(voxel, ivec3(0))) && all(lessThan(voxel, voxels)))
      atomicAdd(density[(voxel.z * voxels.y + voxel.y) * voxels.x + voxel.x], weight);
  } while (++piece < pieces);
}
