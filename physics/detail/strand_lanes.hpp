#pragma once
// Internal: the hair step's hot loops over a block of strands stored lane by lane (structure of
// arrays), with a hand-written AVX2 version. Not part of the public API.
//
// Layout: kBlockLanes strands side by side; component c of particle i of lane b lives at
// c[i * kBlockLanes + b]. Lanes whose strand is shorter than `longest`, idle lanes and strands
// stopped by a fault have count[b] ≤ i, and every kernel leaves their values untouched.
//
// Bit-exactness: each AVX2 kernel performs, per lane, exactly the IEEE operations of the scalar
// functions it mirrors (projectDistance, projectTether, verletPosition), in the same order:
// add, sub, mul, div and sqrt are correctly rounded in SIMD as in scalar SSE; no FMA (the
// functions are compiled for "avx2" only and the project builds with -ffp-contract=off), no
// approximate reciprocal. Conditions become lane masks and results are blended, which selects
// the same values the scalar branches keep. tests/physics/hair_test.cpp checks AVX2 against the
// scalar path bit for bit.

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "physics/constraints.hpp"

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define MANE_STRAND_LANES_AVX2 1
#else
#define MANE_STRAND_LANES_AVX2 0
#endif

namespace mane::physics::detail {

inline constexpr std::size_t kSimdWidth = 8;   // floats per AVX register
inline constexpr std::size_t kSimdGroups = 4;  // independent registers per particle: hides sqrt/div latency
inline constexpr std::size_t kBlockLanes = kSimdWidth * kSimdGroups;

/// A block of strands, lane by lane (see the file comment).
struct StrandLanes {
  float* x;
  float* y;
  float* z;
  float* px;  // previous positions
  float* py;
  float* pz;
  const float* w;                    // inverse masses (1/kg)
  const float* segment;              // rest distance to the previous particle, metres
  const float* reach;                // rest distance to the root along the strand, metres
  const std::int32_t* count;         // per lane: particles to simulate (0: lane idle or stopped)
  std::size_t longest;               // max of count
  std::size_t groups = kSimdGroups;  // the first groups of kSimdWidth lanes hold every active lane
};

/// True when the CPU running this process has AVX2 (checked once).
inline bool cpuHasAvx2() noexcept {
#if MANE_STRAND_LANES_AVX2
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

// ---- Scalar reference on the lane layout (the same functions the per-strand path calls). ----

inline void integrateScalar(const StrandLanes& s, float keep, const glm::vec3& kick) noexcept {
  for (std::size_t i = 1; i < s.longest; ++i)
    for (std::size_t b = 0; b < kBlockLanes; ++b) {
      const std::size_t n = i * kBlockLanes + b;
      if (static_cast<std::int32_t>(i) >= s.count[b] || s.w[n] <= 0.0f) continue;
      const glm::vec3 current(s.x[n], s.y[n], s.z[n]);
      const glm::vec3 next = current + (current - glm::vec3(s.px[n], s.py[n], s.pz[n])) * keep + kick;
      s.x[n] = next.x, s.y[n] = next.y, s.z[n] = next.z;
      s.px[n] = current.x, s.py[n] = current.y, s.pz[n] = current.z;
    }
}

inline void relaxDistancesScalar(const StrandLanes& s) noexcept {
  for (std::size_t i = 1; i < s.longest; ++i)
    for (std::size_t b = 0; b < kBlockLanes; ++b) {
      if (static_cast<std::int32_t>(i) >= s.count[b]) continue;
      const std::size_t n = i * kBlockLanes + b, m = n - kBlockLanes;
      glm::vec3 pa(s.x[m], s.y[m], s.z[m]), pb(s.x[n], s.y[n], s.z[n]);
      projectDistance(pa, pb, s.w[m], s.w[n], s.segment[n]);
      s.x[m] = pa.x, s.y[m] = pa.y, s.z[m] = pa.z;
      s.x[n] = pb.x, s.y[n] = pb.y, s.z[n] = pb.z;
    }
}

inline void tethersScalar(const StrandLanes& s) noexcept {
  for (std::size_t i = 1; i < s.longest; ++i)
    for (std::size_t b = 0; b < kBlockLanes; ++b) {
      if (static_cast<std::int32_t>(i) >= s.count[b]) continue;
      const std::size_t n = i * kBlockLanes + b;
      glm::vec3 p(s.x[n], s.y[n], s.z[n]);
      projectTether(p, glm::vec3(s.x[b], s.y[b], s.z[b]), s.reach[n]);
      s.x[n] = p.x, s.y[n] = p.y, s.z[n] = p.z;
    }
}

#if MANE_STRAND_LANES_AVX2

// ---- AVX2: call only when cpuHasAvx2(). ----

#define MANE_AVX2 __attribute__((target("avx2")))

// Lanes b of group g with i < count[b].
MANE_AVX2 inline __m256 laneMask(const StrandLanes& s, std::size_t g, std::size_t i) noexcept {
  const __m256i count = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s.count + g * kSimdWidth));
  return _mm256_castsi256_ps(_mm256_cmpgt_epi32(count, _mm256_set1_epi32(static_cast<int>(i))));
}

