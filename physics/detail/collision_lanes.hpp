#pragma once
// Internal: the hair step's particle collisions for 8 particles at once (one AVX2 register per
// coordinate), on the lane layout of strand_lanes.hpp. Not part of the public API.
//
// Bit-exactness: `collideLanesAvx2` performs, per lane, the IEEE operations of the scalar
// HairSystem::collidePoint → collideParticle → SignedDistanceField::sampleWithGradient chain
// (colliders.cpp, sdf.hpp), in the same order, so a lane ends with the bits the scalar code gives
// that particle: the same cull tests, the same rounds, pushes, Newton steps and friction. Branches
// become lane masks; a lane leaves a loop where the scalar code would break out of it, and its
// values are then left untouched. The scalar code's cache of the last field sample only saves
// work (it returns what sampling again returns); the lanes keep one too (FieldSamples). Field
// samples gather their 8 node values per lane; lanes that do not sample read node 0 and discard
// it, so no gather leaves the grid. tests/physics/hair_test.cpp checks the AVX2 step against
// the scalar step bit for bit, with spheres, capsules, the field and friction.

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

MANE_AVX2 inline __m256 gatherNode(const float* values, __m256i at, int offset) noexcept {
  return _mm256_i32gather_ps(values, _mm256_add_epi32(at, _mm256_set1_epi32(offset)), 4);
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
  const __m256 v000 = gatherNode(v, at, 0), v100 = gatherNode(v, at, 1), v010 = gatherNode(v, at, sy),
               v110 = gatherNode(v, at, 1 + sy);
  const __m256 v001 = gatherNode(v, at, sz), v101 = gatherNode(v, at, 1 + sz), v011 = gatherNode(v, at, sy + sz),
               v111 = gatherNode(v, at, 1 + sy + sz);
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

// collideParticle for the lanes of `mask` (positions and previous positions in the set's frame);
// returns the lanes that touched anything.
MANE_AVX2 inline __m256 collideParticle(const ColliderSet& set, Vec& position, const Vec& previous, float mu,
                                        __m256 mask) noexcept {
  const float thickness = set.thickness;
  __m256 touched = _mm256_setzero_ps();
  __m256 going = mask;
  FieldSamples samples{set.sdf.get()};
  for (int round = 0; round < kCollisionRounds; ++round) {
    __m256 contact = _mm256_setzero_ps();
    for (const SphereCollider& s : set.spheres)
      contact = either(contact, pushOutOfBall(position, previous, splat(s.centre), s.radius + thickness, mu, going));
    for (const CapsuleCollider& c : set.capsules)
      contact = either(contact, pushOutOfBall(position, previous, closestOnSegment(c.a, c.b, position),
                                              c.radius + thickness, mu, going));
    if (const SignedDistanceField* field = samples.field) {
      __m256 testing = going;
      if (thickness < field->contactLevel() - 1e-6f) {  // SignedDistanceField::mayBeBelow
        const glm::vec3 lo = field->contactLower(), hi = field->contactUpper();
        testing = both(testing, both(both(_mm256_cmp_ps(position.x, splat(lo.x), _CMP_GE_OQ),
                                          _mm256_cmp_ps(position.y, splat(lo.y), _CMP_GE_OQ)),
                                     _mm256_cmp_ps(position.z, splat(lo.z), _CMP_GE_OQ)));
        testing = both(testing, both(both(_mm256_cmp_ps(position.x, splat(hi.x), _CMP_LE_OQ),
                                          _mm256_cmp_ps(position.y, splat(hi.y), _CMP_LE_OQ)),
                                     _mm256_cmp_ps(position.z, splat(hi.z), _CMP_LE_OQ)));
      }
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

}  // namespace lanes

/// HairSystem::collidePoint for the particles i of lane group g of `block` (world space) that
/// are simulated (within their strand, inverse mass > 0): those that touch a collider move.
/// Friction acts against the previous positions; `friction` 0 ignores them.
MANE_AVX2 inline void collideLanesAvx2(const LaneColliders& c, const StrandLanes& block, std::size_t g, std::size_t i,
                                       float friction) noexcept {
  const std::size_t at = i * kBlockLanes + g * kSimdWidth;
  float *x = block.x + at, *y = block.y + at, *z = block.z + at;
  const float *px = block.px + at, *py = block.py + at, *pz = block.pz + at;
  __m256 mask = _mm256_and_ps(laneMask(block, g, i),
                              _mm256_cmp_ps(_mm256_loadu_ps(block.w + at), _mm256_setzero_ps(), _CMP_GT_OQ));
  using namespace lanes;
  const LanePose& pose = c.pose;
  const glm::vec3 b = c.bounds->centre;
  const glm::vec3 centre = pose.axes[0] * b.x + pose.axes[1] * b.y + pose.axes[2] * b.z + pose.translation;
  const Vec world{_mm256_loadu_ps(x), _mm256_loadu_ps(y), _mm256_loadu_ps(z)};
  const Vec offset = sub(world, splat(centre));
  const float radius = c.bounds->radius;
  mask = both(mask, _mm256_cmp_ps(dot(offset, offset), splat(radius * radius), _CMP_NGT_UQ));
  if (!any(mask)) return;
  Vec local = toLocal(pose, world);
  __m256 inBox = _mm256_setzero_ps();
  for (std::size_t box = 0; box < c.cull->lower.size(); ++box) {
    const glm::vec3 lo = c.cull->lower[box], hi = c.cull->upper[box];
    const __m256 above =
        both(both(_mm256_cmp_ps(local.x, splat(lo.x), _CMP_GE_OQ), _mm256_cmp_ps(local.y, splat(lo.y), _CMP_GE_OQ)),
             _mm256_cmp_ps(local.z, splat(lo.z), _CMP_GE_OQ));
    const __m256 below =
        both(both(_mm256_cmp_ps(local.x, splat(hi.x), _CMP_LE_OQ), _mm256_cmp_ps(local.y, splat(hi.y), _CMP_LE_OQ)),
             _mm256_cmp_ps(local.z, splat(hi.z), _CMP_LE_OQ));
    inBox = either(inBox, both(above, below));
  }
  mask = both(mask, inBox);
  if (!any(mask)) return;
  const Vec previousLocal =
      friction > 0.0f ? toLocal(c.before, {_mm256_loadu_ps(px), _mm256_loadu_ps(py), _mm256_loadu_ps(pz)}) : local;
  const __m256 touched = collideParticle(*c.set, local, previousLocal, friction, mask);
  if (!any(touched)) return;
  const Vec moved = pick(world, toWorld(pose, local), touched);
  _mm256_storeu_ps(x, moved.x);
  _mm256_storeu_ps(y, moved.y);
  _mm256_storeu_ps(z, moved.z);
}

/// Bit b set for each simulated particle i of lane group g of `block` that lies farther than
/// its reach + `slack` from its root, as HairSystem::settlePoint tests (x − root, squared
/// length left to right, against (reach + slack)²).
MANE_AVX2 inline unsigned beyondTetherAvx2(const StrandLanes& block, std::size_t g, std::size_t i,
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
  return static_cast<unsigned>(_mm256_movemask_ps(both(beyond, simulated)));
}

#undef MANE_AVX2

}  // namespace mane::physics::detail

#endif  // MANE_STRAND_LANES_AVX2
