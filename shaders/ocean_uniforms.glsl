// The sea's constants and this frame's phases (render/passes/ocean_pass.hpp), at set OCEAN_SET of
// the ocean's shaders (1 by default: the draw binds the surfaces' frame set first). Mirrors
// OceanUniforms in render/passes/ocean_pass.cpp (vectors of four floats: std430 lays them out as
// std140 would).

const int kMaxOceanWaves = 64;
const int kMaxFoamSources = 64;

#ifndef OCEAN_SET
#define OCEAN_SET 1
#endif
// A storage buffer, not a uniform block: lavapipe folds a uniform block's values into the branches
// and loop counts that depend on them and compiles the shader again at every bind
// (docs/lavapipe.md, "Shader recompiles on bind"); the wave loop's count is one.
layout(set = OCEAN_SET, binding = 0, std430) readonly buffer Ocean {
  mat4 clipToWorld;      // the inverse of the frame's view-projection
  vec4 eye;              // xyz: the camera, metres; w: how far the grid reaches from it, metres
  vec4 shape;            // x: the choppiness λ; y: waves; z, w: the grid's cells across and down
  vec4 waves[kMaxOceanWaves];  // direction (x, z), wavenumber k (1/m), amplitude A (m)
  vec4 phases[kMaxOceanWaves / 4];  // φ − ω t of each wave this frame, four to a vector
  vec4 water;            // rgb: what the water scatters up from below, per unit of light; a: Fresnel's exponent
  vec4 sky;              // rgb: the sky's radiance where there is no environment
  vec4 fog;              // rgb: its colour where there is no environment; a: its density, 1/m
  vec4 foam;             // rgb: its albedo; a: J under which crests break
  vec4 foamMap;          // xy: the foam map's lowest corner (x, z) at rest, m; z: 1/its side, 1/m; w: texels a side
  vec4 foamStep;         // x: what the foam keeps this frame, 2^(−Δt/T½); y: what a breaking crest adds; z: foam sources
  vec4 reachOfWaves;     // x: the farthest the waves move water sideways, λ Σ A, metres
  vec4 foamSources[kMaxFoamSources];  // (x, z) at rest, m; 1/r², 1/m²; what it adds this frame at its centre
  mat4 reflectorFromWorld;  // the ellipsoid round what hides the sky in the reflection, to the unit sphere
  vec4 reflector;           // rgb: its albedo; a: 1 where there is one
  vec4 gridRows;            // x: the grid's first row this frame holds (those above hold no sea); y: how many
} ocean;

float oceanPhase(int wave) { return ocean.phases[wave / 4][wave % 4]; }
