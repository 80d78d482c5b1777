// Bands 0, 1 and 2 of a function given by nine real spherical harmonics (rgb), each evaluated at
// the unit direction `n`, in the order and normalisation of render/environment/spherical_harmonics.hpp.
void harmonicBands(vec4 coefficients[9], vec3 n, out vec3 band0, out vec3 band1, out vec3 band2) {
  band0 = coefficients[0].rgb * 0.282094792;
  band1 = (coefficients[1].rgb * n.y + coefficients[2].rgb * n.z + coefficients[3].rgb * n.x) * 0.488602512;
  band2 = (coefficients[4].rgb * (n.x * n.y) + coefficients[5].rgb * (n.y * n.z) + coefficients[7].rgb * (n.x * n.z)) *
              1.092548431 +
          coefficients[6].rgb * (0.315391565 * (3.0 * n.z * n.z - 1.0)) +
          coefficients[8].rgb * (0.546274215 * (n.x * n.x - n.y * n.y));
}
