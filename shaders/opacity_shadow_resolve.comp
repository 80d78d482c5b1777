#version 450
// Opacity shadow map, compute builder, step 2 (render/passes/opacity_shadow_map_pass.hpp): slice k of
// a texel is the sum of its increments 0..k (opacity_shadow_splat.comp), converted from 16.16
// fixed point and stored where the graphics builder's blending puts it (layer k/4, channel k%4).
// It leaves the increments zero for the next frame's splat: cheaper than clearing the buffer in a
// pass of its own.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 2, std430) buffer Increments {
  uvec4 increments[];  // a texel's 16 slices in 4 loads
};
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2DArray slices;

layout(push_constant) uniform Build {
  mat4 lightFromWorld;
  vec4 weights;  // z resolution
  uvec4 counts;
} build;

void main() {
  uint size = uint(build.weights.z);
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (texel.x >= size || texel.y >= size) return;
  uint base = (texel.y * size + texel.x) * 4u;
  uint sum = 0u;
  for (int layer = 0; layer < 4; ++layer) {
    uvec4 added = increments[base + uint(layer)];
    increments[base + uint(layer)] = uvec4(0u);
    vec4 value;
    for (int channel = 0; channel < 4; ++channel) {
      sum += added[channel];
      value[channel] = float(sum) / 65536.0;
    }
    imageStore(slices, ivec3(texel, layer), value);
  }
}
