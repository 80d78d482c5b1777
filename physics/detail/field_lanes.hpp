#pragma once
// Internal: a signed distance field (sdf.hpp) on 8 lanes at once for the hair step's collision
// kernels: SignedDistanceField::sampleWithGradient, bit for bit (the same clamp, cell, trilinear
// weights and gradient, operation for operation), a cache of the last sample per lane, and
// SignedDistanceField::mayBeBelow's culls (the contact box and cells). Not part of the public API.
//
// Samples load their 8 node values per lane as 4 pairs of x-neighbours (8 bytes each); lanes
// that do not sample read nodes 0 and 1 and discard them, so no load leaves the grid.
// tests/physics/colliders_test.cpp checks samples and culls against the scalar field lane by
// lane.

#include <cstdint>

#include <glm/vec3.hpp>

#include "physics/detail/lane_math.hpp"
#include "physics/sdf.hpp"

#if MANE_STRAND_LANES_AVX2

namespace mane::physics::detail::lanes {

#define MANE_AVX2 __attribute__((target("avx2")))

// A field's constants spread over the lanes, set up once per pass over a block so that a sample
// recomputes none of them; with the contact box and cells (sdf.hpp) where `thickness` lets them
// cull.
struct FieldLanes {
  const SignedDistanceField* field = nullptr;  // null: the set has no field
  const float* values = nullptr;
  const std::int32_t* contactCells = nullptr;
  Vec origin{}, top{};  // top: dims − 1, grid units
  __m256 inverse{}, cellSize{};
  __m256i lastX{}, lastY{}, lastZ{};  // dims − 2: the last cell along each axis
  __m256i strideY{}, strideZ{};       // nodes
  int rowStride = 0, sliceStride = 0;
  bool culls = false;    // the contact box and cells hold for `thickness`
  Vec lower{}, upper{};  // the contact box

