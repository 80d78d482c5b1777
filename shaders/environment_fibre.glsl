// The environment's irradiance over π averaged over the normals perpendicular to `tangent` (a
// fibre's side), from its nine harmonics (the order of render/environment/spherical_harmonics.hpp).
// Opposite normals cancel band 1, and the average of band 2 over the circle is the mean of any two
// normals at right angles: the constant term plus that half-sum, exactly.
vec3 environmentAroundFibre(vec4 harmonics[9], vec3 tangent) {
  vec3 helper = abs(tangent.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 a = normalize(cross(tangent, helper));
  vec3 b = cross(tangent, a);
  vec3 band2 = vec3(0.0);
  for (int k = 0; k < 2; ++k) {
    vec3 n = k == 0 ? a : b;
    band2 += (harmonics[4].rgb * (n.x * n.y) + harmonics[5].rgb * (n.y * n.z) + harmonics[7].rgb * (n.x * n.z)) *
                 1.092548431 +
             harmonics[6].rgb * (0.315391565 * (3.0 * n.z * n.z - 1.0)) +
             harmonics[8].rgb * (0.546274215 * (n.x * n.x - n.y * n.y));
  }
  return harmonics[0].rgb * 0.282094792 + 0.5 * band2;
}
