#pragma once
// Internal: moving a block's particle positions between the system's arrays (glm::vec3 per
// particle, strands one after another) and the lane layout of strand_lanes.hpp. Not part of the
// public API.
//
// The hair step keeps the lanes between steps and writes every particle's position back once
// per block and step (reading them in only when something else moved them); done one float at
// a time, those copies would be a large share of a step. Here 8 strands × 8 particles move as a tile: a
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
// The loops over a tile's floats are unrolled so that each float's coordinate and row are
// constants: worked out at run time, the divisions by 3 would cost more than the transposition.
MANE_AVX2 inline void loadTile(const LaneStrands& s, std::size_t g, std::size_t i0, const float* source, float* lanes,
                               std::size_t n) noexcept {
#pragma GCC unroll 3
  for (int chunk = 0; chunk < 3; ++chunk) {
    __m256 r[8];
    for (std::size_t k = 0; k < kSimdWidth; ++k)
      r[k] = _mm256_loadu_ps(source + 3 * (std::size_t{s.first[g * kSimdWidth + k]} + i0) + 8 * chunk);
    transpose8(r);
#pragma GCC unroll 8
    for (int j = 0; j < 8; ++j) {
      const int f = 8 * chunk + j;  // float f of the tile: coordinate f % 3 of particle i0 + f / 3
      _mm256_storeu_ps(lanes + static_cast<std::size_t>(f % 3) * n +
                           (i0 + static_cast<std::size_t>(f / 3)) * kBlockLanes + g * kSimdWidth,
                       r[j]);
    }
  }
}

// The inverse of loadTile. Unless `probe` is null, ORs v − v for every value v it moves into it
// (per lane of the group): v − v is +0 (all bits clear) for finite v and NaN for NaN or ±∞, and
// an OR with a NaN stays a NaN, so each lane ends +0 exactly when all its values are finite.
MANE_AVX2 inline void storeTile(const LaneStrands& s, std::size_t g, std::size_t i0, const float* lanes, std::size_t n,
                                float* target, __m256* probe) noexcept {
#pragma GCC unroll 3
  for (int chunk = 0; chunk < 3; ++chunk) {
    __m256 r[8];
#pragma GCC unroll 8
    for (int j = 0; j < 8; ++j) {
      const int f = 8 * chunk + j;
      r[j] = _mm256_loadu_ps(lanes + static_cast<std::size_t>(f % 3) * n +
                             (i0 + static_cast<std::size_t>(f / 3)) * kBlockLanes + g * kSimdWidth);
    }
    if (probe) {
      __m256 d[8];
      for (int j = 0; j < 8; ++j) d[j] = _mm256_sub_ps(r[j], r[j]);
      // A tree, not a chain: the probe must not add a long dependency to the copy.
      *probe = _mm256_or_ps(*probe, _mm256_or_ps(_mm256_or_ps(_mm256_or_ps(d[0], d[1]), _mm256_or_ps(d[2], d[3])),
                                                 _mm256_or_ps(_mm256_or_ps(d[4], d[5]), _mm256_or_ps(d[6], d[7]))));
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

/// The inverse of loadLanePositions for each strand's own particles; `previous` null: the
/// positions only. On the way, per lane of the first `groups` groups, `probe` gets 0 when every
/// position coordinate of the lane's strand is finite and NaN otherwise (see storeTile), so
/// that the step's fault check needs no pass of its own.
MANE_AVX2 inline void storeLanePositions(const LaneStrands& s, std::size_t rows, std::size_t groups, const float* lanes,
                                         float* positions, float* previous, float (&probe)[kBlockLanes]) noexcept {
  const std::size_t n = rows * kBlockLanes;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t tiled = transfer::groupRows(s, g) / 8 * 8;
    __m256 groupProbe = _mm256_setzero_ps();
    for (std::size_t i0 = 0; i0 < tiled; i0 += 8) {
      transfer::storeTile(s, g, i0, lanes, n, positions, &groupProbe);
      if (previous) transfer::storeTile(s, g, i0, lanes + 3 * n, n, previous, nullptr);
    }
    _mm256_storeu_ps(probe + g * kSimdWidth, groupProbe);
    for (std::size_t b = g * kSimdWidth; b < (g + 1) * kSimdWidth; ++b)
      for (std::size_t i = tiled; i < s.count[b]; ++i) {
        const std::size_t at = i * kBlockLanes + b, to = 3 * (std::size_t{s.first[b]} + i);
        for (std::size_t c = 0; c < 3; ++c) {
          const float v = lanes[c * n + at];
          positions[to + c] = v;
          probe[b] += v - v;
        }
        if (previous)
          for (std::size_t c = 0; c < 3; ++c) previous[to + c] = lanes[(3 + c) * n + at];
      }
  }
}

#undef MANE_AVX2

}  // namespace mane::physics::detail

#endif  // MANE_STRAND_LANES_AVX2