  MANE_AVX2 FieldLanes(const SignedDistanceField* f, float thickness) noexcept : field(f) {
    if (!f) return;
    const glm::ivec3 dims = f->dimensions();
    values = f->values().data();
    origin = splat(f->origin());
    top = splat(glm::vec3(dims - 1));
    inverse = splat(f->inverseCellSize());
    cellSize = splat(f->cellSize());
    lastX = _mm256_set1_epi32(dims.x - 2), lastY = _mm256_set1_epi32(dims.y - 2), lastZ = _mm256_set1_epi32(dims.z - 2);
    rowStride = dims.x, sliceStride = dims.x * dims.y;
    strideY = _mm256_set1_epi32(rowStride), strideZ = _mm256_set1_epi32(sliceStride);
    culls = thickness < f->contactLevel() - 1e-6f;
    lower = splat(f->contactLower()), upper = splat(f->contactUpper());
    contactCells = reinterpret_cast<const std::int32_t*>(f->contactCells().data());
  }
};

// The node values at[lane] + offset and at[lane] + offset + 1 (neighbours along x, adjacent in
// memory) of the 8 lanes: one 8-byte load per lane, two lanes to a 128-bit half. Plain loads,
// not gathers: AVX2 gathers are microcoded and slow on many AMD cores, and these loads issue as
// early and as independently as a gather's.
MANE_AVX2 inline void loadNodePairs(const float* values, const std::int32_t (&at)[kSimdWidth], int offset,
                                    __m256& first, __m256& second) noexcept {
  const auto pair = [&](int l) MANE_AVX2 {  // a b of lane l (an unaligned 8-byte load)
    return _mm_loadl_epi64(reinterpret_cast<const __m128i*>(values + at[l] + offset));
  };
  const auto pairs = [&](int l) MANE_AVX2 {  // a b of lanes l and l + 1
    return _mm_castsi128_ps(_mm_unpacklo_epi64(pair(l), pair(l + 1)));
  };
  const __m256 low = _mm256_insertf128_ps(_mm256_castps128_ps256(pairs(0)), pairs(4), 1);
  const __m256 high = _mm256_insertf128_ps(_mm256_castps128_ps256(pairs(2)), pairs(6), 1);
  // low = a0 b0 a1 b1 | a4 b4 a5 b5, high = a2 b2 a3 b3 | a6 b6 a7 b7.
  first = _mm256_shuffle_ps(low, high, 0x88);
  second = _mm256_shuffle_ps(low, high, 0xDD);
}

// SignedDistanceField::interpolate at grid coordinates c (inside the grid) for every lane: the
// trilinear value and its gradient (metres).
MANE_AVX2 inline __m256 interpolateField(const FieldLanes& f, const Vec& c, Vec& gradient) noexcept {
  const __m256i i = _mm256_min_epi32(_mm256_cvttps_epi32(c.x), f.lastX);
  const __m256i j = _mm256_min_epi32(_mm256_cvttps_epi32(c.y), f.lastY);
  const __m256i k = _mm256_min_epi32(_mm256_cvttps_epi32(c.z), f.lastZ);
  const __m256 fx = sub(c.x, _mm256_cvtepi32_ps(i)), fy = sub(c.y, _mm256_cvtepi32_ps(j)),
               fz = sub(c.z, _mm256_cvtepi32_ps(k));
  alignas(32) std::int32_t at[kSimdWidth];
  _mm256_store_si256(
      reinterpret_cast<__m256i*>(at),
      _mm256_add_epi32(_mm256_add_epi32(i, _mm256_mullo_epi32(j, f.strideY)), _mm256_mullo_epi32(k, f.strideZ)));
  __m256 v000, v100, v010, v110, v001, v101, v011, v111;
  loadNodePairs(f.values, at, 0, v000, v100);
  loadNodePairs(f.values, at, f.rowStride, v010, v110);
  loadNodePairs(f.values, at, f.sliceStride, v001, v101);
  loadNodePairs(f.values, at, f.rowStride + f.sliceStride, v011, v111);
  const __m256 c00 = add(v000, mul(sub(v100, v000), fx)), c10 = add(v010, mul(sub(v110, v010), fx));
  const __m256 c01 = add(v001, mul(sub(v101, v001), fx)), c11 = add(v011, mul(sub(v111, v011), fx));
  const __m256 c0 = add(c00, mul(sub(c10, c00), fy)), c1 = add(c01, mul(sub(c11, c01), fy));
  const __m256 dx0 = add(sub(v100, v000), mul(sub(sub(v110, v010), sub(v100, v000)), fy));
  const __m256 dx1 = add(sub(v101, v001), mul(sub(sub(v111, v011), sub(v101, v001)), fy));
  const __m256 dy0 = sub(c10, c00), dy1 = sub(c11, c01);
  gradient = {mul(add(dx0, mul(sub(dx1, dx0), fz)), f.inverse), mul(add(dy0, mul(sub(dy1, dy0), fz)), f.inverse),
              mul(sub(c1, c0), f.inverse)};
  return add(c0, mul(sub(c1, c0), fz));
}

// SignedDistanceField::sampleWithGradient for the lanes of `mask`; other lanes of `value` and
// `gradient` keep what they held.
MANE_AVX2 inline void sampleField(const FieldLanes& f, const Vec& p, __m256 mask, __m256& value,
                                  Vec& gradient) noexcept {
  Vec u{mul(sub(p.x, f.origin.x), f.inverse), mul(sub(p.y, f.origin.y), f.inverse),
        mul(sub(p.z, f.origin.z), f.inverse)};
  const __m256 zero = _mm256_setzero_ps();
  // Inside the grid (not NaN): the clamp leaves u as it is.
  const __m256 inside = both(both(both(_mm256_cmp_ps(u.x, zero, _CMP_GE_OQ), _mm256_cmp_ps(u.y, zero, _CMP_GE_OQ)),
                                  both(_mm256_cmp_ps(u.z, zero, _CMP_GE_OQ), _mm256_cmp_ps(u.x, f.top.x, _CMP_LE_OQ))),
                             both(_mm256_cmp_ps(u.y, f.top.y, _CMP_LE_OQ), _mm256_cmp_ps(u.z, f.top.z, _CMP_LE_OQ)));
  if (!any(butNot(mask, inside))) {
    // Lanes outside `mask` read node 0; their results are discarded.
    Vec sampledGradient;
    const __m256 sampled = interpolateField(f, {both(u.x, mask), both(u.y, mask), both(u.z, mask)}, sampledGradient);
    value = pick(value, sampled, mask);
    gradient = pick(gradient, sampledGradient, mask);
    return;
  }
  const __m256 nan = either(either(_mm256_cmp_ps(u.x, u.x, _CMP_UNORD_Q), _mm256_cmp_ps(u.y, u.y, _CMP_UNORD_Q)),
                            _mm256_cmp_ps(u.z, u.z, _CMP_UNORD_Q));
  const __m256 nanValue = add(add(u.x, u.y), u.z);  // NaN in, NaN out
  const __m256 gathering = butNot(mask, nan);
  // Lanes that do not sample read node 0 (their results are discarded).
  u = pick({zero, zero, zero}, u, gathering);
  const Vec c{clampLanes(u.x, zero, f.top.x), clampLanes(u.y, zero, f.top.y), clampLanes(u.z, zero, f.top.z)};
  Vec sampledGradient;
  __m256 sampled = interpolateField(f, c, sampledGradient);
  // Outside the grid: the nearest grid point's value plus the way there.
  const __m256 clamped = butNot(gathering, inside);
  const Vec outward = scaled(sub(u, c), f.cellSize);
  const __m256 gap = _mm256_sqrt_ps(dot(outward, outward));
  const Vec outwardGradient{div(outward.x, gap), div(outward.y, gap), div(outward.z, gap)};
  sampled = pick(sampled, add(sampled, gap), clamped);
  sampledGradient = pick(sampledGradient, outwardGradient, clamped);
  value = pick(value, pick(nanValue, sampled, gathering), mask);
  gradient = pick(gradient, sampledGradient, gathering);
}

// The field samples of one collideParticle call, lane by lane: like the scalar code's cache, a
// lane whose position has not changed (byte for byte) since its last sample reuses it, which is
// bit for bit what sampling again would return.
struct FieldSamples {
  const FieldLanes& field;
  __m256 value = _mm256_setzero_ps();
  Vec gradient{_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
  Vec at{_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
  __m256 held = _mm256_setzero_ps();  // lanes with a sample

  MANE_AVX2 void sample(const Vec& position, __m256 mask) noexcept {
    const __m256 current =
        both(held, both(both(sameBits(position.x, at.x), sameBits(position.y, at.y)), sameBits(position.z, at.z)));
    const __m256 needed = butNot(mask, current);
    if (!any(needed)) return;
    sampleField(field, position, needed, value, gradient);
    at = pick(at, position, needed);
    held = either(held, needed);
  }
};

// SignedDistanceField::mayBeBelow's contact box test, for the lanes of `mask`.
MANE_AVX2 inline __m256 fieldMayBeBelow(const FieldLanes& f, const Vec& p, __m256 mask) noexcept {
  if (!f.culls) return mask;
  mask = both(mask, both(both(_mm256_cmp_ps(p.x, f.lower.x, _CMP_GE_OQ), _mm256_cmp_ps(p.y, f.lower.y, _CMP_GE_OQ)),
                         _mm256_cmp_ps(p.z, f.lower.z, _CMP_GE_OQ)));
  return both(mask, both(both(_mm256_cmp_ps(p.x, f.upper.x, _CMP_LE_OQ), _mm256_cmp_ps(p.y, f.upper.y, _CMP_LE_OQ)),
                         _mm256_cmp_ps(p.z, f.upper.z, _CMP_LE_OQ)));
}

// SignedDistanceField::mayBeBelow for the lanes of `mask`: the contact box, then the contact
// cells. In the box, grid coordinates lie within (−1, dims), where truncation and the last-cell
// limit give the cell that sampleField's clamp gives.
MANE_AVX2 inline __m256 fieldMayTouch(const FieldLanes& f, const Vec& p, __m256 mask) noexcept {
  if (!f.culls) return mask;
  mask = fieldMayBeBelow(f, p, mask);
  if (!any(mask)) return mask;
  const __m256i i = _mm256_min_epi32(_mm256_cvttps_epi32(mul(sub(p.x, f.origin.x), f.inverse)), f.lastX);
  const __m256i j = _mm256_min_epi32(_mm256_cvttps_epi32(mul(sub(p.y, f.origin.y), f.inverse)), f.lastY);
  const __m256i k = _mm256_min_epi32(_mm256_cvttps_epi32(mul(sub(p.z, f.origin.z), f.inverse)), f.lastZ);
  const __m256i cell = _mm256_and_si256(  // other lanes: cell 0
      _mm256_add_epi32(_mm256_add_epi32(i, _mm256_mullo_epi32(j, f.strideY)), _mm256_mullo_epi32(k, f.strideZ)),
      _mm256_castps_si256(mask));
  // One gather of the cells' words: cheaper here than reading them lane by lane.
  const __m256i word = _mm256_i32gather_epi32(f.contactCells, _mm256_srli_epi32(cell, 5), 4);
  const __m256i bit = _mm256_sllv_epi32(_mm256_set1_epi32(1), _mm256_and_si256(cell, _mm256_set1_epi32(31)));
  return both(mask, _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(word, bit), bit)));
}

#undef MANE_AVX2

}  // namespace mane::physics::detail::lanes

#endif  // MANE_STRAND_LANES_AVX2
