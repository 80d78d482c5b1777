#pragma once
// Internal: stepAvx2 (strand_lanes.hpp) again with AVX-512 registers, for CPUs that have them.
// Not part of the public API.
//
// Same block layout, same operations per lane in the same order, so the same bits: a 16-float
// register covers two of stepAvx2's 8-lane groups (a "wide group"), conditions become mask
// registers, and a masked add or subtract keeps the old value where the scalar branch keeps
// it, as stepAvx2's blends do. Lanes without a strand in a wide group that is only half in use
// have count 0, so every mask leaves them as they are. stepAvx2 is limited by the instructions
// around each sqrt and divide (loads, stores, the dot products), which cover twice the lanes
// here. tests/physics/hair_test.cpp checks this kernel against the scalar sweeps bit for bit.

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "physics/detail/strand_lanes.hpp"

#if MANE_STRAND_LANES_AVX2

namespace mane::physics::detail {

inline constexpr std::size_t kWideWidth = 16;                        // floats per AVX-512 register
inline constexpr std::size_t kWideGroups = kBlockLanes / kWideWidth;  // wide groups per block
static_assert(kWideWidth == 2 * kSimdWidth && kBlockLanes % kWideWidth == 0);

/// True when the CPU running this process (and its operating system) supports AVX-512F.
inline bool cpuHasAvx512() noexcept {
  static const bool has = __builtin_cpu_supports("avx512f");
  return has;
}

#define MANE_AVX512 __attribute__((target("avx2,avx512f")))

namespace wide {

// _mm512_sqrt_ps on every lane; GCC 12's version of that intrinsic starts from an undefined
// register, which -Wmaybe-uninitialized reports, so the zero-masked form with a full mask.
MANE_AVX512 inline __m512 squareRoot(__m512 v) noexcept { return _mm512_maskz_sqrt_ps(__mmask16(0xFFFF), v); }

// Lanes b of wide group h with i < count[b].
MANE_AVX512 inline __mmask16 activeLanes(const StrandLanes& s, std::size_t h, std::size_t i) noexcept {
  const __m512i count = _mm512_loadu_si512(s.count + h * kWideWidth);
  return _mm512_cmpgt_epi32_mask(count, _mm512_set1_epi32(static_cast<int>(i)));
}

// verletPosition for one coordinate of the lanes in `mask`.
MANE_AVX512 inline void verlet(float* c, float* p, __m512 keep, __m512 kick, __mmask16 mask) noexcept {
  const __m512 current = _mm512_loadu_ps(c), previous = _mm512_loadu_ps(p);
  const __m512 next =
      _mm512_add_ps(_mm512_add_ps(current, _mm512_mul_ps(_mm512_sub_ps(current, previous), keep)), kick);
  _mm512_storeu_ps(c, _mm512_mask_blend_ps(mask, current, next));
  _mm512_storeu_ps(p, _mm512_mask_blend_ps(mask, previous, current));
}

// integrateRow for wide group h; `plain`: the smaller plainRows of its two groups.
MANE_AVX512 inline void integrateRow(const StrandLanes& s, std::size_t h, std::size_t i, std::size_t plain, __m512 keep,
                                     __m512 kx, __m512 ky, __m512 kz) noexcept {
  const std::size_t n = i * kBlockLanes + h * kWideWidth;
  const __mmask16 mask =
      i < plain ? __mmask16(0xFFFF)
                : __mmask16(activeLanes(s, h, i) &
                            _mm512_cmp_ps_mask(_mm512_loadu_ps(s.w + n), _mm512_setzero_ps(), _CMP_GT_OQ));
  verlet(s.x + n, s.px + n, keep, kx, mask);
  verlet(s.y + n, s.py + n, keep, ky, mask);
  verlet(s.z + n, s.pz + n, keep, kz, mask);
}

// distanceRow for wide group h: projectDistance(x[i−1], x[i], w[i−1], w[i], segment[i]).
MANE_AVX512 inline void distanceRow(const StrandLanes& s, std::size_t h, std::size_t i, std::size_t plain) noexcept {
  const __m512 zero = _mm512_setzero_ps();
  const std::size_t n = i * kBlockLanes + h * kWideWidth, m = n - kBlockLanes;
  const __m512 ax = _mm512_loadu_ps(s.x + m), ay = _mm512_loadu_ps(s.y + m), az = _mm512_loadu_ps(s.z + m);
  const __m512 bx = _mm512_loadu_ps(s.x + n), by = _mm512_loadu_ps(s.y + n), bz = _mm512_loadu_ps(s.z + n);
  const __m512 dx = _mm512_sub_ps(bx, ax), dy = _mm512_sub_ps(by, ay), dz = _mm512_sub_ps(bz, az);
  const __m512 lengthSquared =
      _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)), _mm512_mul_ps(dz, dz));
  const __m512 length = squareRoot(lengthSquared);
  const __m512 segment = _mm512_loadu_ps(s.segment + n);
  if (i >= 2 && i < plain) {
    // Both ends weigh 1, as in distanceRow: the same values with fewer operations.
    const __mmask16 mask = _mm512_cmp_ps_mask(lengthSquared, zero, _CMP_GT_OQ);
    const __m512 scale = _mm512_div_ps(_mm512_sub_ps(length, segment), _mm512_add_ps(length, length));
    const __m512 mx = _mm512_mul_ps(dx, scale), my = _mm512_mul_ps(dy, scale), mz = _mm512_mul_ps(dz, scale);
    _mm512_storeu_ps(s.x + m, _mm512_mask_add_ps(ax, mask, ax, mx));
    _mm512_storeu_ps(s.y + m, _mm512_mask_add_ps(ay, mask, ay, my));
    _mm512_storeu_ps(s.z + m, _mm512_mask_add_ps(az, mask, az, mz));
    _mm512_storeu_ps(s.x + n, _mm512_mask_sub_ps(bx, mask, bx, mx));
    _mm512_storeu_ps(s.y + n, _mm512_mask_sub_ps(by, mask, by, my));
    _mm512_storeu_ps(s.z + n, _mm512_mask_sub_ps(bz, mask, bz, mz));
    return;
  }
  const __m512 wa = _mm512_loadu_ps(s.w + m), wb = _mm512_loadu_ps(s.w + n);
  const __m512 weightSum = _mm512_add_ps(wa, wb);
  const __mmask16 mask = activeLanes(s, h, i) & _mm512_cmp_ps_mask(weightSum, zero, _CMP_GT_OQ) &
                         _mm512_cmp_ps_mask(lengthSquared, zero, _CMP_GT_OQ);
  const __m512 scale = _mm512_div_ps(_mm512_sub_ps(length, segment), _mm512_mul_ps(length, weightSum));
  const __m512 sa = _mm512_mul_ps(wa, scale), sb = _mm512_mul_ps(wb, scale);
  _mm512_storeu_ps(s.x + m, _mm512_mask_add_ps(ax, mask, ax, _mm512_mul_ps(dx, sa)));
  _mm512_storeu_ps(s.y + m, _mm512_mask_add_ps(ay, mask, ay, _mm512_mul_ps(dy, sa)));
  _mm512_storeu_ps(s.z + m, _mm512_mask_add_ps(az, mask, az, _mm512_mul_ps(dz, sa)));
  _mm512_storeu_ps(s.x + n, _mm512_mask_sub_ps(bx, mask, bx, _mm512_mul_ps(dx, sb)));
  _mm512_storeu_ps(s.y + n, _mm512_mask_sub_ps(by, mask, by, _mm512_mul_ps(dy, sb)));
  _mm512_storeu_ps(s.z + n, _mm512_mask_sub_ps(bz, mask, bz, _mm512_mul_ps(dz, sb)));
}

