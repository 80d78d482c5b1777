#pragma once
// Internal: the hair step's particle collisions for 8 particles at once (one AVX2 register per
// coordinate), on the lane layout of strand_lanes.hpp. Not part of the public API.
//
// Bit-exactness: `collidePointLanes` and `collideBlockAvx2` perform, per lane, the IEEE
// operations of the scalar HairSystem::collidePoint → collideParticle →
// SignedDistanceField::sampleWithGradient chain (colliders.cpp, sdf.hpp, field_lanes.hpp), in the
// same order, so a lane ends with the bits the scalar code gives that particle: the same cull
// tests, the same rounds, pushes, Newton steps and friction (tether_lanes.hpp does the same for
// HairSystem::settleTether). Branches become lane masks; a lane leaves a loop where the scalar
// code would break out of it, and its values are then left untouched. Which lanes share a
// register (the row's, or particles packed from anywhere in the block) changes nothing in any
// lane. The scalar code's cache of the last field sample only saves work (it returns what
// sampling again returns); the lanes keep one too (FieldSamples), which may also be handed a
// sample taken earlier at the same position. Culls (the bounding ball, the cull boxes, the
// field's contact box and cells) skip only lanes whose result they prove, never change one.
// tests/physics/hair_test.cpp checks the AVX2 step against the scalar step bit for bit, with
// spheres, capsules, the field, friction and draped, taut strands.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>

#include <glm/vec3.hpp>

#include "physics/colliders.hpp"
#include "physics/detail/field_lanes.hpp"
#include "physics/detail/lane_math.hpp"
#include "physics/detail/strand_lanes.hpp"

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

// HairSystem's toHeadLocal: Rᵀ(x − t), each row a left-to-right dot product.
MANE_AVX2 inline Vec toLocal(const LanePose& pose, const Vec& world) noexcept {
  const Vec d = sub(world, splat(pose.translation));
  return {dot(splat(pose.axes[0]), d), dot(splat(pose.axes[1]), d), dot(splat(pose.axes[2]), d)};
}

