#include "render/passes/mesh_welding.hpp"

#include <array>
#include <cstring>
#include <unordered_map>

namespace mane::render {

std::vector<std::uint32_t> weldByPosition(std::span<const glm::vec3> positions) {
  struct Hash {
    std::size_t operator()(const glm::vec3& p) const {
      const glm::vec3 positiveZeros = p + glm::vec3(0.0f);  // −0 + 0 = +0: equal values, equal bits
      std::array<std::uint32_t, 3> bits{};
      std::memcpy(bits.data(), &positiveZeros, sizeof(positiveZeros));
      return (std::size_t(bits[0]) * 73856093u) ^ (std::size_t(bits[1]) * 19349663u) ^
             (std::size_t(bits[2]) * 83492791u);
    }
  };
  std::unordered_map<glm::vec3, std::uint32_t, Hash> first;
  std::vector<std::uint32_t> canonical(positions.size());
  for (std::uint32_t i = 0; i < positions.size(); ++i) canonical[i] = first.try_emplace(positions[i], i).first->second;
  return canonical;
}

}  // namespace mane::render
