// Light through a translucent surface (render/passes/translucency_pass.hpp): the
// thickness d it crossed from where the first light entered to the shaded point, and what of it
// comes out. Include in surface.frag after frame_uniforms.glsl and the material block.
//
// Specialization constant 4 is the material's TranslucencyMethod: 0 none, 1 the depth map, 2 the
// voxelized thickness table.

layout(constant_id = 4) const uint kTranslucency = 0u;

// The voxelized thickness table of the mesh drawn (render/passes/thickness_table.hpp).
layout(set = 2, binding = 0, std140) uniform ThicknessGrid {
  vec4 origin;        // xyz: the grid's minimum corner, mesh units
  vec4 inverseVoxel;  // xyz: cells per mesh unit
  uvec4 size;         // x: N, y: M
  vec4 scale;         // x: mesh units per table unit
} grid;
layout(set = 2, binding = 1, std430) readonly buffer NearestSurfaceVoxel {
  uint nearestSurfaceVoxel[];
};
layout(set = 2, binding = 2, std430) readonly buffer ThicknessPairs {
  uint thicknessPairs[];  // M × M half floats, two per word
};

// Metres the first light travelled inside the surfaces of the depth map to reach `world`: its
// depth behind the first surface the light met there. Hollows and gaps on the way count. The
// entry depth is interpolated bilinearly between the four nearest texels (one gather): with the
// nearest texel alone, surfaces at a grazing angle to the light flicker between in front of and
// behind their own texel's depth, which speckles them in a moiré of the map's grid.
float depthMapThickness(vec3 world) {
  vec4 light = frame.lightDepth.lightFromWorld * vec4(world, 1.0);
  vec2 uv = light.xy * 0.5 + 0.5;
  vec4 depths = textureGather(lightDepthMap, uv, 0);  // (i0, j1), (i1, j1), (i1, j0), (i0, j0)
  vec2 f = fract(uv * float(textureSize(lightDepthMap, 0).x) - 0.5);
  float entry = mix(mix(depths.w, depths.z, f.x), mix(depths.x, depths.y, f.x), f.y);
  return max(light.z - entry, 0.0) * frame.lightDepth.scale.x;
}

// VoxelThicknessLut::surfaceVoxelAt: the surface voxel nearest the cell that holds `point`.
uint surfaceVoxelAt(vec3 point) {
  int n = int(grid.size.x);
  ivec3 cell = clamp(ivec3(floor((point - grid.origin.xyz) * grid.inverseVoxel.xyz)), ivec3(0), ivec3(n - 1));
  return nearestSurfaceVoxel[cell.x + n * (cell.y + n * cell.z)];
}

// VoxelThicknessLut::thicknessBetween, mesh units: hollows subtracted.
float voxelThickness(vec3 from, vec3 to) {
  uint pair = surfaceVoxelAt(from) * grid.size.y + surfaceVoxelAt(to);
  vec2 halves = unpackHalf2x16(thicknessPairs[pair >> 1u]);
  return ((pair & 1u) == 0u ? halves.x : halves.y) * grid.scale.x;
}

// Metres of material between light 0's entry point and the shaded point, by the pipeline's
// method. `objectPosition` is `world` in mesh units, `objectTowardLight` the light's direction
// there (mesh units per metre), `metresPerUnit` the instance's scale.
float translucentThickness(vec3 world, vec3 objectPosition, vec3 objectTowardLight, float metresPerUnit) {
  float depth = depthMapThickness(world);
  if (kTranslucency == 1u) return depth;
  // The entry: the shaded point moved towards the light by the depth map's thickness.
  return voxelThickness(objectPosition + objectTowardLight * depth, objectPosition) * metresPerUnit;
}

// How much of light 0's radiance leaves through the back: the transmittance after `thickness`
// metres times Jimenez et al.'s (2010) wrap max(0.3 − N·L, 0) ≤ 1, which fades the term in
// from the terminator instead of switching it on.
vec3 translucentLight(vec3 transmittance, vec3 geometricNormal) {
  return frame.lightRadiance[0].rgb * transmittance *
         clamp(0.3 - dot(geometricNormal, frame.lightDirection[0].xyz), 0.0, 1.0);
}