// A pose's rows and translation spread over the lanes, for loops that transform many registers.
struct PoseLanes {
  Vec row[3];
  Vec translation;
  MANE_AVX2 explicit PoseLanes(const LanePose& pose) noexcept
      : row{splat(pose.axes[0]), splat(pose.axes[1]), splat(pose.axes[2])}, translation(splat(pose.translation)) {}
};
MANE_AVX2 inline Vec toLocal(const PoseLanes& pose, const Vec& world) noexcept {
  const Vec d = sub(world, pose.translation);
  return {dot(pose.row[0], d), dot(pose.row[1], d), dot(pose.row[2], d)};
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
    if (samples.field.field) {
      const __m256 testing = fieldMayBeBelow(samples.field, position, going);
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

MANE_AVX2 inline __m256 collideParticle(const ColliderSet& set, const FieldLanes& field, Vec& position,
                                        const Vec& previous, float mu, __m256 mask) noexcept {
  FieldSamples samples{field};
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
// taken (at `position`) are left in `samples`. `nearField`: the lanes that fieldMayTouch keeps.
MANE_AVX2 inline __m256 mayTouch(const ColliderSet& set, const Vec& position, __m256 mask, __m256 nearField,
                                 FieldSamples& samples) noexcept {
  __m256 maybe = insideShapes(set, position, mask);
  if (samples.field.field) {
    const __m256 testing = butNot(both(nearField, mask), maybe);
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

  // Without a branch (whether a row has lanes to list is hard to predict): an empty mask
  // stores past the end and counts nothing.
  MANE_AVX2 void push(const __m256 (&lane)[C], __m256 mask) noexcept {
    const unsigned m = static_cast<unsigned>(_mm256_movemask_ps(mask));
    const __m256i order = compressOrder(m);
    for (int c = 0; c < C; ++c) _mm256_storeu_ps(v[c] + count, _mm256_permutevar8x32_ps(lane[c], order));
    count += __builtin_popcount(m);
  }
  [[nodiscard]] MANE_AVX2 __m256 at(int c, int from) const noexcept { return _mm256_loadu_ps(v[c] + from); }
};

// values[slot] for the 8 lanes' slots, read lane by lane (AVX2 gathers are microcoded and slow
// on many AMD cores).
MANE_AVX2 inline __m256 gatherLanes(const float* values, __m256i slots) noexcept {
  alignas(32) std::int32_t at[kSimdWidth];
  _mm256_store_si256(reinterpret_cast<__m256i*>(at), slots);
  return _mm256_setr_ps(values[at[0]], values[at[1]], values[at[2]], values[at[3]], values[at[4]], values[at[5]],
                        values[at[6]], values[at[7]]);
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

// Lanes of `mask` whose body-frame position lies in one of the cull boxes [first, last).
MANE_AVX2 inline __m256 inCullBoxes(const ColliderCull& cull, std::size_t first, std::size_t last, const Vec& local,
                                    __m256 mask) noexcept {
  __m256 inBox = _mm256_setzero_ps();
  for (std::size_t box = first; box < last; ++box) {
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
MANE_AVX2 inline __m256 inCullBoxes(const ColliderCull& cull, const Vec& local, __m256 mask) noexcept {
  return inCullBoxes(cull, 0, cull.lower.size(), local, mask);
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
MANE_AVX2 inline __m256 collidePointLanes(const LaneColliders& c, const lanes::FieldLanes& field, lanes::Vec& world,
                                          const lanes::Vec& previous, __m256 mask, float friction) noexcept {
  using namespace lanes;
  const Vec offset = sub(world, splat(boundsCentre(c)));
  const float radius = c.bounds->radius;
  mask = both(mask, _mm256_cmp_ps(dot(offset, offset), splat(radius * radius), _CMP_NGT_UQ));
  if (!any(mask)) return mask;
  Vec local = toLocal(c.pose, world);
  mask = inCullBoxes(*c.cull, local, mask);
  if (!any(mask)) return mask;
  const Vec previousLocal = friction > 0.0f ? toLocal(c.before, previous) : local;
  const __m256 touched = collideParticle(*c.set, field, local, previousLocal, friction, mask);
  if (any(touched)) world = pick(world, toWorld(c.pose, local), touched);
  return touched;
}

/// Floats of working storage collideBlockAvx2 needs for a block of `rows` rows.
constexpr std::size_t collideBlockStorage(std::size_t rows) noexcept {
  return 5 * (rows * kBlockLanes + kSimdWidth);
}

/// HairSystem::collidePoint for every simulated particle (within its strand, inverse mass > 0,
/// rows 1 … longest − 1) of `block` (world space): those that touch a collider move. Friction
/// acts against the previous positions; `friction` 0 ignores them. `work`: collideBlockStorage
/// (block.longest) floats.
///
/// One particle's push reads and writes only that particle, so the order does not matter, and
/// the particles are not taken row by row (where on average 4.9 of 8 lanes were still in play
/// after the culls) but packed into full registers in two stages: those that pass the bounding
/// ball and the cull boxes (the field's refined by its contact cells) are listed, then screened
/// (mayTouch: one field sample), and only those that can make contact run the whole of
/// collideParticle, starting from the screen's sample. Every lane performs the same operations
/// as the row-by-row version, bit for bit.
MANE_AVX2 inline void collideBlockAvx2(const LaneColliders& c, const StrandLanes& block, float friction,
                                       float* work) noexcept {
  using namespace lanes;
  const glm::vec3 centre = boundsCentre(c);
  const float radius = c.bounds->radius;
  const ColliderSet& set = *c.set;
  const FieldLanes field(set.sdf.get(), set.thickness);
  const PoseLanes pose(c.pose);
  const Vec ballCentre = splat(centre);
  const __m256 ballReach = splat(radius * radius);
  // The spheres' and capsules' cull boxes, spread over the lanes (a few; more take the loop).
  constexpr std::size_t kSpreadBoxes = 4;
  Vec lower[kSpreadBoxes], upper[kSpreadBoxes];
  const std::size_t shapeBoxes = c.cull->shapeBoxes, spread = shapeBoxes <= kSpreadBoxes ? shapeBoxes : 0;
  for (std::size_t b = 0; b < spread; ++b) lower[b] = splat(c.cull->lower[b]), upper[b] = splat(c.cull->upper[b]);
  const auto inShapeBoxes = [&](const Vec& local, __m256 mask) MANE_AVX2 {
    if (spread != shapeBoxes) return inCullBoxes(*c.cull, 0, shapeBoxes, local, mask);
    __m256 inBox = _mm256_setzero_ps();
    for (std::size_t b = 0; b < spread; ++b)
      inBox = either(
          inBox,
          both(
              both(
                  both(_mm256_cmp_ps(local.x, lower[b].x, _CMP_GE_OQ), _mm256_cmp_ps(local.y, lower[b].y, _CMP_GE_OQ)),
                  both(_mm256_cmp_ps(local.z, lower[b].z, _CMP_GE_OQ), _mm256_cmp_ps(local.x, upper[b].x, _CMP_LE_OQ))),
              both(_mm256_cmp_ps(local.y, upper[b].y, _CMP_LE_OQ), _mm256_cmp_ps(local.z, upper[b].z, _CMP_LE_OQ))));
    return both(mask, inBox);
  };
  const std::size_t room = block.longest * kBlockLanes + kSimdWidth;
  // slot, body-frame position, near the field (fieldMayTouch)
  LaneList<5> candidates{{work, work + room, work + 2 * room, work + 3 * room, work + 4 * room}};
  for (std::size_t i = 1; i < block.longest; ++i)
    for (std::size_t g = 0; g < block.groups; ++g) {
      const std::size_t at = i * kBlockLanes + g * kSimdWidth;
      __m256 mask =
          both(laneMask(block, g, i), _mm256_cmp_ps(_mm256_loadu_ps(block.w + at), _mm256_setzero_ps(), _CMP_GT_OQ));
      const Vec world{_mm256_loadu_ps(block.x + at), _mm256_loadu_ps(block.y + at), _mm256_loadu_ps(block.z + at)};
      const Vec offset = sub(world, ballCentre);
      mask = both(mask, _mm256_cmp_ps(dot(offset, offset), ballReach, _CMP_NGT_UQ));
      if (!any(mask)) continue;
      const Vec local = toLocal(pose, world);
      // The cull boxes, the field's refined by its contact cells.
      const __m256 nearField = field.field ? fieldMayTouch(field, local, mask) : _mm256_setzero_ps();
      mask = either(inShapeBoxes(local, mask), nearField);
      const __m256 slot = _mm256_castsi256_ps(
          _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(at)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
      candidates.push({slot, local.x, local.y, local.z, nearField}, mask);
    }

  LaneQueue<9> contacts;  // slot, body-frame position, field value, gradient, sampled lanes
  const auto resolve = [&]() MANE_AVX2 {
    const __m256 mask = firstLanes(contacts.count);
    const __m256i slots = contacts.slots();
    FieldSamples samples{field};
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
  // Two registers of candidates are screened before either is queued: their field samples do
  // not depend on each other, so their latencies overlap.
  constexpr int kScreened = 2;
  for (int from = 0; from < candidates.count; from += kScreened * static_cast<int>(kSimdWidth)) {
    __m256 lane[kScreened][9], maybe[kScreened];
    for (int r = 0; r < kScreened; ++r) {
      const int at = from + r * static_cast<int>(kSimdWidth);
      FieldSamples samples{field};
      const Vec local{candidates.at(1, at), candidates.at(2, at), candidates.at(3, at)};
      maybe[r] = mayTouch(set, local, firstLanes(candidates.count - at), candidates.at(4, at), samples);
      const __m256 screened[9] = {
          candidates.at(0, at), local.x,     local.y, local.z, samples.value, samples.gradient.x, samples.gradient.y,
          samples.gradient.z,   samples.held};
      std::copy(std::begin(screened), std::end(screened), lane[r]);
    }
    for (int r = 0; r < kScreened; ++r) {
      contacts.push(lane[r], maybe[r]);
      if (contacts.count >= static_cast<int>(kSimdWidth)) {
        resolve();
        contacts.pop();
      }
    }
  }
  if (contacts.count > 0) resolve();
}

#undef MANE_AVX2

}  // namespace mane::physics::detail

#endif  // MANE_STRAND_LANES_AVX2
