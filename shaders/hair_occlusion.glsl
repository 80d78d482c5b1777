// The farthest depth of the opaque scene in each square tile of the frame
// (render/passes/hair_occlusion_pass.hpp), for HairPass to hide strands behind. One invocation per
// tile; define HAIR_OCCLUSION_SAMPLES (1: a single-sample depth image) before including.

#if HAIR_OCCLUSION_SAMPLES == 1
layout(set = 0, binding = 0) uniform sampler2D opaqueDepth;
#else
layout(set = 0, binding = 0) uniform sampler2DMS opaqueDepth;
#endif

layout(set = 0, binding = 1, std430) writeonly buffer Tiles {
  float tileMaxDepth[];
};

layout(push_constant) uniform Grid {
  uvec2 tiles;    // across and down
  uint tileSize;  // pixels
} grid;

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 tile = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(tile, grid.tiles))) return;
#if HAIR_OCCLUSION_SAMPLES == 1
  ivec2 size = textureSize(opaqueDepth, 0);
#else
  ivec2 size = textureSize(opaqueDepth);
#endif
  ivec2 first = ivec2(tile * grid.tileSize);
  ivec2 end = min(first + int(grid.tileSize), size);
  float farthest = 0.0;
  // Loops that test at the end, as a tile holds at least one pixel: lavapipe (Mesa 22.3) runs a
  // loop's body once more, every lane masked off, before a test at the top ends it.
#if HAIR_OCCLUSION_SAMPLES == 1
  // Four texels a read: the 2 × 2 block whose shared corner is at (x + 1, y + 1). Past the
  // image's edge the sampler clamps, repeating texels of the tile.
  vec2 texel = 1.0 / vec2(size);
  int y = first.y;
  do {
    int x = first.x;
    do {
      vec4 block = textureGather(opaqueDepth, vec2(x + 1, y + 1) * texel);
      farthest = max(farthest, max(max(block.x, block.y), max(block.z, block.w)));
      x += 2;
    } while (x < end.x);
    y += 2;
  } while (y < end.y);
#else
  int y = first.y;
  do {
    int x = first.x;
    do {
      for (int s = 0; s < HAIR_OCCLUSION_SAMPLES; ++s)
        farthest = max(farthest, texelFetch(opaqueDepth, ivec2(x, y), s).r);
      ++x;
    } while (x < end.x);
    ++y;
  } while (y < end.y);
#endif
  tileMaxDepth[tile.y * grid.tiles.x + tile.x] = farthest;
}
