#version 450
// Hair density, the visibility (render/passes/hair_density_pass.hpp): from each voxel's centre,
// the hair's transmittance along kDirections directions, marched a voxel at a time, projected on the
// first two spherical-harmonic bands and stored as occlusion (−b, 1 − a), V(ω) ≈ a + b·ω.

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(set = 0, binding = 0) uniform usamplerBuffer density;  // 1/2²⁰ units across a voxel
layout(set = 0, binding = 1, rgba16f) uniform writeonly image3D occlusion;

layout(push_constant) uniform Visibility {
  uvec4 voxels;  // xyz: the grid's voxels along each axis, in the image's lowest corner; w: voxels marched
} visibility;

const int kDirections = 16;

float depthAt(ivec3 voxel, ivec3 voxels) {
  if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, voxels))) return 0.0;
  return float(texelFetch(density, (voxel.z * voxels.y + voxel.y) * voxels.x + voxel.x).x) * (1.0 / 1048576.0);
}

void main() {
  ivec3 voxels = ivec3(visibility.voxels.xyz);
  ivec3 voxel = ivec3(gl_GlobalInvocationID);
  // The image past the grid: nothing hidden.
  if (any(greaterThanEqual(voxel, voxels))) {
    imageStore(occlusion, voxel, vec4(0.0));
    return;
  }
  vec3 centre = vec3(voxel) + 0.5;
  float own = 0.5 * depthAt(voxel, voxels);
  int steps = int(visibility.voxels.w);
  float mean = 0.0;
  vec3 first = vec3(0.0);
  // A spherical Fibonacci set: equal areas, no direction favoured (a small rule's axes would put
  // a third of their weight on the plane a scalp's hair grazes).
  for (int d = 0; d < kDirections; ++d) {
    float z = 1.0 - (2.0 * float(d) + 1.0) / float(kDirections);
    float ring = sqrt(max(1.0 - z * z, 0.0));
    float turn = 2.399963230 * float(d);  // the golden angle
    vec3 direction = vec3(ring * cos(turn), ring * sin(turn), z);
    // A voxel's side per step: each adds the depth across one voxel of the voxel it lands in.
    float tau = own;
    int k = 1;
    do {
      tau += depthAt(ivec3(floor(centre + float(k) * direction)), voxels);
    } while (++k <= steps);
    float transmittance = exp(-tau);
    mean += transmittance;
    first += transmittance * direction;
  }
  mean /= float(kDirections);
  first /= float(kDirections);
  imageStore(occlusion, voxel, vec4(-3.0 * first, 1.0 - mean));
}
