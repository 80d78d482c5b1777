#pragma once
// Internal: the hair step's particle collisions for 8 particles at once (one AVX2 register per
// coordinate), on the lane layout of strand_lanes.hpp. Not part of the public API.
//
// Bit-exactness: `collidePointLanes` and `collideBlockAvx2` perform, per lane, the IEEE
// operations of the scalar HairSystem::collidePoint → collideParticle →
// SignedDistanceField::sampleWithGradient chain (colliders.cpp, sdf.hpp), in the same order, so a
// lane ends with the bits the scalar code gives that particle: the same cull tests, the same
// rounds, pushes, Newton steps and friction; `repairTethersAvx2` does the same for
// HairSystem::settleTether's rounds. Branches become lane masks; a lane leaves a loop where the
// scalar code would break out of it, and its values are then left untouched. Which lanes share a
// register (the row's, or particles packed from anywhere in the block) changes nothing in any
// lane. The scalar code's cache of the last field sample only saves work (it returns what
// sampling again returns); the lanes keep one too (FieldSamples), which may also be handed a
// sample taken earlier at the same position. Field samples gather their 8 node values per lane,
// as 4 pairs of x-neighbours (8 bytes each); lanes that do not sample read nodes 0 and 1 and
// discard them, so no gather leaves the grid.
// tests/physics/hair_test.cpp checks the AVX2 step against the scalar step bit for bit, with
// spheres, capsules, the field, friction and draped, taut strands.

#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "physics/colliders.hpp"
#include "physics/detail/strand_lanes.hpp"
#include "physics/sdf.hpp"

#if MANE_STRAND_LANES_AVX2

