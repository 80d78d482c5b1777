#pragma once
// Internal: the tether repair of the hair step's collision pass for 8 particles at once, after
// collideBlockAvx2 (collision_lanes.hpp): HairSystem::settleTether's alternating projections
// (repairTethersAvx2) and, for the few they leave, HairSystem::bisectTether
// (bisectTethersAvx2), bit for bit. Not part of the public API.
// tests/physics/hair_test.cpp checks them against the scalar step on a groom draped over a head,
// where hundreds of repairs end in the bisection.

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "physics/colliders.hpp"
#include "physics/constraints.hpp"
#include "physics/detail/collision_lanes.hpp"

#if MANE_STRAND_LANES_AVX2

namespace mane::physics::detail {

#define MANE_AVX2 __attribute__((target("avx2")))

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
  const FieldLanes field(c.set->sdf.get(), c.set->thickness);
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
      const __m256 touched = collidePointLanes(c, field, p, p, going, 0.0f);
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

// The lanes of `mask` where colliders.cpp's signedDistance(set, p) ≥ `level`: where each shape's
// signed distance and the field's sample is ≥ `level` or NaN (std::min passes NaN over). The
// field is sampled only where the shapes leave the question open and its contact cells cannot
// answer it (`level` must lie below the thickness `field` was set up with).
MANE_AVX2 inline __m256 outsideColliders(const ColliderSet& set, const lanes::FieldLanes& field, const lanes::Vec& p,
                                         __m256 level, __m256 mask) noexcept {
  using namespace lanes;
  __m256 clear = mask;
  for (const SphereCollider& s : set.spheres) {
    const Vec offset = sub(p, splat(s.centre));
    clear = both(clear, _mm256_cmp_ps(sub(_mm256_sqrt_ps(dot(offset, offset)), splat(s.radius)), level, _CMP_NLT_UQ));
  }
  for (const CapsuleCollider& c : set.capsules) {
    const Vec offset = sub(p, closestOnSegment(c.a, c.b, p));
    clear = both(clear, _mm256_cmp_ps(sub(_mm256_sqrt_ps(dot(offset, offset)), splat(c.radius)), level, _CMP_NLT_UQ));
  }
  if (!field.field) return clear;
  const __m256 sampling = fieldMayTouch(field, p, clear);
  if (!any(sampling)) return clear;
  __m256 value = _mm256_setzero_ps();
  Vec gradient{value, value, value};
  sampleField(field, p, sampling, value, gradient);
  return butNot(clear, both(sampling, _mm256_cmp_ps(value, level, _CMP_LT_OQ)));
}

/// HairSystem's toHeadLocal for one point: Rᵀ(x − t), each row a left-to-right dot product.
inline glm::vec3 localPoint(const LanePose& pose, const glm::vec3& world) noexcept {
  const glm::vec3 d = world - pose.translation;
  return {pose.axes[0].x * d.x + pose.axes[0].y * d.y + pose.axes[0].z * d.z,
          pose.axes[1].x * d.x + pose.axes[1].y * d.y + pose.axes[1].z * d.z,
          pose.axes[2].x * d.x + pose.axes[2].y * d.y + pose.axes[2].z * d.z};
}

/// After repairTethersAvx2, the rest of HairSystem::settleTether for each of the `count`
/// particles whose slots (ascending, as floats) are in `unmet`, in that order: the particle
/// pulled back onto its tether ball where that lies outside the colliders, else (bisectTether)
/// `halvings` bisection steps on the segment from the parent's final position towards the
/// particle, keeping the farthest point within the tether (reach + `slack`) and at least
/// thickness − `slack` outside every collider (pose `c.pose`).
///
/// The halvings of one particle depend on each other, so the lanes look ahead instead: from an
/// interval [good, bad], the next d halvings can only test the 2^d − 1 points
/// good + (bad − good)·j/2^d, which are tested at once and the path through them followed
/// afterwards. Every such point is a dyadic fraction with at most `halvings` bits, exactly what
/// the scalar halvings compute, so the same points are tested and the same one is kept. Particles
/// of different strands (none the parent of another; consecutive entries of `unmet`) share a
/// register: one looks 3 halvings ahead on 7 lanes, two look 2 ahead on 3 lanes each, up to 8 take
/// one halving at a time.
MANE_AVX2 inline void bisectTethersAvx2(const LaneColliders& c, const StrandLanes& block, int halvings, float slack,
                                        const float* unmet, std::size_t count) noexcept {
  using namespace lanes;
  const ColliderSet& set = *c.set;
  const FieldLanes field(set.sdf.get(), set.thickness);
  const PoseLanes pose(c.pose);
  const __m256 level = splat(set.thickness - slack);
  constexpr int kMost = static_cast<int>(kSimdWidth);
  std::size_t slot[kMost];
  glm::vec3 parent[kMost], towards[kMost];
  float good[kMost], bad[kMost];
  int searching = 0;
  // The particles [first, first + many) on one register, each looking `ahead` halvings ahead.
  const auto search = [&](int first, int many, int ahead) MANE_AVX2 {
    const int width = (1 << ahead) - 1;  // lanes per particle
    alignas(32) float lane[10][kMost];   // per lane: parent, towards, root, limit
    alignas(32) float from[kMost], span[kMost], fraction[kMost];
    int owner[kMost];
    for (int l = 0; l < kMost; ++l) {
      owner[l] = l / width < many ? first + l / width : first;
      const std::size_t n = slot[owner[l]], r = n % kBlockLanes;
      const float reach = block.reach[n];
      const float values[10] = {parent[owner[l]].x,  parent[owner[l]].y,
                                parent[owner[l]].z,  towards[owner[l]].x,
                                towards[owner[l]].y, towards[owner[l]].z,
                                block.x[r],          block.y[r],
                                block.z[r],          (reach + slack) * (reach + slack)};
      for (int v = 0; v < 10; ++v) lane[v][l] = values[v];
    }
    const auto load = [&](int v) MANE_AVX2 { return _mm256_load_ps(lane[v]); };
    const Vec start{load(0), load(1), load(2)}, direction{load(3), load(4), load(5)}, root{load(6), load(7), load(8)};
    const __m256 limit = load(9);
    for (int done = 0; done < halvings;) {
      const int depth = std::min(ahead, halvings - done);
      // Lane l of particle j tests good + (bad − good)·(l − j·width + 1)/2^depth.
      for (int l = 0; l < kMost; ++l) {
        from[l] = good[owner[l]], span[l] = bad[owner[l]] - good[owner[l]];
        fraction[l] = static_cast<float>(l % width + 1) / static_cast<float>(1 << depth);
      }
      const __m256 t = add(_mm256_load_ps(from), mul(_mm256_load_ps(span), _mm256_load_ps(fraction)));
      const Vec q{add(start.x, mul(direction.x, t)), add(start.y, mul(direction.y, t)),
                  add(start.z, mul(direction.z, t))};
      const Vec fromRoot = sub(q, root);
      const __m256 tethered = _mm256_cmp_ps(dot(fromRoot, fromRoot), limit, _CMP_NGT_UQ);
      const unsigned clear =
          static_cast<unsigned>(_mm256_movemask_ps(outsideColliders(set, field, toLocal(pose, q), level, tethered)));
      alignas(32) float points[kMost];
      _mm256_store_ps(points, t);
      for (int j = 0; j < many; ++j) {
        const int base = j * width;
        int low = 0, high = 1 << depth;  // the interval in units of (bad − good) / 2^depth
        for (int halving = 0; halving < depth; ++halving) {
          const int middle = (low + high) / 2;
          (clear >> (base + middle - 1) & 1u ? low : high) = middle;
        }
        const int p = first + j;
        const float nextGood = low == 0 ? good[p] : points[base + low - 1];
        bad[p] = high == 1 << depth ? bad[p] : points[base + high - 1];
        good[p] = nextGood;
      }
      done += depth;
    }
  };
  const auto settle = [&]() MANE_AVX2 {
    if (searching == 1)
      search(0, 1, 3);
    else if (searching == 2)
      search(0, 2, 2);
    else if (searching == 3)
      search(0, 2, 2), search(2, 1, 3);
    else
      search(0, searching, 1);
    for (int g = 0; g < searching; ++g) {
      const glm::vec3 settled = parent[g] + towards[g] * good[g];
      block.x[slot[g]] = settled.x, block.y[slot[g]] = settled.y, block.z[slot[g]] = settled.z;
    }
    searching = 0;
  };
  for (std::size_t u = 0; u < count; ++u) {
    const auto n = static_cast<std::size_t>(unmet[u]);
    {  // the particle pulled back onto its tether ball, where that lies outside the colliders
      const std::size_t r = n % kBlockLanes;
      const glm::vec3 root(block.x[r], block.y[r], block.z[r]);
      const float limit = (block.reach[n] + slack) * (block.reach[n] + slack);
      glm::vec3 tethered(block.x[n], block.y[n], block.z[n]);
      projectTether(tethered, root, block.reach[n]);
      const glm::vec3 fromRoot = tethered - root;
      if (!(fromRoot.x * fromRoot.x + fromRoot.y * fromRoot.y + fromRoot.z * fromRoot.z > limit) &&
          signedDistance(set, localPoint(c.pose, tethered)) >= 0.0f) {
        block.x[n] = tethered.x, block.y[n] = tethered.y, block.z[n] = tethered.z;
        continue;
      }
    }
    bool parentSearching = false;
    for (int g = 0; g < searching; ++g) parentSearching = parentSearching || slot[g] + kBlockLanes == n;
    if (parentSearching || searching == kMost) settle();
    const std::size_t up = n - kBlockLanes;
    slot[searching] = n;
    parent[searching] = glm::vec3(block.x[up], block.y[up], block.z[up]);
    towards[searching] = glm::vec3(block.x[n], block.y[n], block.z[n]) - parent[searching];
    good[searching] = 0.0f, bad[searching] = 1.0f;
    ++searching;
  }
  if (searching > 0) settle();
}

#undef MANE_AVX2

}  // namespace mane::physics::detail

#endif  // MANE_STRAND_LANES_AVX2
