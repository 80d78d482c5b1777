// Colliders (physics/colliders.hpp): analytic sphere and capsule distances, projection to the
// surface, Coulomb friction against its analytic laws, the culls and the AVX2 field lanes
// against the scalar field, a violent head shake in which no hair particle may end a step
// inside a sphere, a capsule or a mesh SDF, and strands draped over a head that keep every
// segment.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/colliders.hpp"
#include "physics/detail/field_lanes.hpp"
#include "physics/detail/tether_lanes.hpp"
#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/sdf.hpp"
#include "physics/solver.hpp"
#include "tests/support/particle_solver.hpp"

namespace mane::physics {
namespace {

using mane::testing::ParticleSolver;

using ::testing::HasSubstr;

float norm(const glm::vec3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

TEST(Colliders, SphereAndCapsuleDistancesAreAnalytic) {
  // Exact values (3-4-5 triangles); tolerance: float rounding of a few operations.
  const SphereCollider sphere{{1.0f, 0.0f, 0.0f}, 1.0f};
  EXPECT_NEAR(signedDistance(sphere, {4.0f, 4.0f, 0.0f}), 4.0f, 1e-6f);
  EXPECT_NEAR(signedDistance(sphere, {1.0f, 0.5f, 0.0f}), -0.5f, 1e-6f);
  EXPECT_NEAR(signedDistance(sphere, {1.0f, 0.0f, 0.0f}), -1.0f, 1e-6f);

  const CapsuleCollider capsule{{0.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}, 0.5f};
  EXPECT_NEAR(signedDistance(capsule, {3.0f, 1.0f, 4.0f}), 4.5f, 1e-6f);      // beside the axis: 5 − r
  EXPECT_NEAR(signedDistance(capsule, {0.0f, 5.0f, 4.0f}), 4.5f, 1e-6f);      // beyond end b: |(0,3,4)| − r
  EXPECT_NEAR(signedDistance(capsule, {3.0f, -4.0f, 0.0f}), 4.5f, 1e-6f);     // beyond end a
  EXPECT_NEAR(signedDistance(capsule, {0.0f, 1.0f, 0.1f}), -0.4f, 1e-6f);     // inside
  const CapsuleCollider point{{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, 1.0f};  // a = b: a sphere
  EXPECT_NEAR(signedDistance(point, {1.0f, 4.0f, 5.0f}), 4.0f, 1e-6f);

  ColliderSet set;
  set.spheres = {sphere};
  set.capsules = {capsule};
  EXPECT_NEAR(signedDistance(set, {0.2f, 1.0f, 0.0f}), -0.3f, 1e-6f);  // the smaller of −0.3 and 0.28
  EXPECT_EQ(signedDistance(ColliderSet{}, {0.0f, 0.0f, 0.0f}), std::numeric_limits<float>::infinity());
}

TEST(Colliders, ProjectionMovesToTheSurfaceAlongTheNormal) {
  // Frictionless: a particle inside ends on the surface (distance 0 within rounding), moved
  // only along the outward normal; one outside is left alone bit for bit.
  ColliderSet set;
  set.spheres = {{{0.0f, 0.0f, 0.0f}, 1.0f}};
  set.capsules = {{{3.0f, 0.0f, 0.0f}, {3.0f, 2.0f, 0.0f}, 0.5f}};
  glm::vec3 p(0.3f, 0.4f, 0.0f);
  EXPECT_TRUE(collideParticle(set, p, p));
  EXPECT_NEAR(p.x, 0.6f, 1e-6f);
  EXPECT_NEAR(p.y, 0.8f, 1e-6f);
  glm::vec3 q(3.1f, 1.0f, 0.0f);
  EXPECT_TRUE(collideParticle(set, q, q));
  EXPECT_NEAR(q.x, 3.5f, 1e-6f);
  EXPECT_NEAR(q.y, 1.0f, 1e-6f);
  glm::vec3 r(5.0f, 5.0f, 5.0f);
  const glm::vec3 before = r;
  EXPECT_FALSE(collideParticle(set, r, r));
  EXPECT_EQ(r, before);
  // With a thickness the particle stops that far outside.
  set.thickness = 0.01f;
  glm::vec3 s(0.0f, 0.5f, 0.0f);
  collideParticle(set, s, s);
  EXPECT_NEAR(s.y, 1.01f, 1e-6f);
}

TEST(Colliders, OverlappingCollidersBothEndUnpenetrated) {
  // A point inside the overlap of two balls must leave both: the set is run through again while
  // it still finds contacts.
  ColliderSet set;
  set.spheres = {{{0.0f, 0.0f, 0.0f}, 1.0f}, {{1.2f, 0.0f, 0.0f}, 1.0f}};
  glm::vec3 p(0.6f, 0.1f, 0.0f);
  collideParticle(set, p, p);
  EXPECT_GE(signedDistance(set, p), -1e-5f);
}

// Arc length travelled from the top of a sphere of radius R centred at (0, −R, 0), metres.
double arcFromTop(const glm::vec3& p, double radius) {
  return radius * std::atan2(static_cast<double>(p.x), static_cast<double>(p.y) + radius);
}

TEST(Colliders, SlidingFrictionDeceleratesAsCoulombsLaw) {
  // A particle slides from the top of a large sphere (R = 50 m, nearly a plane) at 2 m/s with
  // μ = 0.3. Reference: the arc-length equation of Coulomb sliding on a sphere,
  //   s'' = g·sin(s/R) − μ·(g·cos(s/R) − s'²/R)  while s' > 0,
  // integrated with RK4 at 1e-5 s (on a plane: s'' = −μg, stopping after v0²/(2μg) = 0.680 m).
  // Tolerance: 2 % of the stopping distance, the O(h) lag of position-based friction (Macklin
  // et al. 2014, §6.1) at h = 1/120 s; then static friction holds it (μ > tan of the slope).
  constexpr double kRadius = 50.0, kMu = 0.3, kG = 9.81, kV0 = 2.0;
  SolverSettings settings;
  settings.damping = 0.0f;
  settings.constraintIterations = 1;
  auto solver = ParticleSolver::create(settings);
  ASSERT_TRUE(solver);
  solver->colliders.spheres = {{{0.0f, static_cast<float>(-kRadius), 0.0f}, static_cast<float>(kRadius)}};
  solver->colliders.friction = static_cast<float>(kMu);
  const float h = static_cast<float>(settings.fixedStep);
  solver->particles.add({0.0f, 0.0f, 0.0f}, 1.0f);
  solver->particles.previousPositions[0] = {static_cast<float>(-kV0) * h, 0.0f, 0.0f};

  double s = 0.0, v = kV0, t = 0.0;
  const auto accel = [&](double arc, double speed) {
    return kG * std::sin(arc / kRadius) - kMu * (kG * std::cos(arc / kRadius) - speed * speed / kRadius);
  };
  const double stopDistance = kV0 * kV0 / (2.0 * kMu * kG);
  double worst = 0.0;
  for (int stepIndex = 1; stepIndex <= 120; ++stepIndex) {
    solver->step();
    const double target = stepIndex * settings.fixedStep;
    while (v > 0.0 && t < target) {  // RK4 up to the end of this step
      const double dt = std::min(1e-5, target - t);
      const double k1s = v, k1v = accel(s, v);
      const double k2s = v + 0.5 * dt * k1v, k2v = accel(s + 0.5 * dt * k1s, k2s);
      const double k3s = v + 0.5 * dt * k2v, k3v = accel(s + 0.5 * dt * k2s, k3s);
      const double k4s = v + dt * k3v, k4v = accel(s + dt * k3s, k4s);
      s += dt / 6.0 * (k1s + 2 * k2s + 2 * k3s + k4s);
      v += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
      t += dt;
    }
    const double simulated = arcFromTop(solver->particles.positions[0], kRadius);
    worst = std::max(worst, std::abs(simulated - s));
    ASSERT_NEAR(simulated, s, 0.02 * stopDistance) << "t = " << stepIndex * settings.fixedStep << " s";
    // Never deeper than rounding below the surface.
    EXPECT_GE(signedDistance(solver->colliders, solver->particles.positions[0]), -1e-5f);
  }
  std::printf("friction: stopped at %.4f m (RK4 reference %.4f m, plane %.4f m), max |Δs| = %.4f m\n",
              arcFromTop(solver->particles.positions[0], kRadius), s, stopDistance, worst);
  const glm::vec3 rest = solver->particles.positions[0];
  for (int k = 0; k < 60; ++k) solver->step();
  EXPECT_LT(norm(solver->particles.positions[0] - rest), 1e-4f);

  // Control: without friction the same start slides on, past 2 m after 1 s.
  auto frictionless = ParticleSolver::create(settings);
  ASSERT_TRUE(frictionless);
  frictionless->colliders = solver->colliders;
  frictionless->colliders.friction = 0.0f;
  frictionless->particles.add({0.0f, 0.0f, 0.0f}, 1.0f);
  frictionless->particles.previousPositions[0] = {static_cast<float>(-kV0) * h, 0.0f, 0.0f};
  for (int k = 0; k < 120; ++k) frictionless->step();
  EXPECT_GT(arcFromTop(frictionless->particles.positions[0], kRadius), 2.0);
}

TEST(Colliders, StaticFrictionHoldsInsideTheCoulombCone) {
  // A particle at rest on a unit sphere, 20° from the top. Coulomb: it stays when μ ≥ tan 20°
  // (0.364) and slides when μ < tan 20°. Position-based friction removes a tangential step
  // g·sinθ·h² when μ·g·cosθ·h² is at least as long, the same condition.
  const auto drift = [](float mu) {
    SolverSettings settings;
    settings.constraintIterations = 1;
    auto solver = ParticleSolver::create(settings);
    EXPECT_TRUE(solver);
    solver->colliders.spheres = {{{0.0f, 0.0f, 0.0f}, 1.0f}};
    solver->colliders.friction = mu;
    const float angle = 20.0f * 3.14159265f / 180.0f;
    const glm::vec3 start(std::sin(angle), std::cos(angle), 0.0f);
    solver->particles.add(start, 1.0f);
    for (int k = 0; k < 120; ++k) solver->step();
    return norm(solver->particles.positions[0] - start);
  };
  EXPECT_LT(drift(0.5f), 1e-4f);
  EXPECT_LT(drift(0.38f), 1e-3f);
  EXPECT_GT(drift(0.3f), 0.01f);
  EXPECT_GT(drift(0.0f), 0.1f);
}

TEST(Colliders, BadCollidersAreRejectedByName) {
  ColliderSet set;
  set.spheres = {{{0.0f, 0.0f, 0.0f}, 1.0f}, {{0.0f, 0.0f, 0.0f}, -1.0f}};
  auto valid = validateColliders(set);
  ASSERT_FALSE(valid);
  EXPECT_THAT(valid.error().message, HasSubstr("sphere 1"));
  set.spheres.pop_back();
  set.capsules = {{{0.0f, std::nanf(""), 0.0f}, {0.0f, 0.0f, 0.0f}, 1.0f}};
  EXPECT_THAT(validateColliders(set).error().message, HasSubstr("capsule 0"));
  set.capsules.clear();
  set.friction = -0.1f;
  EXPECT_THAT(validateColliders(set).error().message, HasSubstr("friction"));

  GroomSettings groom;
  groom.strandCount = 2;
  auto hair = HairSystem::create(*generateGroom(groom), SolverSettings{});
  ASSERT_TRUE(hair);
  auto refused = hair->setColliders(set);
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("friction"));
  EXPECT_TRUE(hair->colliders().empty());
}

TEST(Colliders, CullBoxesNeverSkipAContact) {
  // The culls (ColliderCull::mayTouch, SignedDistanceField::mayBeBelow) may only skip points
  // that collideParticle leaves alone and whose SDF sample is ≥ the level. 200,000 random points
  // around a sphere, a capsule and an ellipsoid SDF, thickness 1 mm (below half a cell, 1.7 mm).
  TriangleMesh mesh = makeIcosphere(1.0f, 3);
  for (glm::vec3& p : mesh.positions) p *= glm::vec3(0.085f, 0.097f, 0.095f);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices);
  ASSERT_TRUE(sdf);
  ASSERT_GT(sdf->contactLevel(), 0.0f);  // this field has a contact box
  ColliderSet set;
  set.spheres = {{{0.05f, 0.1f, 0.0f}, 0.03f}};
  set.capsules = {{{0.0f, -0.06f, -0.01f}, {0.0f, -0.3f, -0.01f}, 0.05f}};
  set.sdf = std::make_shared<const SignedDistanceField>(std::move(*sdf));
  set.thickness = 0.001f;
  const ColliderCull cull = cullBoxes(set);
  SplitMix64 random(3);
  int skipped = 0;
  for (int n = 0; n < 200000; ++n) {
    const glm::vec3 p(random.nextFloat(-0.25f, 0.25f), random.nextFloat(-0.4f, 0.25f), random.nextFloat(-0.25f, 0.25f));
    if (!set.sdf->mayBeBelow(p, set.thickness)) {
      ASSERT_GE(set.sdf->sample(p), set.thickness);
    }
    if (cull.mayTouch(p)) continue;
    ++skipped;
    glm::vec3 q = p;
    ASSERT_FALSE(collideParticle(set, q, q)) << p.x << ", " << p.y << ", " << p.z;
  }
  EXPECT_GT(skipped, 50000);  // the cull does skip most of empty space
}

#if MANE_STRAND_LANES_AVX2
// What the collision lanes (detail/field_lanes.hpp, detail/tether_lanes.hpp) make of 8 points:
// the field's sample and gradient, its cull (fieldMayTouch) and outsideColliders at `level`.
struct FieldLaneResults {
  float value[8], gradient[3][8];
  int nearField, outside;
};
__attribute__((target("avx2"))) FieldLaneResults fieldLanes(const ColliderSet& set, const float (&p)[3][8],
                                                            float level) {
  using namespace detail::lanes;
  const FieldLanes field(set.sdf.get(), set.thickness);
  const Vec at{_mm256_loadu_ps(p[0]), _mm256_loadu_ps(p[1]), _mm256_loadu_ps(p[2])};
  const __m256 all = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
  __m256 value = _mm256_setzero_ps();
  Vec gradient{value, value, value};
  sampleField(field, at, all, value, gradient);
  FieldLaneResults r;
  _mm256_storeu_ps(r.value, value);
  _mm256_storeu_ps(r.gradient[0], gradient.x), _mm256_storeu_ps(r.gradient[1], gradient.y);
  _mm256_storeu_ps(r.gradient[2], gradient.z);
  r.nearField = _mm256_movemask_ps(fieldMayTouch(field, at, all));
  r.outside = _mm256_movemask_ps(detail::outsideColliders(set, field, at, _mm256_set1_ps(level), all));
  return r;
}
#endif

TEST(Colliders, FieldLanesMatchTheScalarFieldBitForBit) {
  // The AVX2 collision pass's field samples and culls against the scalar functions they mirror,
  // lane by lane: 40,000 points in and around the grid of an ellipsoidal head SDF (a quarter
  // outside the grid, one NaN lane in every 16th batch of 8) with a neck capsule, thickness
  // 1 mm. Sample and gradient bytes equal sampleWithGradient's; the cull equals mayBeBelow;
  // outsideColliders equals signedDistance(set, p) ≥ level for the bisection's level and for 0.
  // Tolerance 0.
  if (!detail::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2; the scalar path is used";
#if MANE_STRAND_LANES_AVX2
  TriangleMesh mesh = makeIcosphere(1.0f, 3);
  for (glm::vec3& p : mesh.positions) p *= glm::vec3(0.085f, 0.097f, 0.095f);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices, {.resolution = 40});
  ASSERT_TRUE(sdf);
  ColliderSet set;
  set.capsules = {{{0.0f, -0.06f, -0.01f}, {0.0f, -0.3f, -0.01f}, 0.05f}};
  set.sdf = std::make_shared<const SignedDistanceField>(std::move(*sdf));
  set.thickness = 0.001f;
  ASSERT_LT(set.thickness, set.sdf->contactLevel());
  SplitMix64 random(17);
  for (int batch = 0; batch < 5000; ++batch) {
    float p[3][8];
    for (int lane = 0; lane < 8; ++lane)
      for (int axis = 0; axis < 3; ++axis) p[axis][lane] = random.nextFloat(-0.14f, 0.14f);
    if (batch % 16 == 0) p[1][7] = std::numeric_limits<float>::quiet_NaN();
    for (const float level : {set.thickness - 1e-5f, 0.0f}) {
      const FieldLaneResults lanes = fieldLanes(set, p, level);
      for (int lane = 0; lane < 8; ++lane) {
        const glm::vec3 q(p[0][lane], p[1][lane], p[2][lane]);
        glm::vec3 gradient(0.0f);
        const float value = set.sdf->sampleWithGradient(q, gradient);
        ASSERT_EQ(std::memcmp(&lanes.value[lane], &value, sizeof value), 0) << q.x << ", " << q.y << ", " << q.z;
        if (!std::isnan(value)) {
          for (int axis = 0; axis < 3; ++axis) {
            ASSERT_EQ(std::memcmp(&lanes.gradient[axis][lane], &gradient[axis], sizeof(float)), 0) << axis;
          }
        }
        ASSERT_EQ((lanes.nearField >> lane & 1) != 0, set.sdf->mayBeBelow(q, set.thickness))
            << q.x << ", " << q.y << ", " << q.z;
        ASSERT_EQ((lanes.outside >> lane & 1) != 0, signedDistance(set, q) >= level)
            << q.x << ", " << q.y << ", " << q.z;
      }
    }
  }
#endif
}

// The head used by the shake tests and the benchmark: a cranium ball, a neck capsule and the
// SDF of an ellipsoidal head mesh, all inside the r = 0.1 m scalp the groom grows from.
ColliderSet shakeHead() {
  TriangleMesh mesh = makeIcosphere(1.0f, 4);
  for (glm::vec3& p : mesh.positions) p *= glm::vec3(0.085f, 0.097f, 0.095f);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices);
  EXPECT_TRUE(sdf);
  ColliderSet set;
  set.spheres = {{{0.0f, 0.0f, 0.0f}, 0.09f}};
  set.capsules = {{{0.0f, -0.06f, -0.01f}, {0.0f, -0.3f, -0.01f}, 0.05f}};
  set.sdf = std::make_shared<const SignedDistanceField>(std::move(*sdf));
  set.friction = 0.2f;
  return set;
}

glm::mat4 shakenHead(double t) {
  constexpr double kTwoPi = 6.283185307179586;
  glm::mat4 head =
      glm::translate(glm::mat4(1.0f), glm::vec3(static_cast<float>(0.08 * std::sin(kTwoPi * 3.0 * t)),
                                                static_cast<float>(0.05 * std::sin(kTwoPi * 4.0 * t)), 0.0f));
  head = glm::rotate(head, static_cast<float>(1.2 * std::sin(kTwoPi * 2.5 * t)), glm::vec3(0.0f, 1.0f, 0.0f));
  return glm::rotate(head, static_cast<float>(0.4 * std::sin(kTwoPi * 1.7 * t)), glm::vec3(1.0f, 0.0f, 0.0f));
}

TEST(Colliders, NoHairParticleEndsAStepInsideTheHeadOrBeyondItsTetherDuringAViolentShake) {
  // 3 s of head shaking (yaw ±1.2 rad at 2.5 Hz — up to 19 rad/s —, nod ±0.4 rad, 8 cm and 5 cm
  // sideways and vertical swings), one fixed step per frame so every step is checked. After
  // every step, both: (1) no particle inside a collider — reference: each collider's own
  // distance in head-local space (inverse head transform); (2) the anti-stretch guarantee — no
  // particle farther from its root than its rest length along the strand. Tolerance 1e-4 m for
  // both: the final pass settles within HairSystem::kSettleSlack (1e-5 m), the SDF is reached by
  // Newton steps on a trilinear field, and the head pose inside the step is rebuilt from a
  // quaternion (float rounding ≈ 1e-7 m at this scale).
  GroomSettings groom;
  groom.seed = 17;
  groom.strandCount = 300;
  groom.particlesPerStrand = 16;
  groom.strandLength = 0.3f;
  groom.capMinNormalY = -0.3f;
  auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  SolverSettings settings;
  settings.constraintIterations = 4;
  auto hair = HairSystem::create(*strands, settings, shakenHead(0.0));
  ASSERT_TRUE(hair);
  const ColliderSet head = shakeHead();
  ASSERT_TRUE(hair->setColliders(head));

  float deepest = 0.0f, worstStretch = 0.0f;
  int touching = 0;
  for (int k = 1; k <= 360; ++k) {
    const glm::mat4 transform = shakenHead(k * settings.fixedStep);
    ASSERT_TRUE(hair->setHeadTransform(transform));
    ASSERT_TRUE(hair->advance(settings.fixedStep, 2));
    const glm::mat4 toLocal = glm::inverse(transform);
    for (std::size_t s = 0; s < hair->strandCount(); ++s) {
      const auto x = hair->strandPositions(s);
      const auto reach = hair->strandRestDistances(s);
      for (std::size_t i = 1; i < x.size(); ++i) {
        const glm::vec3 local(toLocal * glm::vec4(x[i], 1.0f));
        const float d = std::min(
            {signedDistance(head.spheres[0], local), signedDistance(head.capsules[0], local), head.sdf->sample(local)});
        deepest = std::min(deepest, d);
        if (d < 1e-3f) ++touching;
        ASSERT_GE(d, -1e-4f) << "step " << k << ", strand " << s << ", particle " << i;
        const float stretch = norm(x[i] - x[0]) - reach[i];
        worstStretch = std::max(worstStretch, stretch);
        ASSERT_LE(stretch, 1e-4f) << "beyond the tether: step " << k << ", strand " << s << ", particle " << i;
      }
    }
  }
  std::printf(
      "head shake: deepest %.3g m, %d particle-steps within 1 mm of the head, "
      "farthest beyond the tether %.3g m\n",
      static_cast<double>(deepest), touching, static_cast<double>(worstStretch));
  EXPECT_GT(touching, 1000);  // the test exercises contact, not empty space
}

TEST(Colliders, StrandsDrapedOverTheHeadKeepEverySegment) {
  // Roots sit on the scalp, inside the collision thickness. When a particle's collision and
  // tether settling do not meet, the fallback must not land it on its parent: a particle on the
  // root (or on the particle before) makes a zero-length segment and stretches the next one to
  // twice its length, a fold drawn as a zigzag across the crown. 400 strands of 16 particles
  // combed back over a ball head with a 2 mm thickness, the AVX2 and scalar kernels, 2 s of
  // gravity: every segment keeps at least half its rest length (bound: the distance sweeps leave
  // stretched strands a few per cent off), and the two kernels agree bit for bit.
  GroomSettings groom;
  groom.seed = 5;
  groom.strandCount = 400;
  groom.particlesPerStrand = 16;
  groom.strandLength = 0.3f;
  groom.scalpRadius = 0.1f;
  groom.capMinNormalY = 0.1f;
  groom.comb = {0.0f, 0.0f, -3.0f};
  auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  ColliderSet head;
  head.spheres = {{{0.0f, 0.0f, 0.0f}, 0.1f}};
  head.thickness = 0.002f;
  head.friction = 0.2f;
  const auto run = [&](bool vectorised) {
    auto hair = HairSystem::create(*strands, SolverSettings{});
    EXPECT_TRUE(hair);
    EXPECT_TRUE(hair->setColliders(head));
    hair->setVectorised(vectorised);
    for (int frame = 0; frame < 120; ++frame) EXPECT_TRUE(hair->advance(1.0 / 60.0, 2));
    return std::move(*hair);
  };
  const HairSystem simd = run(true);
  float shortest = 1.0f;
  std::size_t shortStrand = 0;
  for (std::size_t s = 0; s < simd.strandCount(); ++s) {
    const auto x = simd.strandPositions(s);
    const auto reach = simd.strandRestDistances(s);
    for (std::size_t i = 1; i < x.size(); ++i) {
      const float ratio = norm(x[i] - x[i - 1]) / (reach[i] - reach[i - 1]);
      if (ratio < shortest) shortest = ratio, shortStrand = s;
    }
  }
  std::printf("draped strands: shortest segment %.3g of its rest length (strand %zu)\n",
              static_cast<double>(shortest), shortStrand);
  EXPECT_GE(shortest, 0.5f) << "strand " << shortStrand;
  EXPECT_EQ(run(false).stateHash(), simd.stateHash());
}

}  // namespace
}  // namespace mane::physics
