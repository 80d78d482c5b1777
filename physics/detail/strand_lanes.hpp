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
// the same values the scalar branches keep; where every lane of a row takes the same branch
// (plainRows, a full movemask), the blend is left out, which stores the same values. The fused
// step (stepAvx2) reorders whole operations only where their operands are the same either way;
// strand_lanes_avx512.hpp has it again for AVX-512 registers. tests/physics/hair_test.cpp checks
// AVX2 and AVX-512 against the scalar path bit for bit.

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <glm/mat4x4.hpp>
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
// Independent registers per particle row: enough sqrt and divide chains in flight, also when
// stepAvx512 (strand_lanes_avx512.hpp) packs two groups into one register.
inline constexpr std::size_t kSimdGroups = 8;
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
  // Per group: rows 2 ≤ i < plainRows[g] have count > i and w = 1 at rows i − 1 and i in every
  // lane, so the AVX2 kernels may skip those masks there (markPlainRows; 0: never).
  std::size_t plainRows[kSimdGroups] = {};
};

/// Sets `s.plainRows` from its counts and inverse masses (again whenever a count changes).
inline void markPlainRows(StrandLanes& s) noexcept {
  for (std::size_t g = 0; g < kSimdGroups; ++g) {
    std::size_t rows = g < s.groups ? s.longest : 0;
    for (std::size_t b = g * kSimdWidth; b < (g + 1) * kSimdWidth; ++b)
      rows = std::min(rows, static_cast<std::size_t>(s.count[b] > 0 ? s.count[b] : 0));
    std::size_t plain = 0;
    for (std::size_t i = 1; i < rows; ++i) {
      bool unit = true;
      for (std::size_t b = g * kSimdWidth; b < (g + 1) * kSimdWidth; ++b) unit = unit && s.w[i * kBlockLanes + b] == 1.0f;
      if (!unit) break;
      plain = i + 1;
    }
    s.plainRows[g] = plain;
  }
}

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

// verletLanes where every lane moves.
MANE_AVX2 inline void verletLanes(float* c, float* p, __m256 keep, __m256 kick) noexcept {
  const __m256 current = _mm256_loadu_ps(c), previous = _mm256_loadu_ps(p);
  _mm256_storeu_ps(c, _mm256_add_ps(_mm256_add_ps(current, _mm256_mul_ps(_mm256_sub_ps(current, previous), keep)), kick));
  _mm256_storeu_ps(p, current);
}

// verletPosition for particle row i of group g, where i < count and w > 0.
MANE_AVX2 inline void integrateRow(const StrandLanes& s, std::size_t g, std::size_t i, __m256 keep, __m256 kx, __m256 ky,
                                   __m256 kz) noexcept {
  const std::size_t n = i * kBlockLanes + g * kSimdWidth;
  if (i < s.plainRows[g]) {  // every lane moves: no blend
    verletLanes(s.x + n, s.px + n, keep, kx);
    verletLanes(s.y + n, s.py + n, keep, ky);
    verletLanes(s.z + n, s.pz + n, keep, kz);
    return;
  }
  const __m256 mask =
      _mm256_and_ps(laneMask(s, g, i), _mm256_cmp_ps(_mm256_loadu_ps(s.w + n), _mm256_setzero_ps(), _CMP_GT_OQ));
  verletLanes(s.x + n, s.px + n, keep, kx, mask);
  verletLanes(s.y + n, s.py + n, keep, ky, mask);
  verletLanes(s.z + n, s.pz + n, keep, kz, mask);
}