namespace mane::physics::detail {

/// A rigid pose of the colliders' body: world = axes · local + translation.
struct LanePose {
  const glm::vec3* axes;  // three columns
  glm::vec3 translation;
};

/// What one collision pass over a block needs: the set, its bounding ball and cull boxes (all in
/// the body's frame), and the poses at the end and at the start of the step.
struct LaneColliders {
  const ColliderSet* set;
  const ColliderBounds* bounds;
  const ColliderCull* cull;
  LanePose pose;
  LanePose before;
};

#define MANE_AVX2 __attribute__((target("avx2")))

namespace lanes {

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

// HairSystem's toHeadLocal: Rᵀ(x − t), each row a left-to-right dot product.
MANE_AVX2 inline Vec toLocal(const LanePose& pose, const Vec& world) noexcept {
  const Vec d = sub(world, splat(pose.translation));
  return {dot(splat(pose.axes[0]), d), dot(splat(pose.axes[1]), d), dot(splat(pose.axes[2]), d)};
}

// One coordinate of HairSystem's toWorld: ((a0·l.x + a1·l.y) + a2·l.z) + t.
MANE_AVX2 inline __m256 worldCoordinate(float a0, float a1, float a2, float t, const Vec& local) noexcept {
  return add(add(add(mul(splat(a0), local.x), mul(splat(a1), local.y)), mul(splat(a2), local.z)), splat(t));
}
MANE_AVX2 inline Vec toWorld(const LanePose& pose, const Vec& local) noexcept {
  const glm::vec3* a = pose.axes;
  const glm::vec3& t = pose.translation;
  return {worldCoordinate(a[0].x, a[1].x, a[2].x, t.x, local), worldCoordinate(a[0].y, a[1].y, a[2].y, t.y, local),
          worldCoordinate(a[0].z, a[1].z, a[2].z, t.z, local)};
}

// std::clamp(v, lo, hi) lane by lane: v < lo ? lo : (hi < v ? hi : v).
MANE_AVX2 inline __m256 clampLanes(__m256 v, __m256 lo, __m256 hi) noexcept {
  const __m256 low = pick(v, lo, _mm256_cmp_ps(v, lo, _CMP_LT_OQ));
  return pick(low, hi, _mm256_cmp_ps(hi, low, _CMP_LT_OQ));
}

// colliders.cpp's applyFriction, for the lanes of `mask`.
MANE_AVX2 inline void applyFriction(Vec& position, const Vec& previous, const Vec& normal, __m256 depth, float mu,
                                    __m256 mask) noexcept {
  if (!(mu > 0.0f)) return;
  const Vec displacement = sub(position, previous);
  const __m256 along = dot(displacement, normal);
  const Vec tangential = sub(displacement, scaled(normal, along));
  const __m256 slide = _mm256_sqrt_ps(dot(tangential, tangential));
  const __m256 sliding = both(mask, _mm256_cmp_ps(slide, _mm256_setzero_ps(), _CMP_GT_OQ));
  const __m256 stop = mul(splat(mu), depth);
  const Vec partial = scaled(tangential, div(stop, slide));
  const Vec removed = pick(partial, tangential, _mm256_cmp_ps(stop, slide, _CMP_GE_OQ));
  position = pick(position, sub(position, removed), sliding);
}

// colliders.cpp's pushOutOfBall followed, where the depth is positive, by friction; returns the
// lanes of `mask` that made contact (positive depth).
MANE_AVX2 inline __m256 pushOutOfBall(Vec& position, const Vec& previous, const Vec& centre, float reach, float mu,
                                      __m256 mask) noexcept {
  const Vec offset = sub(position, centre);
  const __m256 distanceSquared = dot(offset, offset);
  const __m256 inside = both(mask, _mm256_cmp_ps(distanceSquared, splat(reach * reach), _CMP_LT_OQ));
  if (!any(inside)) return inside;
  const __m256 distance = _mm256_sqrt_ps(distanceSquared);
  const __m256 centred = _mm256_cmp_ps(distance, _mm256_setzero_ps(), _CMP_GT_OQ);
  const Vec up{_mm256_setzero_ps(), splat(1.0f), _mm256_setzero_ps()};
  const Vec normal = pick(up, {div(offset.x, distance), div(offset.y, distance), div(offset.z, distance)}, centred);
  const Vec surface{add(centre.x, mul(normal.x, splat(reach))), add(centre.y, mul(normal.y, splat(reach))),
                    add(centre.z, mul(normal.z, splat(reach)))};
  position = pick(position, surface, inside);
  const __m256 depth = sub(splat(reach), distance);
  const __m256 contact = both(inside, _mm256_cmp_ps(depth, _mm256_setzero_ps(), _CMP_GT_OQ));
  applyFriction(position, previous, normal, depth, mu, contact);
  return contact;
}

// colliders.cpp's closestOnSegment(a, b, p).
MANE_AVX2 inline Vec closestOnSegment(const glm::vec3& a, const glm::vec3& b, const Vec& p) noexcept {
  const glm::vec3 ab = b - a;
  const float lengthSquared = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
  if (!(lengthSquared > 0.0f)) return splat(a);
  const __m256 t =
      clampLanes(div(dot(sub(p, splat(a)), splat(ab)), splat(lengthSquared)), _mm256_setzero_ps(), splat(1.0f));
  return {add(splat(a.x), mul(splat(ab.x), t)), add(splat(a.y), mul(splat(ab.y), t)),
          add(splat(a.z), mul(splat(ab.z), t))};
}

// The node values at[lane] + offset and at[lane] + offset + 1 (neighbours along x, adjacent in
// memory) of the 8 lanes: one 8-byte read per lane, two 4-lane gathers, instead of two 8-lane
// gathers of 4 bytes.
MANE_AVX2 inline void gatherNodePair(const float* values, __m256i at, int offset, __m256& first,
                                     __m256& second) noexcept {
  const __m256i index = _mm256_add_epi32(at, _mm256_set1_epi32(offset));
  const auto* base = reinterpret_cast<const double*>(values);  // read as bytes by the gather
  const __m256d zero = _mm256_setzero_pd(), all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  const __m256 low = _mm256_castpd_ps(_mm256_mask_i32gather_pd(zero, base, _mm256_castsi256_si128(index), all, 4));
  const __m256 high =
      _mm256_castpd_ps(_mm256_mask_i32gather_pd(zero, base, _mm256_extracti128_si256(index, 1), all, 4));
  // low = a0 b0 a1 b1 | a2 b2 a3 b3, high = a4 b4 a5 b5 | a6 b6 a7 b7.
  first = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(low, high, 0x88)), 0xD8));
  second = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(low, high, 0xDD)), 0xD8));
}

