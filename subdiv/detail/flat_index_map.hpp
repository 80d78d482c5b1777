#pragma once
// Private to subdiv/: a map from 64-bit keys to dense indices 0, 1, 2, … in order of first
// insertion, with open addressing (linear probing) in two flat arrays. The tessellator names
// hundreds of thousands of points a frame; std::unordered_map would spend most of that time
// allocating nodes. Storage is kept across `clear` calls.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace mane::subdiv::detail {

class FlatIndexMap {
public:
  /// Empties the map and makes room for `expected` keys without growing.
  void clear(std::size_t expected = 0) {
    size_ = 0;
    const std::size_t wanted = std::bit_ceil(std::max<std::size_t>(16, 2 * expected));
    if (wanted > keys_.size()) {
      keys_.assign(wanted, 0);
      values_.assign(wanted, kEmpty);
    } else {
      std::fill(values_.begin(), values_.end(), kEmpty);
    }
  }

  [[nodiscard]] std::size_t size() const { return size_; }

  /// The index of `key`, and whether it was inserted now (with index size() − 1).
  std::pair<std::uint32_t, bool> insert(std::uint64_t key) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t slot = hash(key) & mask;; slot = (slot + 1) & mask) {
      if (values_[slot] == kEmpty) {
        keys_[slot] = key;
        values_[slot] = static_cast<std::uint32_t>(size_++);
        return {values_[slot], true};
      }
      if (keys_[slot] == key) return {values_[slot], false};
    }
  }

private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;

  // splitmix64's finaliser: point names differ in a few low bits of packed fields.
  static std::size_t hash(std::uint64_t key) {
    key ^= key >> 30;
    key *= 0xbf58476d1ce4e5b9ull;
    key ^= key >> 27;
    key *= 0x94d049bb133111ebull;
    key ^= key >> 31;
    return static_cast<std::size_t>(key);
  }

  void grow() {
    std::vector<std::uint64_t> keys = std::move(keys_);
    std::vector<std::uint32_t> values = std::move(values_);
    keys_.assign(std::max<std::size_t>(16, 2 * keys.size()), 0);
    values_.assign(keys_.size(), kEmpty);
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (values[i] == kEmpty) continue;
      std::size_t slot = hash(keys[i]) & mask;
      while (values_[slot] != kEmpty) slot = (slot + 1) & mask;
      keys_[slot] = keys[i];
      values_[slot] = values[i];
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::size_t size_ = 0;
};

}  // namespace mane::subdiv::detail
