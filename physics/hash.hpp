#pragma once
// State hashing for determinism checks (docs/design.md#determinism): equal hashes mean equal bytes
// of simulated state, so runs can be compared across thread counts, repetitions and builds.
//
// The hash is 64-bit FNV-1a (Fowler, Noll & Vo; http://www.isthe.com/chongo/tech/comp/fnv/):
// for each byte b, h = (h XOR b) × 1099511628211, starting from 14695981039346656037. Not
// cryptographic; chosen because it is tiny, byte-order explicit and has no platform variants.
// Floats are hashed as their raw IEEE-754 bytes (little-endian on every target we build), so
// −0 and +0, or two NaN payloads, hash differently — exactly what a bit-identity check wants.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>

#include "physics/particles.hpp"

namespace mane::physics {

/// FNV-1a 64-bit offset basis.
inline constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ull;
/// FNV-1a 64-bit prime.
inline constexpr std::uint64_t kFnvPrime = 1099511628211ull;

/// Continues an FNV-1a 64-bit hash `hash` over `bytes`.
[[nodiscard]] std::uint64_t fnv1a(std::span<const std::byte> bytes, std::uint64_t hash = kFnvOffsetBasis) noexcept;

/// Accumulates the raw bytes of several arrays into one FNV-1a 64-bit hash.
class StateHasher {
public:
  /// Adds the object representation of every element of `values` (trivially copyable types).
  template <class T>
  void add(std::span<const T> values) noexcept {
    static_assert(std::is_trivially_copyable_v<T>);
    hash_ = fnv1a(std::as_bytes(values), hash_);
  }

  /// Adds the object representation of one value.
  template <class T>
  void addValue(const T& value) noexcept {
    add(std::span<const T>(&value, 1));
  }

  /// The hash of everything added so far.
  [[nodiscard]] std::uint64_t value() const noexcept { return hash_; }

private:
  std::uint64_t hash_ = kFnvOffsetBasis;
};

/// Hash of a particle store: positions, then previous positions (all x, y, z floats in particle
/// order). Inverse masses are configuration, not simulated, and are left out.
[[nodiscard]] std::uint64_t stateHash(const Particles& particles) noexcept;

/// A hash as text: 16 lower-case hex digits, as `mane sim` prints its state hash.
[[nodiscard]] std::string hashText(std::uint64_t hash);

}  // namespace mane::physics
