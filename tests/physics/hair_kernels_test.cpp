// The hair system's strand kernels: the lane kernels (scalar, AVX2, AVX-512) and the fused
// step against the scalar functions and the general particle solver, bit for bit, with
// collisions, the stretch clamp, tethers and faults.

#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "physics/colliders.hpp"
#include "physics/detail/lane_transfer.hpp"
#include "physics/detail/strand_lanes.hpp"
#include "physics/detail/strand_lanes_avx512.hpp"
#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/sdf.hpp"
#include "tests/support/particle_solver.hpp"

namespace mane::physics {
namespace {

using mane::testing::ParticleSolver;

/// Runs `run(vectorised, threads)`, which returns the state hash and the positions, with the
/// scalar kernel on one thread and the vector kernel on one and two, for a head collider of
/// thickness 0 (field samples culled with the field's contact box) and of 6 mm (above that
/// box's level, half a cell of about 7 mm, where every particle in the grid is sampled); expects
/// the same bits from each.
template <typename Run>
void expectVectorKernelMatchesScalar(ColliderSet& head, const Run& run) {
  for (const float thickness : {0.0f, 0.006f}) {
    head.thickness = thickness;
    const auto scalar = run(false, 1);
    for (unsigned threads : {1u, 2u}) {
      const auto simd = run(true, threads);
      EXPECT_EQ(simd.first, scalar.first) << threads << " threads, thickness " << thickness;
      ASSERT_EQ(simd.second.size(), scalar.second.size());
      EXPECT_EQ(std::memcmp(simd.second.data(), scalar.second.data(), simd.second.size() * sizeof(glm::vec3)), 0);
    }
  }
}

TEST(HairSystem, StrandKernelMatchesTheGeneralSolverBitForBit) {
  // The hair kernel advances several strands side by side for speed. With the head at rest it
  // must do exactly what the general ParticleSolver (tests/support) does to one strand on its
  // own (Verlet, then per sweep distances root → tip and tethers root → tip): equal bits,
  // tolerance 0. Five strands of different lengths, so lanes run out at different particles.
  GroomSettings groom;
  groom.seed = 9;
  groom.strandCount = 5;
  groom.particlesPerStrand = 14;
  groom.curlRadius = 0.01f;
  auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  for (std::size_t s = 0; s < strands->size(); ++s) (*strands)[s].resize(6 + 2 * s);
  SolverSettings settings;
  settings.constraintIterations = 3;
  auto hair = HairSystem::create(*strands, settings);
  ASSERT_TRUE(hair) << hair.error().message;
  for (int frame = 0; frame < 30; ++frame) ASSERT_TRUE(hair->advance(1.0 / 60.0, 1));

  for (std::size_t s = 0; s < strands->size(); ++s) {
    auto solver = ParticleSolver::create(settings);
    ASSERT_TRUE(solver);
    const auto reach = hair->strandRestDistances(s);
    const std::vector<glm::vec3>& points = (*strands)[s];
    for (std::size_t i = 0; i < points.size(); ++i) {
      solver->particles.add(points[i], i == 0 ? 0.0f : 1.0f);
      if (i == 0) continue;
      const glm::vec3 d = points[i] - points[i - 1];
      solver->distances.push_back({static_cast<ParticleIndex>(i - 1), static_cast<ParticleIndex>(i),
                                   std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z)});
      solver->tethers.push_back({static_cast<ParticleIndex>(i), 0, reach[i]});
    }
    for (int frame = 0; frame < 30; ++frame) solver->advance(1.0 / 60.0);
    const auto x = hair->strandPositions(s);
    for (std::size_t i = 0; i < points.size(); ++i)
      ASSERT_EQ(x[i], solver->particles.positions[i]) << "strand " << s << ", particle " << i;
  }
}

TEST(HairSimd, LaneKernelsMatchTheScalarFunctionsBitForBit) {
  // The AVX2 kernels of detail/strand_lanes.hpp against the scalar lane loops (which call
  // projectDistance, projectTether and verletPosition) on random, stretched and compressed
  // blocks with lanes of different lengths, idle lanes and kinematic particles. Tolerance 0.
  if (!detail::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2; the scalar path is used";
#if MANE_STRAND_LANES_AVX2
  constexpr std::size_t W = detail::kBlockLanes, kLongest = 23;
  SplitMix64 random(5);
  std::vector<float> data[2];
  std::vector<float> w(kLongest * W), segment(kLongest * W), reach(kLongest * W);
  std::int32_t count[W];
  for (std::size_t b = 0; b < W; ++b)
    count[b] = b % 7 == 3 ? 0 : static_cast<std::int32_t>(2 + (b * 5) % (kLongest - 1));
  count[9] = kLongest;
  for (std::size_t n = 0; n < kLongest * W; ++n) {
    w[n] = n < W || n % 11 == 0 ? 0.0f : 1.0f;
    segment[n] = random.nextFloat(0.001f, 0.03f);
    reach[n] = static_cast<float>(n / W) * random.nextFloat(0.0f, 0.03f);
  }
  data[0].resize(6 * kLongest * W);
  for (float& v : data[0]) v = random.nextFloat(-0.3f, 0.3f);
  data[1] = data[0];
  const auto lanes = [&](std::vector<float>& d) {
    float* p = d.data();
    const std::size_t n = kLongest * W;
    return detail::StrandLanes{p,        p + n,          p + 2 * n,    p + 3 * n, p + 4 * n, p + 5 * n,
                               w.data(), segment.data(), reach.data(), count,     kLongest};
  };
  const glm::vec3 kick(0.0f, -9.81f / 14400.0f, 1e-5f);
  for (int round = 0; round < 5; ++round) {
    detail::integrateScalar(lanes(data[0]), 0.99f, kick);
    detail::integrateAvx2(lanes(data[1]), 0.99f, kick);
    detail::relaxDistancesScalar(lanes(data[0]));
    detail::relaxDistancesAvx2(lanes(data[1]));
    detail::tethersScalar(lanes(data[0]));
    detail::tethersAvx2(lanes(data[1]));
    ASSERT_EQ(std::memcmp(data[0].data(), data[1].data(), data[0].size() * sizeof(float)), 0) << "round " << round;
  }
#endif
}

TEST(HairSimd, FusedStepMatchesTheSeparateSweepsBitForBit) {
  // detail::stepAvx2 and, where the CPU has AVX-512, detail::stepAvx512 (Verlet and every
  // constraint sweep in one wavefront, with the unmasked paths for plain rows) against
  // integrateScalar followed by the scalar distance and tether sweeps, 1 to 5 iterations,
  // tethers on and off. The block has full-length lanes (plain rows), shorter and idle lanes, a
  // kinematic particle mid-strand, two coincident particles and a root at −0 (the root copy per
  // sweep keeps the sign the first segment leaves it); once with every group of lanes in use and
  // once with an odd number of groups (the last AVX-512 register then spans a group in use and
  // one without strands). Tolerance 0.
  if (!detail::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2; the scalar path is used";
#if MANE_STRAND_LANES_AVX2
  constexpr std::size_t W = detail::kBlockLanes, kLongest = 19;
  SplitMix64 random(11);
  std::vector<float> w(kLongest * W), segment(kLongest * W), reach(kLongest * W);
  for (std::size_t n = 0; n < kLongest * W; ++n) {
    w[n] = n < W ? 0.0f : 1.0f;
    segment[n] = n < W ? 0.0f : random.nextFloat(0.005f, 0.02f);
    reach[n] = static_cast<float>(n / W) * random.nextFloat(0.004f, 0.02f);
  }
  w[7 * W + 20] = 0.0f;  // a kinematic particle mid-strand
  std::vector<float> start(6 * kLongest * W);
  for (float& v : start) v = random.nextFloat(-0.2f, 0.2f);
  const std::size_t n = kLongest * W;
  for (std::size_t c = 0; c < 6; c += 3) start[c * n + 5 * W + 3] = start[c * n + 4 * W + 3];  // coincident
  start[2 * n + 2] = -0.0f;
  const glm::vec3 kick(0.0f, -9.81f / 14400.0f, 2e-5f);
  const bool wide = detail::cpuHasAvx512();
  for (const std::size_t groups : {detail::kSimdGroups, detail::kSimdGroups - 3}) {
    std::int32_t count[W];
    for (std::size_t b = 0; b < W; ++b)
      count[b] = b >= groups * detail::kSimdWidth ? 0
                 : b < 16                         ? kLongest
                                                  : (b % 5 == 0 ? 0 : 2 + static_cast<int>(b % 13));
    for (const bool tethers : {false, true})
      for (int iterations = 1; iterations <= 5; ++iterations) {
        std::vector<float> data[3] = {start, start, start};
        std::vector<float> storage(detail::stepStorage(iterations));
        const auto lanes = [&](std::vector<float>& d) {
          float* p = d.data();
          detail::StrandLanes s{p,        p + n,          p + 2 * n,    p + 3 * n, p + 4 * n, p + 5 * n,
                                w.data(), segment.data(), reach.data(), count,     kLongest, groups};
          detail::markPlainRows(s);
          return s;
        };
        ASSERT_GT(lanes(data[1]).plainRows[0], 2u) << "the block should have plain rows";
        for (int round = 0; round < 4; ++round) {
          detail::integrateScalar(lanes(data[0]), 0.99f, kick);
          for (int k = 0; k < iterations; ++k) {
            detail::relaxDistancesScalar(lanes(data[0]));
            if (tethers) detail::tethersScalar(lanes(data[0]));
          }
          detail::stepAvx2(lanes(data[1]), 0.99f, kick, iterations, tethers, storage.data());
          ASSERT_EQ(std::memcmp(data[0].data(), data[1].data(), data[0].size() * sizeof(float)), 0)
              << "AVX2, " << groups << " groups, tethers " << tethers << ", " << iterations << " iterations, round "
              << round;
          if (!wide) continue;
          detail::stepAvx512(lanes(data[2]), 0.99f, kick, iterations, tethers, storage.data());
          ASSERT_EQ(std::memcmp(data[0].data(), data[2].data(), data[0].size() * sizeof(float)), 0)
              << "AVX-512, " << groups << " groups, tethers " << tethers << ", " << iterations << " iterations, round "
              << round;
        }
      }
  }
#endif
}

TEST(HairSimd, LaneTransferPlacesEveryCoordinateWhereTheLaneLayoutSays) {
  // detail/lane_transfer.hpp against the layout's definition (component c of particle i of lane
  // b at c[i * kBlockLanes + b]): strands of 8 to 27 particles (whole 8 × 8 tiles and tails),
  // lanes without a strand, lane groups left out; then back. Copies only: tolerance 0. On the way
  // back the fault probe is +0 for every lane whose positions are all finite, and NaN for the
  // lanes given an infinite or NaN coordinate (in a tile, in a tail).
  if (!detail::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2; the scalar path is used";
#if MANE_STRAND_LANES_AVX2
  constexpr std::size_t W = detail::kBlockLanes, kRows = 27, kGroups = 3;
  detail::LaneStrands where{};
  std::vector<float> positions, previous;
  SplitMix64 random(9);
  for (std::size_t b = 0; b < W; ++b) {
    // Lanes without a strand only in the third group: the first two move whole tiles too.
    const std::size_t count = b % 5 == 4 && b >= 16 ? 0 : (b == 2 ? kRows : 8 + (b * 7) % (kRows - 8));
    where.first[b] = static_cast<std::uint32_t>(positions.size() / 3);
    where.count[b] = static_cast<std::uint32_t>(count);
    for (std::size_t k = 0; k < 3 * count; ++k) {
      positions.push_back(random.nextFloat(-1.0f, 1.0f));
      previous.push_back(random.nextFloat(-1.0f, 1.0f));
    }
  }
  const std::size_t n = kRows * W;
  std::vector<float> lanes(6 * n, 7.0f);
  detail::loadLanePositions(where, kRows, kGroups, positions.data(), previous.data(), lanes.data());
  for (std::size_t b = 0; b < kGroups * detail::kSimdWidth; ++b)
    for (std::size_t i = 0; i < kRows; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const bool inside = i < where.count[b];
        const std::size_t from = 3 * (where.first[b] + i) + c, at = i * W + b;
        ASSERT_EQ(lanes[c * n + at], inside ? positions[from] : 0.0f) << "lane " << b << ", particle " << i;
        ASSERT_EQ(lanes[(3 + c) * n + at], inside ? previous[from] : 0.0f) << "lane " << b << ", particle " << i;
      }
  for (std::size_t b = kGroups * detail::kSimdWidth; b < W; ++b)
    for (std::size_t i = 0; i < kRows; ++i)
      for (std::size_t c = 0; c < 6; ++c) ASSERT_EQ(lanes[c * n + i * W + b], 7.0f) << "lane " << b << " was written";
  std::vector<float> positionsBack(positions.size(), 0.0f), previousBack(previous.size(), 0.0f);
  float probe[W];
  detail::storeLanePositions(where, kRows, kGroups, lanes.data(), positionsBack.data(), previousBack.data(), probe);
  for (std::size_t b = 0; b < kGroups * detail::kSimdWidth; ++b)
    EXPECT_TRUE(probe[b] == 0.0f && !std::signbit(probe[b])) << "lane " << b;
  // Back where they came from, for the lanes of the groups that were loaded; nothing else written.
  std::vector<float> positionsExpected(positions.size(), 0.0f), previousExpected(previous.size(), 0.0f);
  for (std::size_t b = 0; b < kGroups * detail::kSimdWidth; ++b)
    for (std::size_t k = 3 * where.first[b]; k < 3 * (where.first[b] + where.count[b]); ++k)
      positionsExpected[k] = positions[k], previousExpected[k] = previous[k];
  EXPECT_EQ(positionsBack, positionsExpected);
  EXPECT_EQ(previousBack, previousExpected);

  // Lane 2 (27 particles) gets +∞ in a tile (particle 3, y), lane 10 a NaN in its tail (its
  // last particle, z), lane 11 a NaN in a previous position only, which the probe does not read.
  ASSERT_GE(where.count[10], 9u);
  lanes[n + 3 * W + 2] = std::numeric_limits<float>::infinity();
  lanes[2 * n + (where.count[10] - 1) * W + 10] = std::numeric_limits<float>::quiet_NaN();
  lanes[3 * n + 11] = std::numeric_limits<float>::quiet_NaN();
  detail::storeLanePositions(where, kRows, kGroups, lanes.data(), positionsBack.data(), previousBack.data(), probe);
  for (std::size_t b = 0; b < kGroups * detail::kSimdWidth; ++b)
    EXPECT_EQ(std::isnan(probe[b]), b == 2 || b == 10) << "lane " << b;
#endif
}

TEST(HairSimd, VectorKernelMatchesTheScalarKernelBitForBitWithCollisionsAndClamp) {
  // The whole step, AVX2 path against the per-strand scalar path (setVectorised(false)): a
  // groom of 77 strands (one full block of 64 and a partial one) of different lengths, a moving
  // head with sphere, capsule and SDF colliders, friction and the velocity clamp; 1 and 2
  // threads; two thicknesses. Equal hashes and equal position bytes (tolerance 0).
  if (!detail::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2; the scalar path is used";
  GroomSettings groom;
  groom.seed = 31;
  groom.strandCount = 77;
  groom.particlesPerStrand = 18;
  groom.strandLength = 0.3f;
  groom.curlRadius = 0.005f;
  auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  for (std::size_t s = 0; s < strands->size(); ++s) (*strands)[s].resize(6 + s % 13);
  TriangleMesh mesh = makeIcosphere(0.09f, 3);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices, {.resolution = 32});
  ASSERT_TRUE(sdf);
  ColliderSet head;
  head.spheres = {{{0.0f, 0.0f, 0.0f}, 0.085f}};
  head.capsules = {{{0.0f, -0.06f, 0.0f}, {0.0f, -0.3f, 0.0f}, 0.05f}};
  head.sdf = std::make_shared<const SignedDistanceField>(std::move(*sdf));
  head.friction = 0.3f;
  const auto run = [&](bool vectorised, unsigned threads) {
    SolverSettings settings;
    settings.maxSpeed = 3.0f;
    auto hair = HairSystem::create(*strands, settings);
    EXPECT_TRUE(hair);
    EXPECT_TRUE(hair->setColliders(head));
    hair->setVectorised(vectorised);
    EXPECT_EQ(hair->vectorised(), vectorised);
    for (int frame = 1; frame <= 90; ++frame) {
      const float t = static_cast<float>(frame) / 60.0f;
      const float swing = t - 2.0f * static_cast<float>(static_cast<int>(t * 0.5f + 0.5f));  // sawtooth, exact
      glm::mat4 transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.15f * swing, 0.0f, 0.0f));
      transform = glm::rotate(transform, 1.5f * swing, glm::vec3(0.0f, 1.0f, 0.0f));
      EXPECT_TRUE(hair->setHeadTransform(transform));
      EXPECT_TRUE(hair->advance(1.0 / 60.0, threads));
    }
    return std::make_pair(hair->stateHash(), hair->particles().positions);
  };
  expectVectorKernelMatchesScalar(head, run);
}

TEST(HairSimd, VectorKernelMatchesTheScalarKernelBitForBitOnAGroomDrapedOverTheHead) {
  // The collision pass's packed lanes (detail/collision_lanes.hpp: pushes gathered from the
  // whole block, tether repairs 8 at a time, the bisection afterwards root to tip) against the
  // scalar path on the benchmark's situation in small: 100 strands of up to 32 particles (a full
  // block and a partial one, strands of different lengths) falling onto an ellipsoidal head
  // SDF and a neck capsule, friction 0.3, taut tethers, a swaying head; about 900 of the tether
  // repairs end in the bisection. 1 and 2 threads, two thicknesses. Tolerance 0.
  if (!detail::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2; the scalar path is used";
  GroomSettings groom;
  groom.seed = 11;
  groom.strandCount = 100;
  groom.particlesPerStrand = 32;
  groom.strandLength = 0.4f;
  auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  for (std::size_t s = 0; s < strands->size(); s += 7) (*strands)[s].resize(12 + s % 19);
  TriangleMesh mesh = makeIcosphere(1.0f, 3);
  for (glm::vec3& p : mesh.positions) p *= glm::vec3(0.085f, 0.097f, 0.095f);
  auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices, {.resolution = 32});
  ASSERT_TRUE(sdf);
  ColliderSet head;
  head.capsules = {{{0.0f, -0.06f, -0.01f}, {0.0f, -0.3f, -0.01f}, 0.05f}};
  head.sdf = std::make_shared<const SignedDistanceField>(std::move(*sdf));
  head.friction = 0.3f;
  const auto run = [&](bool vectorised, unsigned threads) {
    SolverSettings settings;
    settings.fixedStep = 1.0 / 60.0;
    auto hair = HairSystem::create(*strands, settings);
    EXPECT_TRUE(hair);
    EXPECT_TRUE(hair->setColliders(head));
    hair->setVectorised(vectorised);
    EXPECT_EQ(hair->vectorised(), vectorised);
    for (int frame = 1; frame <= 60; ++frame) {
      const float sway = 0.002f * static_cast<float>(frame % 100 < 50 ? frame % 100 : 100 - frame % 100);
      EXPECT_TRUE(hair->setHeadTransform(glm::translate(glm::mat4(1.0f), glm::vec3(sway, 0.0f, 0.0f))));
      EXPECT_TRUE(hair->advance(1.0 / 60.0, threads));
    }
    return std::make_pair(hair->stateHash(), hair->particles().positions);
  };
  expectVectorKernelMatchesScalar(head, run);
}

TEST(HairSimd, VectorKernelMatchesTheScalarKernelBitForBitOnSingleStepFrames) {
  // Frames of one fixed step, where the AVX2 path writes the new positions into the previous
  // positions' array and the two trade places: 70 strands (a full block and a partial one) of
  // different lengths under a head that turns and moves (the roots' motion computed lane by
  // lane), tethers on and off, 1 and 2 threads; then a setParticleState (the lanes are read in
  // again), roots on per-root targets, and last a head transform so large that the groom's
  // coordinates overflow: both paths must report the same fault (strand, particle, step), which
  // the vector path finds while writing the positions back. Equal state hashes (positions and
  // previous positions) after every phase; tolerance 0.
  if (!detail::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2; the scalar path is used";
  GroomSettings groom;
  groom.seed = 5;
  groom.strandCount = 70;
  groom.particlesPerStrand = 20;
  groom.strandLength = 0.25f;
  auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  for (std::size_t s = 0; s < strands->size(); ++s) (*strands)[s].resize(5 + s % 16);
  const auto run = [&](bool vectorised, unsigned threads, bool tethers) {
    SolverSettings settings;
    settings.fixedStep = 1.0 / 60.0;
    settings.tethers = tethers;
    auto hair = HairSystem::create(*strands, settings);
    EXPECT_TRUE(hair);
    hair->setVectorised(vectorised);
    std::vector<std::uint64_t> hashes;
    const auto headAt = [](int frame) {
      const float t = static_cast<float>(frame) / 60.0f;
      return glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.1f * t, 0.02f * t, 0.0f)), 0.8f * t,
                         glm::vec3(0.3f, 1.0f, 0.1f));
    };
    for (int frame = 1; frame <= 40; ++frame) {
      EXPECT_TRUE(hair->setHeadTransform(headAt(frame)));
      EXPECT_TRUE(hair->advance(1.0 / 60.0, threads));
    }
    hashes.push_back(hair->stateHash());
    std::vector<glm::vec3> positions = hair->particles().positions, previous = hair->particles().previousPositions;
    for (glm::vec3& p : previous) p += glm::vec3(0.001f, 0.0f, -0.0005f);
    EXPECT_TRUE(hair->setParticleState(positions, previous));
    std::vector<glm::vec3> targets(hair->strandCount()), normals(hair->strandCount(), glm::vec3(0.0f, 1.0f, 0.0f));
    for (int frame = 41; frame <= 60; ++frame) {
      for (std::size_t s = 0; s < targets.size(); ++s)
        targets[s] = glm::vec3(headAt(frame) * glm::vec4(hair->strands()[s].rootLocal, 1.0f)) +
                     glm::vec3(0.0f, 0.001f * static_cast<float>(s % 3), 0.0f);
      EXPECT_TRUE(hair->setRootTargets(targets, normals));
      EXPECT_TRUE(hair->advance(1.0 / 60.0, threads));
    }
    hashes.push_back(hair->stateHash());
    EXPECT_TRUE(hair->teleport(headAt(60)));
    EXPECT_TRUE(hair->setHeadTransform(glm::scale(headAt(60), glm::vec3(1e21f))));
    EXPECT_FALSE(hair->advance(1.0 / 60.0, threads));
    hashes.push_back(hair->stateHash());
    EXPECT_TRUE(hair->fault().has_value());
    const SimulationFault fault = hair->fault().value_or(SimulationFault{});
    return std::make_tuple(hashes, fault.strand, fault.particle, fault.step);
  };
  for (const bool tethers : {false, true}) {
    const auto scalar = run(false, 1, tethers);
    EXPECT_EQ(std::get<3>(scalar), 61u) << "the fault comes in the last frame's only step";
    for (unsigned threads : {1u, 2u})
      EXPECT_EQ(run(true, threads, tethers), scalar) << threads << " threads, tethers " << tethers;
  }
}

}  // namespace
}  // namespace mane::physics
