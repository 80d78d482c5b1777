// mane_physics benchmarks.
//
//   BM_DistanceProjections/<particles>: one Gauss–Seidel sweep of distance constraints along a
//     single long strand (Jakobsen 2001 relaxation); items/s = constraint projections per second.
//   BM_StrandLaneProjections/<particles>/<avx2>: the hair step's distance sweep over a block of
//     32 strands of <particles> each, lane by lane (physics/detail/strand_lanes.hpp), scalar
//     (avx2 = 0) or AVX2 (1, bit-identical); items/s = constraint projections per second, one core.
//   BM_HairFrame/<threads>/<vectorised>/<steps>: one 1/60 s frame of a 10,000-guide ×
//     32-particle groom with 4 constraint iterations per fixed step and tethers, on a head that
//     sways, with the scalar (0) or the AVX2 (1) strand kernel (HairSystem::setVectorised), in
//     <steps> fixed steps (1: one 1/60 s step, 4 iterations per frame, the headline case; 2: two
//     1/120 s steps, 8); items/s = particle updates (particles × fixed steps) per second.
//   BM_HairFrameCollisions/<threads>/<vectorised>/<steps>: the same frame with a neck capsule
//     and the SDF (64³ class) of a 20,480-triangle ellipsoidal head mesh as colliders,
//     friction 0.3.
//   BM_NaluFrame/<collisions>: the Nalu case, 762 guides × 16 particles, one 1/60 s frame on one
//     thread, without (0) or with (1) the capsule + SDF head colliders.
//   BM_SdfBuild: building that SDF (20,480 triangles, about LeePerrySmith's 17,684) at 64³.
//   BM_StateHash: FNV-1a over the same groom's state; bytes/s.

#include <cstdint>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include "physics/colliders.hpp"
#include "physics/constraints.hpp"
#include "physics/detail/strand_lanes.hpp"
#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/sdf.hpp"