// tetherRow for wide group h: projectTether(x[i], root, reach[i]); `root` holds the wide
// group's roots as 3 × kWideWidth floats (x, y, z).
MANE_AVX512 inline void tetherRow(const StrandLanes& s, std::size_t h, std::size_t i, std::size_t plain,
                                  const float* root) noexcept {
  const std::size_t n = i * kBlockLanes + h * kWideWidth;
  const __m512 px = _mm512_loadu_ps(s.x + n), py = _mm512_loadu_ps(s.y + n), pz = _mm512_loadu_ps(s.z + n);
  const __m512 reach = _mm512_loadu_ps(s.reach + n);
  const __m512 rx = _mm512_loadu_ps(root), ry = _mm512_loadu_ps(root + kWideWidth),
               rz = _mm512_loadu_ps(root + 2 * kWideWidth);
  const __m512 dx = _mm512_sub_ps(px, rx), dy = _mm512_sub_ps(py, ry), dz = _mm512_sub_ps(pz, rz);
  const __m512 lengthSquared =
      _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)), _mm512_mul_ps(dz, dz));
  const __mmask16 stretched = _mm512_cmp_ps_mask(lengthSquared, _mm512_mul_ps(reach, reach), _CMP_GT_OQ);
  const __mmask16 mask = i < plain ? stretched : __mmask16(activeLanes(s, h, i) & stretched);
  if (mask == 0) return;  // nothing stretched: stores would change nothing
  const __m512 ratio = _mm512_div_ps(reach, squareRoot(lengthSquared));
  _mm512_storeu_ps(s.x + n, _mm512_mask_add_ps(px, mask, rx, _mm512_mul_ps(dx, ratio)));
  _mm512_storeu_ps(s.y + n, _mm512_mask_add_ps(py, mask, ry, _mm512_mul_ps(dy, ratio)));
  _mm512_storeu_ps(s.z + n, _mm512_mask_add_ps(pz, mask, rz, _mm512_mul_ps(dz, ratio)));
}