// SignedDistanceField::sampleWithGradient for the lanes of `mask`; other lanes of `value` and
// `gradient` keep what they held.
MANE_AVX2 inline void sampleField(const SignedDistanceField& field, const Vec& p, __m256 mask, __m256& value,
                                  Vec& gradient) noexcept {
  const glm::vec3 origin = field.origin();
  const __m256 inverse = splat(field.inverseCellSize());
  Vec u{mul(sub(p.x, splat(origin.x)), inverse), mul(sub(p.y, splat(origin.y)), inverse),
        mul(sub(p.z, splat(origin.z)), inverse)};
  const __m256 nan = either(either(_mm256_cmp_ps(u.x, u.x, _CMP_UNORD_Q), _mm256_cmp_ps(u.y, u.y, _CMP_UNORD_Q)),
                            _mm256_cmp_ps(u.z, u.z, _CMP_UNORD_Q));
  const __m256 nanValue = add(add(u.x, u.y), u.z);  // NaN in, NaN out
  const __m256 gathering = butNot(mask, nan);
  // Lanes that do not sample read node 0 (their results are discarded).
  u = pick({_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()}, u, gathering);
  const glm::ivec3 dims = field.dimensions();
  const Vec c{clampLanes(u.x, _mm256_setzero_ps(), splat(static_cast<float>(dims.x - 1))),
              clampLanes(u.y, _mm256_setzero_ps(), splat(static_cast<float>(dims.y - 1))),
              clampLanes(u.z, _mm256_setzero_ps(), splat(static_cast<float>(dims.z - 1)))};
  const __m256 inside = both(both(_mm256_cmp_ps(c.x, u.x, _CMP_EQ_OQ), _mm256_cmp_ps(c.y, u.y, _CMP_EQ_OQ)),
                             _mm256_cmp_ps(c.z, u.z, _CMP_EQ_OQ));

  // SignedDistanceField::interpolate at the clamped grid coordinates.
  const __m256i i = _mm256_min_epi32(_mm256_cvttps_epi32(c.x), _mm256_set1_epi32(dims.x - 2));
  const __m256i j = _mm256_min_epi32(_mm256_cvttps_epi32(c.y), _mm256_set1_epi32(dims.y - 2));
  const __m256i k = _mm256_min_epi32(_mm256_cvttps_epi32(c.z), _mm256_set1_epi32(dims.z - 2));
  const __m256 fx = sub(c.x, _mm256_cvtepi32_ps(i)), fy = sub(c.y, _mm256_cvtepi32_ps(j)),
               fz = sub(c.z, _mm256_cvtepi32_ps(k));
  const int sy = dims.x, sz = dims.x * dims.y;
  const __m256i at = _mm256_add_epi32(_mm256_add_epi32(i, _mm256_mullo_epi32(j, _mm256_set1_epi32(sy))),
                                      _mm256_mullo_epi32(k, _mm256_set1_epi32(sz)));
  const float* v = field.values().data();
  __m256 v000, v100, v010, v110, v001, v101, v011, v111;
  gatherNodePair(v, at, 0, v000, v100);
  gatherNodePair(v, at, sy, v010, v110);
  gatherNodePair(v, at, sz, v001, v101);
  gatherNodePair(v, at, sy + sz, v011, v111);
  const __m256 c00 = add(v000, mul(sub(v100, v000), fx)), c10 = add(v010, mul(sub(v110, v010), fx));
  const __m256 c01 = add(v001, mul(sub(v101, v001), fx)), c11 = add(v011, mul(sub(v111, v011), fx));
  const __m256 c0 = add(c00, mul(sub(c10, c00), fy)), c1 = add(c01, mul(sub(c11, c01), fy));
  const __m256 interpolated = add(c0, mul(sub(c1, c0), fz));
  const __m256 dx0 = add(sub(v100, v000), mul(sub(sub(v110, v010), sub(v100, v000)), fy));
  const __m256 dx1 = add(sub(v101, v001), mul(sub(sub(v111, v011), sub(v101, v001)), fy));
  const __m256 dy0 = sub(c10, c00), dy1 = sub(c11, c01);
  const Vec interpolatedGradient{mul(add(dx0, mul(sub(dx1, dx0), fz)), inverse),
                                 mul(add(dy0, mul(sub(dy1, dy0), fz)), inverse), mul(sub(c1, c0), inverse)};

  __m256 sampled = interpolated;
  Vec sampledGradient = interpolatedGradient;
  if (_mm256_movemask_ps(both(gathering, inside)) != _mm256_movemask_ps(gathering)) {
    // Outside the grid: the nearest grid point's value plus the way there.
    const __m256 cell = splat(field.cellSize());
    const Vec outward = scaled(sub(u, c), cell);
    const __m256 gap = _mm256_sqrt_ps(dot(outward, outward));
    const Vec outwardGradient{div(outward.x, gap), div(outward.y, gap), div(outward.z, gap)};
    sampled = pick(add(interpolated, gap), interpolated, inside);
    sampledGradient = pick(outwardGradient, interpolatedGradient, inside);
  }
  value = pick(value, pick(nanValue, sampled, gathering), mask);
  gradient = pick(gradient, sampledGradient, gathering);
}

// Lanes where a and b hold the same bytes.
MANE_AVX2 inline __m256 sameBits(__m256 a, __m256 b) noexcept {
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_castps_si256(a), _mm256_castps_si256(b)));
}