// verletPosition for one coordinate of 8 lanes: current + (current − previous)·keep + kick.
MANE_AVX2 inline void verletLanes(float* c, float* p, __m256 keep, __m256 kick, __m256 mask) noexcept {
  const __m256 current = _mm256_loadu_ps(c), previous = _mm256_loadu_ps(p);
  const __m256 next =
      _mm256_add_ps(_mm256_add_ps(current, _mm256_mul_ps(_mm256_sub_ps(current, previous), keep)), kick);
  _mm256_storeu_ps(c, _mm256_blendv_ps(current, next, mask));
  _mm256_storeu_ps(p, _mm256_blendv_ps(previous, current, mask));
}

MANE_AVX2 inline void integrateAvx2(const StrandLanes& s, float keep, const glm::vec3& kick) noexcept {
  const __m256 k = _mm256_set1_ps(keep), kx = _mm256_set1_ps(kick.x), ky = _mm256_set1_ps(kick.y),
               kz = _mm256_set1_ps(kick.z), zero = _mm256_setzero_ps();
  for (std::size_t i = 1; i < s.longest; ++i)
    for (std::size_t g = 0; g < s.groups; ++g) {
      const std::size_t n = i * kBlockLanes + g * kSimdWidth;
      // Where w > 0.
      const __m256 mask = _mm256_and_ps(laneMask(s, g, i), _mm256_cmp_ps(_mm256_loadu_ps(s.w + n), zero, _CMP_GT_OQ));
      verletLanes(s.x + n, s.px + n, k, kx, mask);
      verletLanes(s.y + n, s.py + n, k, ky, mask);
      verletLanes(s.z + n, s.pz + n, k, kz, mask);
    }
}

MANE_AVX2 inline void relaxDistancesAvx2(const StrandLanes& s) noexcept {
  const __m256 zero = _mm256_setzero_ps();
  for (std::size_t i = 1; i < s.longest; ++i)
    for (std::size_t g = 0; g < s.groups; ++g) {
      const std::size_t n = i * kBlockLanes + g * kSimdWidth, m = n - kBlockLanes;
      // projectDistance(x[i−1], x[i], w[i−1], w[i], segment[i]), operation for operation.
      const __m256 wa = _mm256_loadu_ps(s.w + m), wb = _mm256_loadu_ps(s.w + n);
      const __m256 weightSum = _mm256_add_ps(wa, wb);
      const __m256 ax = _mm256_loadu_ps(s.x + m), ay = _mm256_loadu_ps(s.y + m), az = _mm256_loadu_ps(s.z + m);
      const __m256 bx = _mm256_loadu_ps(s.x + n), by = _mm256_loadu_ps(s.y + n), bz = _mm256_loadu_ps(s.z + n);
      const __m256 dx = _mm256_sub_ps(bx, ax), dy = _mm256_sub_ps(by, ay), dz = _mm256_sub_ps(bz, az);
      const __m256 lengthSquared =
          _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
      const __m256 mask = _mm256_and_ps(_mm256_and_ps(laneMask(s, g, i), _mm256_cmp_ps(weightSum, zero, _CMP_GT_OQ)),
                                        _mm256_cmp_ps(lengthSquared, zero, _CMP_GT_OQ));
      const __m256 length = _mm256_sqrt_ps(lengthSquared);
      const __m256 scale =
          _mm256_div_ps(_mm256_sub_ps(length, _mm256_loadu_ps(s.segment + n)), _mm256_mul_ps(length, weightSum));
      const __m256 sa = _mm256_mul_ps(wa, scale), sb = _mm256_mul_ps(wb, scale);
      _mm256_storeu_ps(s.x + m, _mm256_blendv_ps(ax, _mm256_add_ps(ax, _mm256_mul_ps(dx, sa)), mask));
      _mm256_storeu_ps(s.y + m, _mm256_blendv_ps(ay, _mm256_add_ps(ay, _mm256_mul_ps(dy, sa)), mask));
      _mm256_storeu_ps(s.z + m, _mm256_blendv_ps(az, _mm256_add_ps(az, _mm256_mul_ps(dz, sa)), mask));
      _mm256_storeu_ps(s.x + n, _mm256_blendv_ps(bx, _mm256_sub_ps(bx, _mm256_mul_ps(dx, sb)), mask));
      _mm256_storeu_ps(s.y + n, _mm256_blendv_ps(by, _mm256_sub_ps(by, _mm256_mul_ps(dy, sb)), mask));
      _mm256_storeu_ps(s.z + n, _mm256_blendv_ps(bz, _mm256_sub_ps(bz, _mm256_mul_ps(dz, sb)), mask));
    }
}

