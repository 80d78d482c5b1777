#pragma once
// Cube maps for the environment tests: a function of direction sampled at each texel's centre.

#include "render/environment/environment_map.hpp"

namespace mane::render {

/// A cube `size` texels wide holding radiance(direction) at each texel's centre.
CubeMap cubeOf(int size, auto radiance) {
  CubeMap cube{.size = size};
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < size; ++row)
      for (int column = 0; column < size; ++column)
        cube.faces[face].push_back(
            radiance(cubeDirection(face, {(float(column) + 0.5f) / float(size), (float(row) + 0.5f) / float(size)})));
  return cube;
}

}  // namespace mane::render
