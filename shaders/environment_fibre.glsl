// The environment's irradiance over π averaged over the normals perpendicular to `tangent` (a
// fibre's side), from its nine harmonics (the order of render/environment/spherical_harmonics.hpp).
// Averaged round the fibre, the clamped cosine of a direction at angle θ from the tangent is
// sin θ/π: this is Kajiya and Kay's diffuse term over the whole environment, ∫ L sin θ dω/π²
// (a constant sky of radiance L gives L).
// Opposite normals cancel band 1, and the average of band 2 over the circle is the mean of any two
// normals at right angles: the constant term plus that half-sum, exactly.
#include "spherical_harmonics.glsl"

vec3 environmentAroundFibre(vec4 harmonics[9], vec3 tangent) {
  vec3 helper = abs(tangent.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 a = normalize(cross(tangent, helper));
  vec3 b = cross(tangent, a);
  vec3 band0, band1, band2a, band2b;
  harmonicBands(harmonics, a, band0, band1, band2a);
  harmonicBands(harmonics, b, band0, band1, band2b);
  return band0 + 0.5 * (band2a + band2b);
}
