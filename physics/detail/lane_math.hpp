#pragma once
// Internal: arithmetic on 8 lanes at once (one AVX2 register per coordinate) for the hair step's
// collision kernels (collision_lanes.hpp, field_lanes.hpp, tether_lanes.hpp). Each operation is
// the correctly rounded IEEE operation of its scalar counterpart, lane by lane: no FMA, no
// approximate reciprocal. Not part of the public API.

#include <glm/vec3.hpp>

#include "physics/detail/strand_lanes.hpp"

#if MANE_STRAND_LANES_AVX2

namespace mane::physics::detail::lanes {

#define MANE_AVX2 __attribute__((target("avx2")))

struct Vec {
  __m256 x, y, z;
};

MANE_AVX2 inline __m256 splat(float v) noexcept {
  return _mm256_set1_ps(v);
}
MANE_AVX2 inline __m256 add(__m256 a, __m256 b) noexcept {
  return _mm256_add_ps(a, b);
}
MANE_AVX2 inline __m256 sub(__m256 a, __m256 b) noexcept {
  return _mm256_sub_ps(a, b);
}
MANE_AVX2 inline __m256 mul(__m256 a, __m256 b) noexcept {
  return _mm256_mul_ps(a, b);
}
MANE_AVX2 inline __m256 div(__m256 a, __m256 b) noexcept {
  return _mm256_div_ps(a, b);
}
MANE_AVX2 inline __m256 both(__m256 a, __m256 b) noexcept {
  return _mm256_and_ps(a, b);
}
MANE_AVX2 inline __m256 either(__m256 a, __m256 b) noexcept {
  return _mm256_or_ps(a, b);
}
MANE_AVX2 inline __m256 butNot(__m256 a, __m256 b) noexcept {
  return _mm256_andnot_ps(b, a);
}
MANE_AVX2 inline bool any(__m256 mask) noexcept {
  return _mm256_movemask_ps(mask) != 0;
}
MANE_AVX2 inline __m256 pick(__m256 keep, __m256 take, __m256 mask) noexcept {
  return _mm256_blendv_ps(keep, take, mask);
}
MANE_AVX2 inline Vec pick(const Vec& keep, const Vec& take, __m256 mask) noexcept {
  return {pick(keep.x, take.x, mask), pick(keep.y, take.y, mask), pick(keep.z, take.z, mask)};
}
// a.x*b.x + a.y*b.y + a.z*b.z, left to right.
MANE_AVX2 inline __m256 dot(const Vec& a, const Vec& b) noexcept {
  return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z));
}
MANE_AVX2 inline Vec sub(const Vec& a, const Vec& b) noexcept {
  return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)};
}
MANE_AVX2 inline Vec scaled(const Vec& a, __m256 s) noexcept {
  return {mul(a.x, s), mul(a.y, s), mul(a.z, s)};
}
MANE_AVX2 inline Vec splat(const glm::vec3& v) noexcept {
  return {splat(v.x), splat(v.y), splat(v.z)};
}

// std::clamp(v, lo, hi) lane by lane: v < lo ? lo : (hi < v ? hi : v).
MANE_AVX2 inline __m256 clampLanes(__m256 v, __m256 lo, __m256 hi) noexcept {
  const __m256 low = pick(v, lo, _mm256_cmp_ps(v, lo, _CMP_LT_OQ));
  return pick(low, hi, _mm256_cmp_ps(hi, low, _CMP_LT_OQ));
}

// Lanes where a and b hold the same bytes.
MANE_AVX2 inline __m256 sameBits(__m256 a, __m256 b) noexcept {
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_castps_si256(a), _mm256_castps_si256(b)));
}

#undef MANE_AVX2

}  // namespace mane::physics::detail::lanes

#endif  // MANE_STRAND_LANES_AVX2
