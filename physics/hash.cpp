#include "physics/hash.hpp"

#include <cinttypes>
#include <cstdio>

namespace mane::physics {

std::uint64_t fnv1a(std::span<const std::byte> bytes, std::uint64_t hash) noexcept {
  for (const std::byte b : bytes) {
    hash ^= static_cast<std::uint64_t>(b);
    hash *= kFnvPrime;
  }
  return hash;
}

std::uint64_t stateHash(const Particles& particles) noexcept {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be three packed floats");
  StateHasher hasher;
  hasher.add(std::span<const glm::vec3>(particles.positions));
  hasher.add(std::span<const glm::vec3>(particles.previousPositions));
  return hasher.value();
}

std::string hashText(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, hash);
  return text;
}

}  // namespace mane::physics