// The field samples of one collideParticle call, lane by lane: like the scalar code's cache, a
// lane whose position has not changed (byte for byte) since its last sample reuses it, which is
// bit for bit what sampling again would return.
struct FieldSamples {
  const SignedDistanceField* field;
  __m256 value = _mm256_setzero_ps();
  Vec gradient{_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
  Vec at{_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
  __m256 held = _mm256_setzero_ps();  // lanes with a sample

  MANE_AVX2 void sample(const Vec& position, __m256 mask) noexcept {
    const __m256 current =
        both(held, both(both(sameBits(position.x, at.x), sameBits(position.y, at.y)), sameBits(position.z, at.z)));
    const __m256 needed = butNot(mask, current);
    if (!any(needed)) return;
    sampleField(*field, position, needed, value, gradient);
    at = pick(at, position, needed);
    held = either(held, needed);
  }
};

// collideParticle's Newton steps while below `thickness`, onto thickness + kContactSkin, for
// the lanes of `mask`.
MANE_AVX2 inline void newtonToLevel(FieldSamples& samples, Vec& position, float thickness, __m256 mask) noexcept {
  const __m256 level = splat(thickness), target = splat(thickness + kContactSkin);
  for (int newton = 0; newton < 4; ++newton) {
    const Vec& g = samples.gradient;
    const __m256 g2 = dot(g, g);
    mask =
        both(both(mask, _mm256_cmp_ps(samples.value, level, _CMP_LT_OQ)), _mm256_cmp_ps(g2, splat(1e-12f), _CMP_GT_OQ));
    if (!any(mask)) return;
    const __m256 s = div(sub(target, samples.value), g2);
    position = pick(position,
                    {add(position.x, mul(g.x, s)), add(position.y, mul(g.y, s)), add(position.z, mul(g.z, s))}, mask);
    samples.sample(position, mask);
  }
}

// SignedDistanceField::mayBeBelow(p, thickness) for the lanes of `mask`.
MANE_AVX2 inline __m256 fieldMayBeBelow(const SignedDistanceField& field, float thickness, const Vec& p,
                                        __m256 mask) noexcept {
  if (!(thickness < field.contactLevel() - 1e-6f)) return mask;
  const glm::vec3 lo = field.contactLower(), hi = field.contactUpper();
  mask = both(mask, both(both(_mm256_cmp_ps(p.x, splat(lo.x), _CMP_GE_OQ), _mm256_cmp_ps(p.y, splat(lo.y), _CMP_GE_OQ)),
                         _mm256_cmp_ps(p.z, splat(lo.z), _CMP_GE_OQ)));
  return both(mask, both(both(_mm256_cmp_ps(p.x, splat(hi.x), _CMP_LE_OQ), _mm256_cmp_ps(p.y, splat(hi.y), _CMP_LE_OQ)),
                         _mm256_cmp_ps(p.z, splat(hi.z), _CMP_LE_OQ)));
}

// collideParticle for the lanes of `mask` (positions and previous positions in the set's frame);
// returns the lanes that touched anything. `samples` may already hold field samples (taken at
// the lanes' current positions or anywhere else): they are reused where the position matches.
MANE_AVX2 inline __m256 collideParticle(const ColliderSet& set, Vec& position, const Vec& previous, float mu,
                                        __m256 mask, FieldSamples& samples) noexcept {
  const float thickness = set.thickness;
  __m256 touched = _mm256_setzero_ps();
  __m256 going = mask;
  for (int round = 0; round < kCollisionRounds; ++round) {
    __m256 contact = _mm256_setzero_ps();
    for (const SphereCollider& s : set.spheres)
      contact = either(contact, pushOutOfBall(position, previous, splat(s.centre), s.radius + thickness, mu, going));
    for (const CapsuleCollider& c : set.capsules)
      contact = either(contact, pushOutOfBall(position, previous, closestOnSegment(c.a, c.b, position),
                                              c.radius + thickness, mu, going));
    if (const SignedDistanceField* field = samples.field) {
      const __m256 testing = fieldMayBeBelow(*field, thickness, position, going);
      if (any(testing)) {
        samples.sample(position, testing);
        const __m256 level = splat(thickness);
        const __m256 depth = sub(level, samples.value);
        const __m256 g2 = dot(samples.gradient, samples.gradient);
        const __m256 pushed = both(both(testing, _mm256_cmp_ps(samples.value, level, _CMP_LT_OQ)),
                                   _mm256_cmp_ps(g2, splat(1e-12f), _CMP_GT_OQ));
        if (any(pushed)) {
          const __m256 norm = _mm256_sqrt_ps(g2);
          const Vec& g = samples.gradient;
          const Vec normal{div(g.x, norm), div(g.y, norm), div(g.z, norm)};
          const __m256 s = div(sub(splat(thickness + kContactSkin), samples.value), g2);
          position =
              pick(position, {add(position.x, mul(g.x, s)), add(position.y, mul(g.y, s)), add(position.z, mul(g.z, s))},
                   pushed);
          applyFriction(position, previous, normal, depth, mu, pushed);
          samples.sample(position, pushed);
          newtonToLevel(samples, position, thickness, pushed);
          contact = either(contact, pushed);
        }
      }
    }
    going = contact;
    touched = either(touched, contact);
    if (!any(going)) break;
  }
  return touched;
}

MANE_AVX2 inline __m256 collideParticle(const ColliderSet& set, Vec& position, const Vec& previous, float mu,
                                        __m256 mask) noexcept {
  FieldSamples samples{set.sdf.get()};
  return collideParticle(set, position, previous, mu, mask, samples);
}

// Lanes of `mask` where a sphere or capsule of the set holds the position (pushOutOfBall's test).
MANE_AVX2 inline __m256 insideShapes(const ColliderSet& set, const Vec& position, __m256 mask) noexcept {
  __m256 inside = _mm256_setzero_ps();
  for (const SphereCollider& s : set.spheres) {
    const float reach = s.radius + set.thickness;
    const Vec offset = sub(position, splat(s.centre));
    inside = either(inside, _mm256_cmp_ps(dot(offset, offset), splat(reach * reach), _CMP_LT_OQ));
  }
  for (const CapsuleCollider& c : set.capsules) {
    const float reach = c.radius + set.thickness;
    const Vec offset = sub(position, closestOnSegment(c.a, c.b, position));
    inside = either(inside, _mm256_cmp_ps(dot(offset, offset), splat(reach * reach), _CMP_LT_OQ));
  }
  return both(inside, mask);
}

// The lanes of `mask` for which collideParticle's first round can find a contact: a sphere or
// capsule that holds the position (pushOutOfBall's test), or a field sample below the thickness.
// Where no sphere or capsule holds it, none moves it, so the first round samples the field at
// this very position: a lane left out touches nothing and keeps its position. The field samples
// taken (at `position`) are left in `samples`.
MANE_AVX2 inline __m256 mayTouch(const ColliderSet& set, const Vec& position, __m256 mask,
                                 FieldSamples& samples) noexcept {
  __m256 maybe = insideShapes(set, position, mask);
  if (samples.field) {
    const __m256 testing = butNot(fieldMayBeBelow(*samples.field, set.thickness, position, mask), maybe);
    if (any(testing)) {
      samples.sample(position, testing);
      maybe = either(maybe, both(testing, _mm256_cmp_ps(samples.value, splat(set.thickness), _CMP_LT_OQ)));
    }
  }
  return maybe;
}

// Lanes whose 32-bit slot (an int in float bits) is in range: the valid entries of a queue.
MANE_AVX2 inline __m256 firstLanes(int count) noexcept {
  return _mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(count), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
}

// Per 8-bit lane mask m, the lanes of m in ascending order, 4 bits each (lane 0 after them).
inline constexpr auto kCompress = [] {
  std::array<std::uint32_t, 256> table{};
  for (unsigned m = 0; m < 256; ++m) {
    unsigned k = 0;
    for (unsigned lane = 0; lane < 8; ++lane)
      if (m >> lane & 1u) table[m] |= lane << (4 * k++);
  }
  return table;
}();

// A first-in first-out queue of lanes: `C` floats per lane (component 0: the lane's slot in the
// block, an int in float bits). Lanes come in 8 at a time under a mask, packed to the front
// (an AVX2 "compress"), and leave 8 at a time: so work on a few scattered lanes runs on full
// registers.
// The permutation that moves the lanes of mask bits `m` to the front, in order.
MANE_AVX2 inline __m256i compressOrder(unsigned m) noexcept {
  return _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(static_cast<int>(kCompress[m])),
                                            _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28)),
                          _mm256_set1_epi32(7));
}

