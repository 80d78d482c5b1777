#pragma once
// Light from every direction (an environment): as an equirectangular panorama, the way files
// store it, and as a cube map, the way the GPU samples it. Both hold linear RGB radiance.
//
// Directions are world directions with +Y up. A panorama's column u runs once round the vertical
// axis: its centre (u = 0.5) looks along −Z, u = 0.75 along +X; its top row looks up. The cube's
// faces follow Vulkan's order and orientation (+X, −X, +Y, −Y, +Z, −Z; the spec's "Cube Map Face
// Selection" table), row 0 of each face at t = 0.

#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace mane::render {

struct EquirectImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> texels;  ///< rows from the top, width × height

  [[nodiscard]] const glm::vec3& at(int column, int row) const {
    return texels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(column)];
  }
};

struct CubeMap {
  int size = 0;                                 ///< texels on a face's side
  std::array<std::vector<glm::vec3>, 6> faces;  ///< each size × size, rows from t = 0

  [[nodiscard]] const glm::vec3& at(int face, int column, int row) const {
    return faces[static_cast<std::size_t>(face)]
                [static_cast<std::size_t>(row) * static_cast<std::size_t>(size) + static_cast<std::size_t>(column)];
  }
};

/// The panorama coordinates (u, v in [0, 1]) of unit `direction`.
[[nodiscard]] glm::vec2 equirectCoordinates(glm::vec3 direction);
/// The unit direction at panorama coordinates `uv`.
[[nodiscard]] glm::vec3 equirectDirection(glm::vec2 uv);
/// Bilinear radiance of `image` towards unit `direction` (wrapping round, clamped at the poles).
[[nodiscard]] glm::vec3 sampleEquirect(const EquirectImage& image, glm::vec3 direction);

/// The unit direction through face coordinates (s, t in [0, 1]) of `face`.
[[nodiscard]] glm::vec3 cubeDirection(int face, glm::vec2 st);
/// The face and face coordinates that unit `direction` falls on.
struct CubeCoordinates {
  int face = 0;
  glm::vec2 st{0.5f};
};
[[nodiscard]] CubeCoordinates cubeCoordinates(glm::vec3 direction);
/// The solid angle (steradians) texel (column, row) of a face `size` texels wide subtends; the
/// texels of all six faces sum to 4π.
[[nodiscard]] double cubeTexelSolidAngle(int size, int column, int row);
/// Bilinear radiance of `cube` towards unit `direction`, within the face it falls on (clamped at
/// the face's edges).
[[nodiscard]] glm::vec3 sampleCube(const CubeMap& cube, glm::vec3 direction);

/// A cube map `size` texels wide sampled from `image`, turned by `rotationRadians` about +Y (a
/// positive angle turns the panorama's content counter-clockwise seen from above) and scaled by
/// `intensity`. Each texel averages 2 × 2 bilinear samples.
[[nodiscard]] CubeMap cubeFromEquirect(const EquirectImage& image, int size, float rotationRadians = 0.0f,
                                       float intensity = 1.0f);

}  // namespace mane::render