MANE_AVX2 inline void tethersAvx2(const StrandLanes& s) noexcept {
  for (std::size_t g = 0; g < s.groups; ++g) {
    const std::size_t r = g * kSimdWidth;
    const __m256 rx = _mm256_loadu_ps(s.x + r), ry = _mm256_loadu_ps(s.y + r), rz = _mm256_loadu_ps(s.z + r);
    for (std::size_t i = 1; i < s.longest; ++i) {
      const std::size_t n = i * kBlockLanes + r;
      // projectTether(x[i], x[0], reach[i]), operation for operation.
      const __m256 px = _mm256_loadu_ps(s.x + n), py = _mm256_loadu_ps(s.y + n), pz = _mm256_loadu_ps(s.z + n);
      const __m256 reach = _mm256_loadu_ps(s.reach + n);
      const __m256 dx = _mm256_sub_ps(px, rx), dy = _mm256_sub_ps(py, ry), dz = _mm256_sub_ps(pz, rz);
      const __m256 lengthSquared =
          _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
      const __m256 mask =
          _mm256_and_ps(laneMask(s, g, i), _mm256_cmp_ps(lengthSquared, _mm256_mul_ps(reach, reach), _CMP_GT_OQ));
      if (_mm256_movemask_ps(mask) == 0) continue;  // nothing stretched: stores would change nothing
      const __m256 ratio = _mm256_div_ps(reach, _mm256_sqrt_ps(lengthSquared));
      _mm256_storeu_ps(s.x + n, _mm256_blendv_ps(px, _mm256_add_ps(rx, _mm256_mul_ps(dx, ratio)), mask));
      _mm256_storeu_ps(s.y + n, _mm256_blendv_ps(py, _mm256_add_ps(ry, _mm256_mul_ps(dy, ratio)), mask));
      _mm256_storeu_ps(s.z + n, _mm256_blendv_ps(pz, _mm256_add_ps(rz, _mm256_mul_ps(dz, ratio)), mask));
    }
  }
}

// Per lane of the block's groups: 0 when every coordinate of the lane is finite, NaN otherwise
// (v − v is 0 for finite v and NaN for NaN or ±∞). Lanes past their strand's end hold finite
// values, so a lane's sum speaks for its strand.
MANE_AVX2 inline void nonFiniteProbeAvx2(const StrandLanes& s, float (&probe)[kBlockLanes]) noexcept {
  for (std::size_t g = 0; g < s.groups; ++g) {
    __m256 sum = _mm256_setzero_ps();
    for (std::size_t i = 0; i < s.longest; ++i) {
      const std::size_t n = i * kBlockLanes + g * kSimdWidth;
      for (const float* c : {s.x + n, s.y + n, s.z + n}) {
        const __m256 v = _mm256_loadu_ps(c);
        sum = _mm256_add_ps(sum, _mm256_sub_ps(v, v));
      }
    }
    _mm256_storeu_ps(probe + g * kSimdWidth, sum);
  }
}

#undef MANE_AVX2

#endif  // MANE_STRAND_LANES_AVX2

}  // namespace mane::physics::detail
