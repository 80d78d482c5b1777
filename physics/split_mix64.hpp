#pragma once
// The random numbers of everything procedural in the physics (grooms, dense-strand layouts, wind
// gusts, the sea's waves, debris): splitmix64 (Steele, Lea & Flood 2014, "Fast Splittable
// Pseudorandom Number Generators"; the constants of Vigna's reference implementation), the same
// bits on every platform for a seed.

#include <cstdint>

namespace mane::physics {

/// splitmix64: a 64-bit state advanced by a Weyl increment and scrambled by two xor-shift-
/// multiply rounds. Tiny, fast, passes BigCrush, and fully specified by its constants.
class SplitMix64 {
public:
  explicit SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}

  /// Next 64 random bits.
  std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  /// Uniform float in [0, 1): the top 24 bits of `next()` times 2⁻²⁴ (exact in a float).
  float nextFloat() noexcept { return static_cast<float>(next() >> 40) * 0x1.0p-24f; }

  /// Uniform float in [lo, hi).
  float nextFloat(float lo, float hi) noexcept { return lo + (hi - lo) * nextFloat(); }

private:
  std::uint64_t state_;
};

}  // namespace mane::physics
