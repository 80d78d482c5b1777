#include "render/environment/environment_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace mane::render {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Bilinear weights of coordinate `x` (texel units, centres at integers) between `low` and `low + 1`,
// both clamped to [0, count − 1].
struct Lerp {
  int low = 0;
  int high = 0;
  float weight = 0.0f;  // of `high`
};
Lerp clampedLerp(float x, int count) {
  x = std::clamp(x, 0.0f, float(count - 1));
  const int low = std::min(static_cast<int>(std::floor(x)), count - 1);
  return {low, std::min(low + 1, count - 1), x - float(low)};
}

double areaElement(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}

glm::vec3 rotateAboutY(glm::vec3 d, float radians) {
  const float c = std::cos(radians), s = std::sin(radians);
  return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

}  // namespace

glm::vec2 equirectCoordinates(glm::vec3 direction) {
  const float u = 0.5f + std::atan2(direction.x, -direction.z) / (2.0f * kPi);
  const float v = std::acos(std::clamp(direction.y, -1.0f, 1.0f)) / kPi;
  return {u, v};
}

glm::vec3 equirectDirection(glm::vec2 uv) {
  const float phi = (uv.x - 0.5f) * 2.0f * kPi;
  const float theta = uv.y * kPi;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::vec3 sampleEquirect(const EquirectImage& image, glm::vec3 direction) {
  const glm::vec2 uv = equirectCoordinates(direction);
  // Columns wrap round; rows stop at the poles.
  const float x = uv.x * float(image.width) - 0.5f;
  const float fx = std::floor(x);
  const float wx = x - fx;
  const int c0 = ((static_cast<int>(fx) % image.width) + image.width) % image.width;
  const int c1 = (c0 + 1) % image.width;
  const Lerp row = clampedLerp(uv.y * float(image.height) - 0.5f, image.height);
  const glm::vec3 top = image.at(c0, row.low) * (1.0f - wx) + image.at(c1, row.low) * wx;
  const glm::vec3 bottom = image.at(c0, row.high) * (1.0f - wx) + image.at(c1, row.high) * wx;
  return top * (1.0f - row.weight) + bottom * row.weight;
}

glm::vec3 cubeDirection(int face, glm::vec2 st) {
  // Inverts the major-axis table: (a, b) are sc/|ma| and tc/|ma|.
  const float a = 2.0f * st.x - 1.0f;
  const float b = 2.0f * st.y - 1.0f;
  glm::vec3 d;
  switch (face) {
    case 0: d = {1.0f, -b, -a}; break;
    case 1: d = {-1.0f, -b, a}; break;
    case 2: d = {a, 1.0f, b}; break;
    case 3: d = {a, -1.0f, -b}; break;
    case 4: d = {a, -b, 1.0f}; break;
    default: d = {-a, -b, -1.0f}; break;
  }
  return glm::normalize(d);
}

CubeCoordinates cubeCoordinates(glm::vec3 d) {
  const glm::vec3 m = glm::abs(d);
  int face;
  float sc, tc, ma;
  // Ties go to x, then y, as the spec allows any consistent choice.
  if (m.x >= m.y && m.x >= m.z) {
    face = d.x >= 0.0f ? 0 : 1;
    sc = d.x >= 0.0f ? -d.z : d.z;
    tc = -d.y;
    ma = m.x;
  } else if (m.y >= m.z) {
    face = d.y >= 0.0f ? 2 : 3;
    sc = d.x;
    tc = d.y >= 0.0f ? d.z : -d.z;
    ma = m.y;
  } else {
    face = d.z >= 0.0f ? 4 : 5;
    sc = d.z >= 0.0f ? d.x : -d.x;
    tc = -d.y;
    ma = m.z;
  }
  return {face, {0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)}};
}

double cubeTexelSolidAngle(int size, int column, int row) {
  // The solid angle of the face rectangle from (0, 0) to (x, y) at unit distance is
  // atan(xy / √(x² + y² + 1)); a texel's is the signed sum at its four corners.
  const double step = 2.0 / size;
  const double x0 = -1.0 + column * step, x1 = x0 + step;
  const double y0 = -1.0 + row * step, y1 = y0 + step;
  return areaElement(x0, y0) - areaElement(x0, y1) - areaElement(x1, y0) + areaElement(x1, y1);
}

glm::vec3 sampleCube(const CubeMap& cube, glm::vec3 direction) {
  const CubeCoordinates at = cubeCoordinates(direction);
  const Lerp x = clampedLerp(at.st.x * float(cube.size) - 0.5f, cube.size);
  const Lerp y = clampedLerp(at.st.y * float(cube.size) - 0.5f, cube.size);
  const glm::vec3 top = cube.at(at.face, x.low, y.low) * (1.0f - x.weight) + cube.at(at.face, x.high, y.low) * x.weight;
  const glm::vec3 bottom =
      cube.at(at.face, x.low, y.high) * (1.0f - x.weight) + cube.at(at.face, x.high, y.high) * x.weight;
  return top * (1.0f - y.weight) + bottom * y.weight;
}

CubeMap cubeFromEquirect(const EquirectImage& image, int size, float rotationRadians, float intensity) {
  CubeMap cube;
  cube.size = size;
  constexpr float kOffsets[2] = {0.25f, 0.75f};
  for (int face = 0; face < 6; ++face) {
    std::vector<glm::vec3>& texels = cube.faces[static_cast<std::size_t>(face)];
    texels.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
    for (int row = 0; row < size; ++row)
      for (int column = 0; column < size; ++column) {
        glm::vec3 sum(0.0f);
        for (float dy : kOffsets)
          for (float dx : kOffsets) {
            const glm::vec3 world =
                cubeDirection(face, {(float(column) + dx) / float(size), (float(row) + dy) / float(size)});
            // What the panorama shows at `world` once turned: its own direction turned back.
            sum += sampleEquirect(image, rotateAboutY(world, -rotationRadians));
          }
        texels[static_cast<std::size_t>(row) * static_cast<std::size_t>(size) + static_cast<std::size_t>(column)] =
            sum * (0.25f * intensity);
      }
  }
  return cube;
}

}  // namespace mane::render