// projectDistance(x[i−1], x[i], w[i−1], w[i], segment[i]) for group g, operation for operation.
MANE_AVX2 inline void distanceRow(const StrandLanes& s, std::size_t g, std::size_t i) noexcept {
  const __m256 zero = _mm256_setzero_ps();
  const std::size_t n = i * kBlockLanes + g * kSimdWidth, m = n - kBlockLanes;
  if (i >= 2 && i < s.plainRows[g]) {
    // Both ends weigh 1: weightSum = 2, so length · weightSum = length + length (both exact
    // doublings) and wa · scale = wb · scale = scale; the same values with fewer operations.
    const __m256 ax = _mm256_loadu_ps(s.x + m), ay = _mm256_loadu_ps(s.y + m), az = _mm256_loadu_ps(s.z + m);
    const __m256 bx = _mm256_loadu_ps(s.x + n), by = _mm256_loadu_ps(s.y + n), bz = _mm256_loadu_ps(s.z + n);
    const __m256 dx = _mm256_sub_ps(bx, ax), dy = _mm256_sub_ps(by, ay), dz = _mm256_sub_ps(bz, az);
    const __m256 lengthSquared =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
    const __m256 mask = _mm256_cmp_ps(lengthSquared, zero, _CMP_GT_OQ);
    const __m256 length = _mm256_sqrt_ps(lengthSquared);
    const __m256 scale =
        _mm256_div_ps(_mm256_sub_ps(length, _mm256_loadu_ps(s.segment + n)), _mm256_add_ps(length, length));
    const __m256 mx = _mm256_mul_ps(dx, scale), my = _mm256_mul_ps(dy, scale), mz = _mm256_mul_ps(dz, scale);
    if (_mm256_movemask_ps(mask) == 0xFF) {  // no coincident ends: every lane moves
      _mm256_storeu_ps(s.x + m, _mm256_add_ps(ax, mx));
      _mm256_storeu_ps(s.y + m, _mm256_add_ps(ay, my));
      _mm256_storeu_ps(s.z + m, _mm256_add_ps(az, mz));
      _mm256_storeu_ps(s.x + n, _mm256_sub_ps(bx, mx));
      _mm256_storeu_ps(s.y + n, _mm256_sub_ps(by, my));
      _mm256_storeu_ps(s.z + n, _mm256_sub_ps(bz, mz));
      return;
    }
    _mm256_storeu_ps(s.x + m, _mm256_blendv_ps(ax, _mm256_add_ps(ax, mx), mask));
    _mm256_storeu_ps(s.y + m, _mm256_blendv_ps(ay, _mm256_add_ps(ay, my), mask));
    _mm256_storeu_ps(s.z + m, _mm256_blendv_ps(az, _mm256_add_ps(az, mz), mask));
    _mm256_storeu_ps(s.x + n, _mm256_blendv_ps(bx, _mm256_sub_ps(bx, mx), mask));
    _mm256_storeu_ps(s.y + n, _mm256_blendv_ps(by, _mm256_sub_ps(by, my), mask));
    _mm256_storeu_ps(s.z + n, _mm256_blendv_ps(bz, _mm256_sub_ps(bz, mz), mask));
    return;
  }
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

// projectTether(x[i], root, reach[i]) for group g, operation for operation; `root` holds the
// group's roots as 3 × kSimdWidth floats (x, y, z).
MANE_AVX2 inline void tetherRow(const StrandLanes& s, std::size_t g, std::size_t i, const float* root) noexcept {
  const std::size_t n = i * kBlockLanes + g * kSimdWidth;
  const __m256 px = _mm256_loadu_ps(s.x + n), py = _mm256_loadu_ps(s.y + n), pz = _mm256_loadu_ps(s.z + n);
  const __m256 reach = _mm256_loadu_ps(s.reach + n);
  const __m256 rx = _mm256_loadu_ps(root), ry = _mm256_loadu_ps(root + kSimdWidth),
               rz = _mm256_loadu_ps(root + 2 * kSimdWidth);
  const __m256 dx = _mm256_sub_ps(px, rx), dy = _mm256_sub_ps(py, ry), dz = _mm256_sub_ps(pz, rz);
  const __m256 lengthSquared =
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
  const __m256 stretched = _mm256_cmp_ps(lengthSquared, _mm256_mul_ps(reach, reach), _CMP_GT_OQ);
  const __m256 mask = i < s.plainRows[g] ? stretched : _mm256_and_ps(laneMask(s, g, i), stretched);
  const int moved = _mm256_movemask_ps(mask);
  if (moved == 0) return;  // nothing stretched: stores would change nothing
  const __m256 ratio = _mm256_div_ps(reach, _mm256_sqrt_ps(lengthSquared));
  const __m256 qx = _mm256_add_ps(rx, _mm256_mul_ps(dx, ratio)), qy = _mm256_add_ps(ry, _mm256_mul_ps(dy, ratio)),
               qz = _mm256_add_ps(rz, _mm256_mul_ps(dz, ratio));
  if (moved == 0xFF) {  // every lane moves: no blend
    _mm256_storeu_ps(s.x + n, qx);
    _mm256_storeu_ps(s.y + n, qy);
    _mm256_storeu_ps(s.z + n, qz);
    return;
  }
  _mm256_storeu_ps(s.x + n, _mm256_blendv_ps(px, qx, mask));
  _mm256_storeu_ps(s.y + n, _mm256_blendv_ps(py, qy, mask));
  _mm256_storeu_ps(s.z + n, _mm256_blendv_ps(pz, qz, mask));
}

// Group g's roots (row 0) into `root` (3 × kSimdWidth floats), as tetherRow reads them.
MANE_AVX2 inline void copyRoots(const StrandLanes& s, std::size_t g, float* root) noexcept {
  const std::size_t r = g * kSimdWidth;
  _mm256_storeu_ps(root, _mm256_loadu_ps(s.x + r));
  _mm256_storeu_ps(root + kSimdWidth, _mm256_loadu_ps(s.y + r));
  _mm256_storeu_ps(root + 2 * kSimdWidth, _mm256_loadu_ps(s.z + r));
}

MANE_AVX2 inline void integrateAvx2(const StrandLanes& s, float keep, const glm::vec3& kick) noexcept {
  const __m256 k = _mm256_set1_ps(keep), kx = _mm256_set1_ps(kick.x), ky = _mm256_set1_ps(kick.y),
               kz = _mm256_set1_ps(kick.z);
  for (std::size_t i = 1; i < s.longest; ++i)
    for (std::size_t g = 0; g < s.groups; ++g) integrateRow(s, g, i, k, kx, ky, kz);
}

MANE_AVX2 inline void relaxDistancesAvx2(const StrandLanes& s) noexcept {
  for (std::size_t i = 1; i < s.longest; ++i)
    for (std::size_t g = 0; g < s.groups; ++g) distanceRow(s, g, i);
}

MANE_AVX2 inline void tethersAvx2(const StrandLanes& s) noexcept {
  for (std::size_t g = 0; g < s.groups; ++g) {
    float root[3 * kSimdWidth];
    copyRoots(s, g, root);
    for (std::size_t i = 1; i < s.longest; ++i) tetherRow(s, g, i, root);
  }
}

/// Storage `stepAvx2` needs for `iterations`, in floats.
constexpr std::size_t stepStorage(int iterations) noexcept {
  return static_cast<std::size_t>(iterations) * 3 * kBlockLanes;
}

/// integrateAvx2, then `iterations` times relaxDistancesAvx2 and (when `tethers`) tethersAvx2,
/// with the same result bit for bit, in one sweep root → tip instead of 1 + 2·iterations.
///
/// Why one sweep: each sweep is a chain of dependent sqrt and divide operations, so a sweep
/// alone keeps only kSimdGroups chains in flight, and each pass reads the whole block again.
/// The sweeps are instead run as a wavefront: at time t, sweep k relaxes the segment ending at
/// particle t − 2k and then the tether of particle t − 2k − 1. Every operation then finds its
/// operands exactly as the separate sweeps leave them: sweep k's segment (i−1, i) needs
/// particle i − 1 as sweep k left it (time t − 1) and particle i as sweep k − 1 left it, which
/// happened at time t − 1 (its segment (i, i+1) and tether i); sweep k − 1 and k + 1 touch
/// other particles at time t. Integration of particle i runs at time i, before sweep 0 reaches
/// it. The one value read out of order is the root: sweep k's tethers need it as sweep k's
/// first segment left it (the segment may add a signed zero to it), while later sweeps reach
/// the root first, so each sweep keeps a copy in `storage` (stepStorage(iterations) floats).
MANE_AVX2 inline void stepAvx2(const StrandLanes& lanes, float keep, const glm::vec3& kick, int iterations,
                               bool tethers, float* storage) noexcept {
  // A local copy: the vector stores may alias anything whose address is known outside, which
  // would make the compiler reload every array pointer after each store.
  const StrandLanes s = lanes;
  const __m256 kk = _mm256_set1_ps(keep), kx = _mm256_set1_ps(kick.x), ky = _mm256_set1_ps(kick.y),
               kz = _mm256_set1_ps(kick.z);
  const std::size_t sweeps = static_cast<std::size_t>(iterations > 0 ? iterations : 0);
  // The last operation: sweep (sweeps − 1)'s tether of the last particle, at time longest + 2(sweeps − 1).
  const std::size_t times = s.longest + (sweeps > 0 ? 2 * (sweeps - 1) : 0);
  for (std::size_t t = 1; t <= times; ++t) {
    if (t < s.longest)
      for (std::size_t g = 0; g < s.groups; ++g) integrateRow(s, g, t, kk, kx, ky, kz);
    for (std::size_t k = 0; k < sweeps && 2 * k < t; ++k) {
      const std::size_t i = t - 2 * k;
      float* root = storage + k * 3 * kBlockLanes;
      if (i < s.longest)
        for (std::size_t g = 0; g < s.groups; ++g) {
          distanceRow(s, g, i);
          if (i == 1) copyRoots(s, g, root + g * 3 * kSimdWidth);
        }
      if (tethers && i >= 2 && i - 1 < s.longest)
        for (std::size_t g = 0; g < s.groups; ++g) tetherRow(s, g, i - 1, root + g * 3 * kSimdWidth);
    }
  }
}

/// The roots' placement at the start of a step, as the scalar path does it per strand: each
/// active lane's previous root position takes its current one, and the root moves to
/// from + travel · fraction. `from` and `travel` hold x, y, z rows of kBlockLanes floats.
MANE_AVX2 inline void placeRootsAvx2(const StrandLanes& s, const float* from, const float* travel,
                                     float fraction) noexcept {
  const __m256 f = _mm256_set1_ps(fraction);
  float* const current[3] = {s.x, s.y, s.z};
  float* const previous[3] = {s.px, s.py, s.pz};
  for (std::size_t g = 0; g < s.groups; ++g) {
    const std::size_t r = g * kSimdWidth;
    const __m256 active = laneMask(s, g, 0);
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t at = c * kBlockLanes + r;
      const __m256 x = _mm256_loadu_ps(current[c] + r);
      const __m256 placed =
          _mm256_add_ps(_mm256_loadu_ps(from + at), _mm256_mul_ps(_mm256_loadu_ps(travel + at), f));
      _mm256_storeu_ps(previous[c] + r, _mm256_blendv_ps(_mm256_loadu_ps(previous[c] + r), x, active));
      _mm256_storeu_ps(current[c] + r, _mm256_blendv_ps(x, placed, active));
    }
  }
}

/// transformPoint(m, p) (hair_math.hpp) for the `groups` groups of lanes of `local` (x, y, z
/// rows of kBlockLanes floats) into `world`, operation for operation: glm computes m · (p, 1)
/// as (m₀·x + m₁·y) + (m₂·z + m₃·1), and m₃·1 is m₃ exactly.
MANE_AVX2 inline void transformRootsAvx2(const glm::mat4& m, const float* local, float* world,
                                         std::size_t groups) noexcept {
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t r = g * kSimdWidth;
    const __m256 x = _mm256_loadu_ps(local + r), y = _mm256_loadu_ps(local + kBlockLanes + r),
                 z = _mm256_loadu_ps(local + 2 * kBlockLanes + r);
    for (int c = 0; c < 3; ++c) {
      const __m256 xy = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(m[0][c]), x), _mm256_mul_ps(_mm256_set1_ps(m[1][c]), y));
      const __m256 zw = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(m[2][c]), z), _mm256_set1_ps(m[3][c]));
      _mm256_storeu_ps(world + static_cast<std::size_t>(c) * kBlockLanes + r, _mm256_add_ps(xy, zw));
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