template <int C>
struct LaneQueue {
  alignas(32) float v[C][2 * kSimdWidth] = {};
  int count = 0;

  MANE_AVX2 void push(const __m256 (&lane)[C], __m256 mask) noexcept {
    const unsigned m = static_cast<unsigned>(_mm256_movemask_ps(mask));
    if (m == 0) return;
    const __m256i order = compressOrder(m);
    for (int c = 0; c < C; ++c) _mm256_storeu_ps(v[c] + count, _mm256_permutevar8x32_ps(lane[c], order));
    count += __builtin_popcount(m);
  }
  [[nodiscard]] MANE_AVX2 __m256 front(int c) const noexcept { return _mm256_load_ps(v[c]); }
  // Drops the 8 front lanes (count ≥ 8).
  MANE_AVX2 void pop() noexcept {
    for (int c = 0; c < C; ++c) _mm256_store_ps(v[c], _mm256_loadu_ps(v[c] + kSimdWidth));
    count -= static_cast<int>(kSimdWidth);
  }
  // The front lanes' slots; lanes past `count` read slot 0.
  [[nodiscard]] MANE_AVX2 __m256i slots() const noexcept {
    return _mm256_and_si256(_mm256_castps_si256(front(0)), _mm256_castps_si256(firstLanes(count)));
  }
};

// The same for a list of any length in the caller's storage: C arrays, each with room for every
// lane pushed plus kSimdWidth.
template <int C>
struct LaneList {
  float* v[C];
  int count = 0;

  MANE_AVX2 void push(const __m256 (&lane)[C], __m256 mask) noexcept {
    const unsigned m = static_cast<unsigned>(_mm256_movemask_ps(mask));
    if (m == 0) return;
    const __m256i order = compressOrder(m);
    for (int c = 0; c < C; ++c) _mm256_storeu_ps(v[c] + count, _mm256_permutevar8x32_ps(lane[c], order));
    count += __builtin_popcount(m);
  }
  [[nodiscard]] MANE_AVX2 __m256 at(int c, int from) const noexcept { return _mm256_loadu_ps(v[c] + from); }
};