namespace {

using namespace mane::physics;

void BM_DistanceProjections(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  Particles particles;
  std::vector<DistanceConstraint> constraints;
  SplitMix64 rng(1);
  for (std::size_t i = 0; i < count; ++i) {
    // A jittered line, so every projection does real work.
    particles.add({0.01f * static_cast<float>(i) + rng.nextFloat(-0.002f, 0.002f), rng.nextFloat(-0.002f, 0.002f),
                   rng.nextFloat(-0.002f, 0.002f)},
                  i == 0 ? 0.0f : 1.0f);
    if (i > 0) constraints.push_back({static_cast<ParticleIndex>(i - 1), static_cast<ParticleIndex>(i), 0.01f});
  }
  for (auto _ : state) {
    solveDistanceConstraints(particles, constraints);
    benchmark::DoNotOptimize(particles.positions.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(constraints.size()));
}
BENCHMARK(BM_DistanceProjections)->Arg(256)->Arg(4096)->Arg(65536);

void BM_StrandLaneProjections(benchmark::State& state) {
  using namespace mane::physics::detail;
  const auto count = static_cast<std::size_t>(state.range(0));
  const bool avx2 = state.range(1) != 0;
  if (avx2 && !cpuHasAvx2()) {
    state.SkipWithError("no AVX2 on this CPU");
    return;
  }
  const std::size_t n = count * kBlockLanes;
  std::vector<float> data(6 * n), w(n), segment(n, 0.01f), reach(n);
  std::vector<std::int32_t> counts(kBlockLanes, static_cast<std::int32_t>(count));
  SplitMix64 rng(1);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t b = 0; b < kBlockLanes; ++b) {
      const std::size_t at = i * kBlockLanes + b;
      // Jittered lines, as BM_DistanceProjections, so every projection does real work.
      data[at] = 0.01f * static_cast<float>(i) + rng.nextFloat(-0.002f, 0.002f);
      data[n + at] = rng.nextFloat(-0.002f, 0.002f) + 0.05f * static_cast<float>(b);
      data[2 * n + at] = rng.nextFloat(-0.002f, 0.002f);
      w[at] = i == 0 ? 0.0f : 1.0f;
      reach[at] = 0.01f * static_cast<float>(i);
    }
  float* p = data.data();
  const StrandLanes lanes{p,        p + n,          p + 2 * n,    p + 3 * n,     p + 4 * n, p + 5 * n,
                          w.data(), segment.data(), reach.data(), counts.data(), count};
  for (auto _ : state) {
#if MANE_STRAND_LANES_AVX2
    if (avx2)
      relaxDistancesAvx2(lanes);
    else
#endif
      relaxDistancesScalar(lanes);
    benchmark::DoNotOptimize(data.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>((count - 1) * kBlockLanes));
}
BENCHMARK(BM_StrandLaneProjections)->Args({32, 0})->Args({32, 1})->Args({4096, 0})->Args({4096, 1});

std::vector<std::vector<glm::vec3>> benchGroom() {
  GroomSettings groom;
  groom.seed = 11;
  groom.strandCount = 10000;
  groom.particlesPerStrand = 32;
  groom.strandLength = 0.4f;
  return *generateGroom(groom);
}

// One 1/60 s frame per iteration with the head swaying sideways by up to 10 cm (so roots move
// and collisions happen); reports particle-steps per second.
void runSwayingFrames(benchmark::State& state, HairSystem& hair, unsigned threads) {
  int frame = 0;
  std::uint64_t particleSteps = 0;
  for (auto _ : state) {
    ++frame;
    const float sway = 0.002f * static_cast<float>(frame % 100 < 50 ? frame % 100 : 100 - frame % 100);
    (void)hair.setHeadTransform(glm::translate(glm::mat4(1.0f), glm::vec3(sway, 0.0f, 0.0f)));
    const auto before = hair.stepCount();
    if (!hair.advance(1.0 / 60.0, threads)) {
      state.SkipWithError("advance failed");
      return;
    }
    particleSteps += (hair.stepCount() - before) * hair.particles().size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(particleSteps));
}

// The frame benchmarks' solver: 4 iterations per fixed step, `steps` fixed steps per 1/60 s.
SolverSettings benchFrameSettings(std::int64_t steps) {
  SolverSettings settings;
  settings.fixedStep = 1.0 / (60.0 * static_cast<double>(steps));
  settings.constraintIterations = 4;
  return settings;
}

ColliderSet benchHeadColliders();

// BM_HairFrame and BM_HairFrameCollisions: the 10k × 32 groom, arguments <threads>/<vectorised>/
// <steps>, with or without the head colliders.
void runHairFrameBench(benchmark::State& state, bool collisions) {
  const auto threads = static_cast<unsigned>(state.range(0));
  const bool vectorised = state.range(1) != 0;
  static const std::vector<std::vector<glm::vec3>> strands = benchGroom();
  auto hair = HairSystem::create(strands, benchFrameSettings(state.range(2)));
  if (!hair) {
    state.SkipWithError(hair.error().message.c_str());
    return;
  }
  if (collisions) (void)hair->setColliders(benchHeadColliders());
  hair->setVectorised(vectorised);
  runSwayingFrames(state, *hair, threads);
  state.counters["particles"] = static_cast<double>(hair->particles().size());
}

// <threads>/<vectorised>/<steps>: the scalar baseline in two steps, AVX2 in one and two.
void hairFrameArgs(benchmark::internal::Benchmark* bench) {
  for (const std::int64_t threads : {1, 2}) bench->Args({threads, 0, 2})->Args({threads, 1, 2})->Args({threads, 1, 1});
}

void BM_HairFrame(benchmark::State& state) {
  runHairFrameBench(state, false);
}
BENCHMARK(BM_HairFrame)->Apply(hairFrameArgs)->Unit(benchmark::kMillisecond)->UseRealTime();

// A head-sized closed mesh: an icosphere (5 subdivisions, 20,480 triangles) scaled into an
// ellipsoid inside the groom's r = 0.1 m scalp.
TriangleMesh benchHeadMesh() {
  TriangleMesh mesh = makeIcosphere(1.0f, 5);
  for (glm::vec3& p : mesh.positions) p *= glm::vec3(0.085f, 0.097f, 0.095f);
  return mesh;
}

void BM_SdfBuild(benchmark::State& state) {
  static const TriangleMesh mesh = benchHeadMesh();
  for (auto _ : state) {
    auto sdf = SignedDistanceField::build(mesh.positions, mesh.indices, {.resolution = 64});
    if (!sdf) {
      state.SkipWithError(sdf.error().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(sdf->values().data());
  }
  state.counters["triangles"] = static_cast<double>(mesh.indices.size() / 3);
}
BENCHMARK(BM_SdfBuild)->Unit(benchmark::kMillisecond)->Iterations(3);

// The collision benches' head: a neck capsule and the head mesh's SDF (built once), μ = 0.3.
ColliderSet benchHeadColliders() {
  static const auto sdf = [] {
    const TriangleMesh mesh = benchHeadMesh();
    return std::make_shared<const SignedDistanceField>(*SignedDistanceField::build(mesh.positions, mesh.indices));
  }();
  ColliderSet head;
  head.capsules = {{{0.0f, -0.06f, -0.01f}, {0.0f, -0.3f, -0.01f}, 0.05f}};
  head.sdf = sdf;
  head.friction = 0.3f;
  return head;
}

void BM_HairFrameCollisions(benchmark::State& state) {
  runHairFrameBench(state, true);
}
BENCHMARK(BM_HairFrameCollisions)->Apply(hairFrameArgs)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_NaluFrame(benchmark::State& state) {
  const bool collisions = state.range(0) != 0;
  static const std::vector<std::vector<glm::vec3>> strands = [] {
    GroomSettings groom;
    groom.seed = 762;
    groom.strandCount = 762;
    groom.particlesPerStrand = 16;
    groom.strandLength = 0.3f;
    return *generateGroom(groom);
  }();
  SolverSettings settings;
  settings.fixedStep = 1.0 / 120.0;
  settings.constraintIterations = 4;
  auto hair = HairSystem::create(strands, settings);
  if (!hair) {
    state.SkipWithError(hair.error().message.c_str());
    return;
  }
  if (collisions) {
    (void)hair->setColliders(benchHeadColliders());
  }
  runSwayingFrames(state, *hair, 1);
  state.counters["particles"] = static_cast<double>(hair->particles().size());
}
BENCHMARK(BM_NaluFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_StateHash(benchmark::State& state) {
  static const std::vector<std::vector<glm::vec3>> strands = benchGroom();
  auto hair = HairSystem::create(strands, SolverSettings{});
  if (!hair) {
    state.SkipWithError(hair.error().message.c_str());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(hair->stateHash());
  state.SetBytesProcessed(state.iterations() *
                          static_cast<std::int64_t>(2 * hair->particles().size() * sizeof(glm::vec3)));
}
BENCHMARK(BM_StateHash)->Unit(benchmark::kMillisecond);

}  // namespace
