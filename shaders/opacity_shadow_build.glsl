// Shared by the shaders that build opacity maps (render/passes/opacity_shadow_map_pass.hpp): the
// strand positions and the push constants (mirrors BuildConstants in opacity_shadow_map_pass.cpp).

// Strand-major vec4 positions: xyz metres, w ignored (StrandInterpolationPass's layout).
layout(set = 0, binding = 0, std430) readonly buffer StrandPositions {
  vec4 positions[];
};

layout(push_constant) uniform Build {
  mat4 lightFromWorld;  // world → (x, y ∈ [−1, 1], z = d/2R ∈ [0, 1])
  vec4 weights;         // x α·2r/s (opacity per texel of strand length), y 1 = rectangular lines,
                        // z resolution (texels), w deep layer spacing Δ in z
  uvec4 counts;         // x strands, y vertices per strand, z segments
} build;

// The vertex segment `segment` starts at; it ends at the next one.
uint segmentStart(uint segment) {
  uint perStrand = build.counts.y - 1u;
  uint strand = segment / perStrand;
  return strand * build.counts.y + (segment - strand * perStrand);
}

// Segment `segment`'s two ends in light space.
void segmentEnds(uint segment, out vec4 a, out vec4 b) {
  uint first = segmentStart(segment);
  a = build.lightFromWorld * vec4(positions[first].xyz, 1.0);
  b = build.lightFromWorld * vec4(positions[first + 1u].xyz, 1.0);
}