// Asks the memory for the field nodes that sampleField reads at the lanes of `mask`.
MANE_AVX2 inline void prefetchField(const SignedDistanceField& field, const Vec& p, __m256 mask) noexcept {
  const glm::vec3 origin = field.origin();
  const __m256 inverse = splat(field.inverseCellSize());
  const glm::ivec3 dims = field.dimensions();
  const auto cell = [&](__m256 coordinate, float lowest, int top) MANE_AVX2 {
    const __m256 u = mul(sub(coordinate, splat(lowest)), inverse);
    return _mm256_min_epi32(_mm256_cvttps_epi32(clampLanes(u, _mm256_setzero_ps(), splat(static_cast<float>(top - 1)))),
                            _mm256_set1_epi32(top - 2));
  };
  const __m256i i = cell(p.x, origin.x, dims.x), j = cell(p.y, origin.y, dims.y), k = cell(p.z, origin.z, dims.z);
  const int sy = dims.x, sz = dims.x * dims.y;
  alignas(32) std::int32_t at[kSimdWidth];
  _mm256_store_si256(reinterpret_cast<__m256i*>(at),
                     _mm256_add_epi32(_mm256_add_epi32(i, _mm256_mullo_epi32(j, _mm256_set1_epi32(sy))),
                                      _mm256_mullo_epi32(k, _mm256_set1_epi32(sz))));
  const float* v = field.values().data();
  for (unsigned m = static_cast<unsigned>(_mm256_movemask_ps(mask)); m != 0; m &= m - 1) {
    const float* node = v + at[__builtin_ctz(m)];  // NaN lanes: an address never read
    for (const int offset : {0, sy, sz, sy + sz}) __builtin_prefetch(node + offset);
  }
}

MANE_AVX2 inline __m256 gatherLanes(const float* values, __m256i slots) noexcept {
  return _mm256_i32gather_ps(values, slots, 4);
}

// Stores the lanes of `mask` of v at values[slot].
MANE_AVX2 inline void scatterLanes(float* x, float* y, float* z, __m256i slots, const Vec& v, __m256 mask) noexcept {
  alignas(32) std::int32_t at[kSimdWidth];
  alignas(32) float vx[kSimdWidth], vy[kSimdWidth], vz[kSimdWidth];
  _mm256_store_si256(reinterpret_cast<__m256i*>(at), slots);
  _mm256_store_ps(vx, v.x), _mm256_store_ps(vy, v.y), _mm256_store_ps(vz, v.z);
  for (unsigned m = static_cast<unsigned>(_mm256_movemask_ps(mask)); m != 0; m &= m - 1) {
    const int b = __builtin_ctz(m);
    x[at[b]] = vx[b], y[at[b]] = vy[b], z[at[b]] = vz[b];
  }
}

// Lanes of `mask` whose body-frame position lies in one of the cull boxes.
MANE_AVX2 inline __m256 inCullBoxes(const ColliderCull& cull, const Vec& local, __m256 mask) noexcept {
  __m256 inBox = _mm256_setzero_ps();
  for (std::size_t box = 0; box < cull.lower.size(); ++box) {
    const glm::vec3 lo = cull.lower[box], hi = cull.upper[box];
    const __m256 above =
        both(both(_mm256_cmp_ps(local.x, splat(lo.x), _CMP_GE_OQ), _mm256_cmp_ps(local.y, splat(lo.y), _CMP_GE_OQ)),
             _mm256_cmp_ps(local.z, splat(lo.z), _CMP_GE_OQ));
    const __m256 below =
        both(both(_mm256_cmp_ps(local.x, splat(hi.x), _CMP_LE_OQ), _mm256_cmp_ps(local.y, splat(hi.y), _CMP_LE_OQ)),
             _mm256_cmp_ps(local.z, splat(hi.z), _CMP_LE_OQ));
    inBox = either(inBox, both(above, below));
  }
  return both(mask, inBox);
}

// The world-space centre of the colliders' bounding ball in `pose`, as HairSystem::collidePoint.
inline glm::vec3 boundsCentre(const LaneColliders& c) noexcept {
  const LanePose& pose = c.pose;
  const glm::vec3 b = c.bounds->centre;
  return pose.axes[0] * b.x + pose.axes[1] * b.y + pose.axes[2] * b.z + pose.translation;
}

}  // namespace lanes

/// HairSystem::collidePoint for 8 particles at once (world space): the lanes of `mask` that touch
/// a collider move; friction against `previous` (in the pose before); returns the lanes that
/// touched anything.
MANE_AVX2 inline __m256 collidePointLanes(const LaneColliders& c, lanes::Vec& world, const lanes::Vec& previous,
                                          __m256 mask, float friction) noexcept {
  using namespace lanes;
  const Vec offset = sub(world, splat(boundsCentre(c)));
  const float radius = c.bounds->radius;
  mask = both(mask, _mm256_cmp_ps(dot(offset, offset), splat(radius * radius), _CMP_NGT_UQ));
  if (!any(mask)) return mask;
  Vec local = toLocal(c.pose, world);
  mask = inCullBoxes(*c.cull, local, mask);
  if (!any(mask)) return mask;
  const Vec previousLocal = friction > 0.0f ? toLocal(c.before, previous) : local;
  const __m256 touched = collideParticle(*c.set, local, previousLocal, friction, mask);
  if (any(touched)) world = pick(world, toWorld(c.pose, local), touched);
  return touched;
}

