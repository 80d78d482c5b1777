// The sum of Gerstner waves of physics/ocean_waves.hpp, for the water that rests at `rest`
// (x, z): its displacement, its normal and the Jacobian of its horizontal map. Each wave's
// phase comes from the CPU (φ − ω t reduced to one turn), so both sides evaluate the same sum.
//
// `footprint` (metres, 0 for none) is the spacing of the samples: a wave shorter than four of
// them is faded out, and gone at two, since the samples could not follow it (it would alias and
// swim as the grid slides over the sea).
// Include after ocean_uniforms.glsl.

struct OceanPoint {
  vec3 displacement;  // added to (x, 0, z)
  vec3 normal;        // unit
  float jacobian;     // < 0 where the surface folds over
};

// A wave's amplitude (direction, k, A) as samples `footprint` apart carry it.
float oceanAmplitude(vec4 wave, float footprint) {
  float wavelength = 6.28318531 / wave.z;
  return footprint > 0.0 ? wave.w * clamp(wavelength / (2.0 * footprint) - 1.0, 0.0, 1.0) : wave.w;
}

OceanPoint oceanWaves(vec2 rest, float footprint) {
  float lambda = ocean.shape.x;
  int count = int(ocean.shape.y);
  vec3 displacement = vec3(0.0);
  vec2 slope = vec2(0.0);
  float pullXX = 0.0, pullZZ = 0.0, pullXZ = 0.0;
  int i = 0;
  // Tested at the end (docs/lavapipe.md, "Loops test at the end"); a sea has one wave at least.
  do {
    vec4 wave = ocean.waves[i];
    vec2 d = wave.xy;
    float k = wave.z;
    float a = oceanAmplitude(wave, footprint);
    float theta = k * dot(d, rest) + oceanPhase(i);
    float s = sin(theta);
    float c = cos(theta);
    float horizontal = lambda * a * s;
    displacement += vec3(-d.x * horizontal, a * c, -d.y * horizontal);
    slope -= (k * a * s) * d;
    float pull = lambda * k * a * c;
    pullXX += pull * d.x * d.x;
    pullZZ += pull * d.y * d.y;
    pullXZ += pull * d.x * d.y;
    ++i;
  } while (i < count);
  vec3 alongX = vec3(1.0 - pullXX, slope.x, -pullXZ);
  vec3 alongZ = vec3(-pullXZ, slope.y, 1.0 - pullZZ);
  OceanPoint point;
  point.displacement = displacement;
  point.normal = normalize(cross(alongZ, alongX));
  point.jacobian = (1.0 - pullXX) * (1.0 - pullZZ) - pullXZ * pullXZ;
  return point;
}

// The Jacobian alone, as oceanWaves() finds it, at kJacobianRun points `spacing` apart along x
// from `rest`: for the foam map, which needs nothing else at its texels. Each wave's constants are
// read once for the whole run (reading them costs lavapipe as much as the wave's arithmetic), and
// its phase steps along the run by a rotation instead of a cosine each.
const int kJacobianRun = 8;

void oceanJacobianRun(vec2 rest, float spacing, float footprint, out float jacobians[kJacobianRun]) {
  float lambda = ocean.shape.x;
  int count = int(ocean.shape.y);
  float pullXX[kJacobianRun], pullZZ[kJacobianRun], pullXZ[kJacobianRun];
  for (int j = 0; j < kJacobianRun; ++j) {
    pullXX[j] = 0.0;
    pullZZ[j] = 0.0;
    pullXZ[j] = 0.0;
  }
  int i = 0;
  do {
    vec4 wave = ocean.waves[i];
    vec2 d = wave.xy;
    float k = wave.z;
    float a = oceanAmplitude(wave, footprint);
    float theta = k * dot(d, rest) + oceanPhase(i);
    vec2 phase = vec2(cos(theta), sin(theta));
    float advance = k * d.x * spacing;
    vec2 turn = vec2(cos(advance), sin(advance));
    float scale = lambda * k * a;
    for (int j = 0; j < kJacobianRun; ++j) {
      float pull = scale * phase.x;
      pullXX[j] += pull * d.x * d.x;
      pullZZ[j] += pull * d.y * d.y;
      pullXZ[j] += pull * d.x * d.y;
      phase = vec2(phase.x * turn.x - phase.y * turn.y, phase.x * turn.y + phase.y * turn.x);
    }
    ++i;
  } while (i < count);
  for (int j = 0; j < kJacobianRun; ++j)
    jacobians[j] = (1.0 - pullXX[j]) * (1.0 - pullZZ[j]) - pullXZ[j] * pullXZ[j];
}
