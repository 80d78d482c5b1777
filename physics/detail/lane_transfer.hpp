#pragma once
// Internal: moving a block's particle positions between the system's arrays (glm::vec3 per
// particle, strands one after another) and the lane layout of strand_lanes.hpp. Not part of the
// public API.
//
// The hair step copies every particle in and out once per block and step; done one float at a
// time, those copies would be a large share of a step (docs/performance.md). Here 8 strands × 8 particles move as a tile: a
// strand's 8 particles are 24 consecutive floats, 3 registers, and the 8 × 24 matrix (strands ×
// floats) transposed is 24 registers whose j-th holds coordinate j % 3 of particle j / 3 of the 8
// strands: exactly 3 lane rows. So each tile is three 8 × 8 transposes; rows that do not fill a
// tile (strand ends, short strands) are copied one float at a time. Copies only: the values are
// bit for bit the same either way.

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "physics/detail/strand_lanes.hpp"

#if MANE_STRAND_LANES_AVX2

namespace mane::physics::detail {

#define MANE_AVX2 __attribute__((target("avx2")))

/// Where a block's strands are: per lane, the first particle's index in the system's arrays and
/// the particle count (0 for lanes without a strand).
struct LaneStrands {
  std::uint32_t first[kBlockLanes];
  std::uint32_t count[kBlockLanes];
};

namespace transfer {

// r[j] ← column j of the 8 × 8 matrix whose rows are r[0..7] (Intel's classic unpack, shuffle,
// permute sequence).
MANE_AVX2 inline void transpose8(__m256 (&r)[8]) noexcept {
  __m256 t[8], u[8];
  for (int k = 0; k < 8; k += 2) {
    t[k] = _mm256_unpacklo_ps(r[k], r[k + 1]);
    t[k + 1] = _mm256_unpackhi_ps(r[k], r[k + 1]);
  }
  for (int k = 0; k < 8; k += 4) {
    u[k] = _mm256_shuffle_ps(t[k], t[k + 2], 0x44);
    u[k + 1] = _mm256_shuffle_ps(t[k], t[k + 2], 0xEE);
    u[k + 2] = _mm256_shuffle_ps(t[k + 1], t[k + 3], 0x44);
    u[k + 3] = _mm256_shuffle_ps(t[k + 1], t[k + 3], 0xEE);
  }
  for (int k = 0; k < 4; ++k) {
    r[k] = _mm256_permute2f128_ps(u[k], u[k + 4], 0x20);
    r[k + 4] = _mm256_permute2f128_ps(u[k], u[k + 4], 0x31);
  }
}

// Smallest particle count among the 8 lanes of group g.
inline std::uint32_t groupRows(const LaneStrands& s, std::size_t g) noexcept {
  return *std::min_element(s.count + g * kSimdWidth, s.count + (g + 1) * kSimdWidth);
}

// Tile (group g, particles i0 … i0 + 7) of xyz-interleaved `source` into lane arrays
// lanes[0], lanes[n], lanes[2n] (x, y, z).
MANE_AVX2 inline void loadTile(const LaneStrands& s, std::size_t g, std::size_t i0, const float* source, float* lanes,
                               std::size_t n) noexcept {
  for (int chunk = 0; chunk < 3; ++chunk) {
    __m256 r[8];
    for (std::size_t k = 0; k < kSimdWidth; ++k)
      r[k] = _mm256_loadu_ps(source + 3 * (std::size_t{s.first[g * kSimdWidth + k]} + i0) + 8 * chunk);
    transpose8(r);
    for (int j = 0; j < 8; ++j) {
      const int f = 8 * chunk + j;  // float f of the tile: coordinate f % 3 of particle i0 + f / 3
      _mm256_storeu_ps(lanes + static_cast<std::size_t>(f % 3) * n +
                           (i0 + static_cast<std::size_t>(f / 3)) * kBlockLanes + g * kSimdWidth,
                       r[j]);
    }
  }
}

// The inverse of loadTile.
MANE_AVX2 inline void storeTile(const LaneStrands& s, std::size_t g, std::size_t i0, const float* lanes, std::size_t n,
                                float* target) noexcept {
  for (int chunk = 0; chunk < 3; ++chunk) {
    __m256 r[8];
    for (int j = 0; j < 8; ++j) {
      const int f = 8 * chunk + j;
      r[j] = _mm256_loadu_ps(lanes + static_cast<std::size_t>(f % 3) * n +
                             (i0 + static_cast<std::size_t>(f / 3)) * kBlockLanes + g * kSimdWidth);
    }
    transpose8(r);
    for (std::size_t k = 0; k < kSimdWidth; ++k)
      _mm256_storeu_ps(target + 3 * (std::size_t{s.first[g * kSimdWidth + k]} + i0) + 8 * chunk, r[k]);
  }
}

}  // namespace transfer

/// Positions and previous positions (xyz-interleaved floats) of the block's strands into the six
/// lane arrays of `rows` × kBlockLanes floats at `lanes` (x, y, z, previous x, y, z), for the
/// first `groups` groups of lanes (those the kernels read). Rows past a strand's end, and lanes
/// without one, get zeros: finite, so the fault probe only sees the strand's own particles.
MANE_AVX2 inline void loadLanePositions(const LaneStrands& s, std::size_t rows, std::size_t groups,
                                        const float* positions, const float* previous, float* lanes) noexcept {
  const std::size_t n = rows * kBlockLanes;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t tiled = transfer::groupRows(s, g) / 8 * 8;
    for (std::size_t i0 = 0; i0 < tiled; i0 += 8) {
      transfer::loadTile(s, g, i0, positions, lanes, n);
      transfer::loadTile(s, g, i0, previous, lanes + 3 * n, n);
    }
    for (std::size_t b = g * kSimdWidth; b < (g + 1) * kSimdWidth; ++b)
      for (std::size_t i = tiled; i < rows; ++i) {
        const std::size_t at = i * kBlockLanes + b, from = 3 * (std::size_t{s.first[b]} + i);
        const bool inside = i < s.count[b];
        for (std::size_t c = 0; c < 3; ++c) {
          lanes[c * n + at] = inside ? positions[from + c] : 0.0f;
          lanes[(3 + c) * n + at] = inside ? previous[from + c] : 0.0f;
        }
      }
  }
}

/// The inverse of loadLanePositions for each strand's own particles.
MANE_AVX2 inline void storeLanePositions(const LaneStrands& s, std::size_t rows, std::size_t groups, const float* lanes,
                                         float* positions, float* previous) noexcept {
  const std::size_t n = rows * kBlockLanes;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t tiled = transfer::groupRows(s, g) / 8 * 8;
    for (std::size_t i0 = 0; i0 < tiled; i0 += 8) {
      transfer::storeTile(s, g, i0, lanes, n, positions);
      transfer::storeTile(s, g, i0, lanes + 3 * n, n, previous);
    }
    for (std::size_t b = g * kSimdWidth; b < (g + 1) * kSimdWidth; ++b)
      for (std::size_t i = tiled; i < s.count[b]; ++i) {
        const std::size_t at = i * kBlockLanes + b, to = 3 * (std::size_t{s.first[b]} + i);
        for (std::size_t c = 0; c < 3; ++c) {
          positions[to + c] = lanes[c * n + at];
          previous[to + c] = lanes[(3 + c) * n + at];
        }
      }
  }
}

#undef MANE_AVX2

}  // namespace mane::physics::detail

#endif  // MANE_STRAND_LANES_AVX2