/// Floats of working storage collideBlockAvx2 needs for a block of `rows` rows.
constexpr std::size_t collideBlockStorage(std::size_t rows) noexcept {
  return 4 * (rows * kBlockLanes + kSimdWidth);
}

/// HairSystem::collidePoint for every simulated particle (within its strand, inverse mass > 0,
/// rows 1 … longest − 1) of `block` (world space): those that touch a collider move. Friction
/// acts against the previous positions; `friction` 0 ignores them. `work`: collideBlockStorage
/// (block.longest) floats.
///
/// One particle's push reads and writes only that particle, so the order does not matter, and
/// the particles are not taken row by row (where on average 4.9 of 8 lanes were still in play
/// after the culls) but packed into full registers in two stages: those that pass the bounding
/// ball and the cull boxes are listed (and their field nodes prefetched), then screened
/// (mayTouch: one field sample), and only those that can make contact (about half) run the
/// whole of collideParticle, starting from the screen's sample. Every lane performs the same
/// operations as the row-by-row version, bit for bit.
MANE_AVX2 inline void collideBlockAvx2(const LaneColliders& c, const StrandLanes& block, float friction,
                                       float* work) noexcept {
  using namespace lanes;
  const glm::vec3 centre = boundsCentre(c);
  const float radius = c.bounds->radius;
  const ColliderSet& set = *c.set;
  const std::size_t room = block.longest * kBlockLanes + kSimdWidth;
  LaneList<4> candidates{{work, work + room, work + 2 * room, work + 3 * room}};  // slot, body-frame position
  for (std::size_t i = 1; i < block.longest; ++i)
    for (std::size_t g = 0; g < block.groups; ++g) {
      const std::size_t at = i * kBlockLanes + g * kSimdWidth;
      __m256 mask =
          both(laneMask(block, g, i), _mm256_cmp_ps(_mm256_loadu_ps(block.w + at), _mm256_setzero_ps(), _CMP_GT_OQ));
      const Vec world{_mm256_loadu_ps(block.x + at), _mm256_loadu_ps(block.y + at), _mm256_loadu_ps(block.z + at)};
      const Vec offset = sub(world, splat(centre));
      mask = both(mask, _mm256_cmp_ps(dot(offset, offset), splat(radius * radius), _CMP_NGT_UQ));
      if (!any(mask)) continue;
      const Vec local = toLocal(c.pose, world);
      mask = inCullBoxes(*c.cull, local, mask);
      if (!any(mask)) continue;
      const __m256 slot = _mm256_castsi256_ps(
          _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(at)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
      candidates.push({slot, local.x, local.y, local.z}, mask);
      if (set.sdf) prefetchField(*set.sdf, local, fieldMayBeBelow(*set.sdf, set.thickness, local, mask));
    }

  LaneQueue<9> contacts;  // slot, body-frame position, field value, gradient, sampled lanes
  const auto resolve = [&]() MANE_AVX2 {
    const __m256 mask = firstLanes(contacts.count);
    const __m256i slots = contacts.slots();
    FieldSamples samples{set.sdf.get()};
    samples.at = {contacts.front(1), contacts.front(2), contacts.front(3)};
    samples.value = contacts.front(4);
    samples.gradient = {contacts.front(5), contacts.front(6), contacts.front(7)};
    samples.held = both(contacts.front(8), mask);
    Vec local = samples.at;
    const Vec previousLocal = friction > 0.0f
                                  ? toLocal(c.before, {gatherLanes(block.px, slots), gatherLanes(block.py, slots),
                                                       gatherLanes(block.pz, slots)})
                                  : local;
    const __m256 touched = collideParticle(set, local, previousLocal, friction, mask, samples);
    if (any(touched)) scatterLanes(block.x, block.y, block.z, slots, toWorld(c.pose, local), touched);
  };
  for (int from = 0; from < candidates.count; from += static_cast<int>(kSimdWidth)) {
    FieldSamples samples{set.sdf.get()};
    const Vec local{candidates.at(1, from), candidates.at(2, from), candidates.at(3, from)};
    const __m256 maybe = mayTouch(set, local, firstLanes(candidates.count - from), samples);
    const __m256 lane[9] = {
        candidates.at(0, from), local.x,     local.y, local.z, samples.value, samples.gradient.x, samples.gradient.y,
        samples.gradient.z,     samples.held};
    contacts.push(lane, maybe);
    if (contacts.count >= static_cast<int>(kSimdWidth)) {
      resolve();
      contacts.pop();
    }
  }
  if (contacts.count > 0) resolve();
}

// Lanes of group g, row i of `block` holding a simulated particle farther than its reach +
// `slack` from its root, as HairSystem::settlePoint tests (x − root, squared length left to
// right, against (reach + slack)²).
MANE_AVX2 inline __m256 beyondTetherLanes(const StrandLanes& block, std::size_t g, std::size_t i,
                                          float slack) noexcept {
  using namespace lanes;
  const std::size_t at = i * kBlockLanes + g * kSimdWidth, root = g * kSimdWidth;
  const Vec d{sub(_mm256_loadu_ps(block.x + at), _mm256_loadu_ps(block.x + root)),
              sub(_mm256_loadu_ps(block.y + at), _mm256_loadu_ps(block.y + root)),
              sub(_mm256_loadu_ps(block.z + at), _mm256_loadu_ps(block.z + root))};
  const __m256 limit = add(_mm256_loadu_ps(block.reach + at), splat(slack));
  const __m256 beyond = _mm256_cmp_ps(dot(d, d), mul(limit, limit), _CMP_GT_OQ);
  const __m256 simulated =
      both(laneMask(block, g, i), _mm256_cmp_ps(_mm256_loadu_ps(block.w + at), _mm256_setzero_ps(), _CMP_GT_OQ));
  return both(beyond, simulated);
}

/// After collideBlockAvx2: the tether repair of HairSystem::settlePoint for every simulated
/// particle of `block` that the push left beyond its reach + `slack` — HairSystem::settleTether's
/// `rounds` alternating projections (onto the tether ball, then frictionless out of the
/// colliders), 8 particles at a time. The rounds read only the particle and its root, so they
/// run in any order; a particle whose rounds do not meet is left at the rounds' last point, and
/// its slot goes to `unmet` (as a float: exact below 2²⁴), ascending, for the bisection, which
/// needs its parent's final position and so runs afterwards, root to tip. Returns how many.
MANE_AVX2 inline std::size_t repairTethersAvx2(const LaneColliders& c, const StrandLanes& block, int rounds,
                                               float slack, float* unmet) noexcept {
  using namespace lanes;
  LaneQueue<1> beyond;  // slot
  std::size_t unmetCount = 0;
  const auto repair = [&]() MANE_AVX2 {
    const __m256i slots = beyond.slots();
    __m256 going = firstLanes(beyond.count);
    const __m256i roots = _mm256_and_si256(slots, _mm256_set1_epi32(static_cast<int>(kBlockLanes - 1)));
    const Vec root{gatherLanes(block.x, roots), gatherLanes(block.y, roots), gatherLanes(block.z, roots)};
    Vec p{gatherLanes(block.x, slots), gatherLanes(block.y, slots), gatherLanes(block.z, slots)};
    const __m256 reach = gatherLanes(block.reach, slots);
    const __m256 limit = mul(add(reach, splat(slack)), add(reach, splat(slack)));
    for (int round = 0; round < rounds; ++round) {
      // projectTether(p, root, reach), operation for operation.
      const Vec delta = sub(p, root);
      const __m256 lengthSquared = dot(delta, delta);
      const __m256 stretched = both(going, _mm256_cmp_ps(lengthSquared, mul(reach, reach), _CMP_GT_OQ));
      if (any(stretched)) {
        const __m256 ratio = div(reach, _mm256_sqrt_ps(lengthSquared));
        p = pick(p,
                 {add(root.x, mul(delta.x, ratio)), add(root.y, mul(delta.y, ratio)), add(root.z, mul(delta.z, ratio))},
                 stretched);
      }
      const __m256 touched = collidePointLanes(c, p, p, going, 0.0f);
      const Vec d = sub(p, root);
      const __m256 done = butNot(going, both(touched, _mm256_cmp_ps(dot(d, d), limit, _CMP_GT_OQ)));
      scatterLanes(block.x, block.y, block.z, slots, p, done);
      going = butNot(going, done);
      if (!any(going)) return;
    }
    scatterLanes(block.x, block.y, block.z, slots, p, going);
    alignas(32) std::int32_t at[kSimdWidth];
    _mm256_store_si256(reinterpret_cast<__m256i*>(at), slots);
    for (unsigned m = static_cast<unsigned>(_mm256_movemask_ps(going)); m != 0; m &= m - 1)
      unmet[unmetCount++] = static_cast<float>(at[__builtin_ctz(m)]);
  };
  for (std::size_t i = 1; i < block.longest; ++i)
    for (std::size_t g = 0; g < block.groups; ++g) {
      const __m256 mask = beyondTetherLanes(block, g, i, slack);
      if (!any(mask)) continue;
      const std::size_t at = i * kBlockLanes + g * kSimdWidth;
      const __m256 slot = _mm256_castsi256_ps(
          _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(at)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
      beyond.push({slot}, mask);
      if (beyond.count >= static_cast<int>(kSimdWidth)) {
        repair();
        beyond.pop();
      }
    }
  if (beyond.count > 0) repair();
  return unmetCount;
}

#undef MANE_AVX2

}  // namespace mane::physics::detail

#endif  // MANE_STRAND_LANES_AVX2
