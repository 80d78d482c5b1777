#version 450
#extension GL_GOOGLE_include_directive : require
// The environment's radiance projected on the nine real spherical harmonics
// (render/environment/harmonics_projection.hpp): Σ L·Y_i·dω over the cube's texels. One
// workgroup a row of a face: each invocation sums every 64th texel of the row, then the
// workgroup adds its 64 sums in a fixed tree and writes the row's nine, which the CPU adds up in
// a fixed order.
#include "cube_directions.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform sampler2DArray cube;  // the faces as layers; level 0 is read
layout(set = 0, binding = 1, std430) writeonly buffer Rows {
  vec4 sums[];  // [face][row][harmonic], rgb
} rows;

layout(push_constant) uniform Projection {
  uint size;  // texels a side
} projection;

shared vec3 partial[64][9];

void main() {
  uint row = gl_WorkGroupID.x, face = gl_WorkGroupID.y, lane = gl_LocalInvocationID.x;
  uint size = projection.size;
  float step = 2.0 / float(size);
  vec3 sum[9];
  for (int i = 0; i < 9; ++i) sum[i] = vec3(0.0);
  for (uint column = lane; column < size; column += 64u) {
    vec2 st = (vec2(column, row) + 0.5) / float(size);
    vec3 d = cubeDirection(face, st);
    // The texel's solid angle, ∫∫ (1 + x² + y²)^(−3/2) dx dy over it, by 2 × 2-point Gauss–Legendre
    // quadrature: the exact four-corner formula's difference of arctangents cancels in single
    // precision.
    vec2 xy = 2.0 * st - 1.0;
    float offset = 0.5 * step * 0.577350269;  // the Gauss points at ±1/√3 of the half-texel
    float solidAngle = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
      vec2 p = xy + offset * vec2((corner & 1) == 0 ? -1.0 : 1.0, (corner & 2) == 0 ? -1.0 : 1.0);
      solidAngle += 0.25 * step * step * pow(1.0 + dot(p, p), -1.5);
    }
    vec3 L = texelFetch(cube, ivec3(column, row, face), 0).rgb * solidAngle;
    // The real harmonics, normalised as in render/environment/spherical_harmonics.cpp.
    sum[0] += L * 0.282094792;
    sum[1] += L * (0.488602512 * d.y);
    sum[2] += L * (0.488602512 * d.z);
    sum[3] += L * (0.488602512 * d.x);
    sum[4] += L * (1.092548431 * d.x * d.y);
    sum[5] += L * (1.092548431 * d.y * d.z);
    sum[6] += L * (0.315391565 * (3.0 * d.z * d.z - 1.0));
    sum[7] += L * (1.092548431 * d.x * d.z);
    sum[8] += L * (0.546274215 * (d.x * d.x - d.y * d.y));
  }
  for (int i = 0; i < 9; ++i) partial[lane][i] = sum[i];
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1) {
    if (lane < stride)
      for (int i = 0; i < 9; ++i) partial[lane][i] += partial[lane + stride][i];
    barrier();
  }
  if (lane < 9u) rows.sums[(face * size + row) * 9u + lane] = vec4(partial[0][lane], 0.0);
}
