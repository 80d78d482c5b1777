#include "scenes/procedural.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mane::scenes {

Mesh makeSphere(int rings, int segments, float radius) {
  rings = std::max(rings, 2);
  segments = std::max(segments, 3);
  Mesh mesh;
  mesh.name = "procedural:sphere";
  const auto columns = static_cast<std::uint32_t>(segments + 1);
  for (int r = 0; r <= rings; ++r) {
    const float v = static_cast<float>(r) / static_cast<float>(rings);
    const float polar = v * std::numbers::pi_v<float>;  // 0 at +Y
    for (int s = 0; s <= segments; ++s) {
      const float u = static_cast<float>(s) / static_cast<float>(segments);
      const float azimuth = u * 2.0f * std::numbers::pi_v<float>;
      const glm::vec3 n(std::sin(polar) * std::sin(azimuth), std::cos(polar), std::sin(polar) * std::cos(azimuth));
      mesh.positions.push_back(n * radius);
      mesh.normals.push_back(n);
      mesh.uvs.emplace_back(u, v);
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = static_cast<std::uint32_t>(r) * columns + static_cast<std::uint32_t>(s);
      const std::uint32_t b = a + columns;  // one ring further south
      // The pole rows collapse to a point: emit only the triangle with area.
      if (r != 0) mesh.indices.insert(mesh.indices.end(), {a, b, a + 1});
      if (r != rings - 1) mesh.indices.insert(mesh.indices.end(), {a + 1, b, b + 1});
    }
  }
  return mesh;
}

}  // namespace mane::scenes