// Wide group h's roots (row 0) into `root` (3 × kWideWidth floats), as tetherRow reads them.
MANE_AVX512 inline void copyRoots(const StrandLanes& s, std::size_t h, float* root) noexcept {
  const std::size_t r = h * kWideWidth;
  _mm512_storeu_ps(root, _mm512_loadu_ps(s.x + r));
  _mm512_storeu_ps(root + kWideWidth, _mm512_loadu_ps(s.y + r));
  _mm512_storeu_ps(root + 2 * kWideWidth, _mm512_loadu_ps(s.z + r));
}

}  // namespace wide

/// stepAvx2 with AVX-512 registers: the same wavefront, the same bits; `storage` as there
/// (stepStorage(iterations) floats). Call only when cpuHasAvx512().
MANE_AVX512 inline void stepAvx512(const StrandLanes& lanes, float keep, const glm::vec3& kick, int iterations,
                                   bool tethers, float* storage) noexcept {
  const StrandLanes s = lanes;  // a local copy, as in stepAvx2
  const __m512 kk = _mm512_set1_ps(keep), kx = _mm512_set1_ps(kick.x), ky = _mm512_set1_ps(kick.y),
               kz = _mm512_set1_ps(kick.z);
  const std::size_t wideGroups = (s.groups + 1) / 2;
  std::size_t plain[kWideGroups];
  for (std::size_t h = 0; h < kWideGroups; ++h) plain[h] = std::min(s.plainRows[2 * h], s.plainRows[2 * h + 1]);
  const std::size_t sweeps = static_cast<std::size_t>(iterations > 0 ? iterations : 0);
  const std::size_t times = s.longest + (sweeps > 0 ? 2 * (sweeps - 1) : 0);
  for (std::size_t t = 1; t <= times; ++t) {
    if (t < s.longest)
      for (std::size_t h = 0; h < wideGroups; ++h) wide::integrateRow(s, h, t, plain[h], kk, kx, ky, kz);
    for (std::size_t k = 0; k < sweeps && 2 * k < t; ++k) {
      const std::size_t i = t - 2 * k;
      float* root = storage + k * 3 * kBlockLanes;
      if (i < s.longest)
        for (std::size_t h = 0; h < wideGroups; ++h) {
          wide::distanceRow(s, h, i, plain[h]);
          if (i == 1) wide::copyRoots(s, h, root + h * 3 * kWideWidth);
        }
      if (tethers && i >= 2 && i - 1 < s.longest)
        for (std::size_t h = 0; h < wideGroups; ++h) wide::tetherRow(s, h, i - 1, plain[h], root + h * 3 * kWideWidth);
    }
  }
}

#undef MANE_AVX512

}  // namespace mane::physics::detail

#endif  // MANE_STRAND_LANES_AVX2
