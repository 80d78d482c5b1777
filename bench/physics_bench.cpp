// mane_physics benchmarks.
//
//   BM_DistanceProjections/<particles>: one Gauss–Seidel sweep of distance constraints along a
//     single long strand (Jakobsen 2001 relaxation); items/s = constraint projections per second.
//   BM_StrandLaneProjections/<particles>/<avx2>: the hair step's distance sweep over a block of
//     kBlockLanes strands of <particles> each, lane by lane (physics/detail/strand_lanes.hpp), scalar
//     (avx2 = 0) or AVX2 (1, bit-identical); items/s = constraint projections per second, one core.
//   BM_HairFrame/<threads>/<vectorised>/<steps>: one 1/60 s frame of a 10,000-guide ×
//     32-particle groom with 4 constraint iterations per fixed step and tethers, on a head that
//     sways, with the scalar (0) or the AVX2 (1) strand kernel (HairSystem::setVectorised), in
//     <steps> fixed steps (1: one 1/60 s step, 4 iterations per frame, the headline case; 2: two
//     1/120 s steps, 8); items/s = particle updates (particles × fixed steps) per second.
//   BM_HairFrameTasks/<workers>/<host>: the same frame (AVX2, one step) through the task
//     interface: the built-in pool (host = 0) against a host job system written here (1), each
//     with <workers> threads.
//   BM_HairFrameCollisions/<threads>/<vectorised>/<steps>: the same frame with a neck capsule
//     and the SDF (64³ class) of a 20,480-triangle ellipsoidal head mesh as colliders,
//     friction 0.3.
//   BM_NaluFrame/<collisions>: the Nalu case, 762 guides × 16 particles, one 1/60 s frame on one
//     thread, without (0) or with (1) the capsule + SDF head colliders.
//   BM_NaluFrameThreads/<threads>: the same frame without colliders on <threads> workers (wall
//     time): what dispatching the parallel loop costs at this size.
//   BM_SdfBuild: building that SDF (20,480 triangles, about LeePerrySmith's 17,684) at 64³.
//   BM_StateHash: FNV-1a over the same groom's state; bytes/s.
//   BM_CharacterBind: binding 10,000 groom roots to a 50,000-triangle skinned head
//     (SurfaceBinding::create), once per iteration: the load-time cost.
//   BM_CharacterStep/<threads>: the 10,000-guide × 32-particle groom on that head as it nods,
//     with three joint capsules (neck, shoulders) as colliders. Each iteration is one fixed step:
//     the per-step update (SurfaceBinding::evaluate of the 10k roots on the skinned mesh,
//     setHeadTransform, setColliders with the capsules re-expressed in the head's frame,
//     setRootTargets), then HairSystem::advance of one 1/120 s step on <threads>. Counters:
//     update_us and step_us per iteration, update_ratio = update / step (the goal: ≤ 0.1), and
//     the update's parts evaluate_us, colliders_us, targets_us.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include "physics/cloth.hpp"
#include "physics/colliders.hpp"
#include "physics/constraints.hpp"
#include "physics/detail/strand_lanes.hpp"
#include "physics/groom_generator.hpp"
#include "physics/floating_body.hpp"
#include "physics/hair.hpp"
#include "physics/ocean_waves.hpp"
#include "physics/sdf.hpp"
#include "physics/skinning.hpp"
#include "physics/surface_binding.hpp"
#include "physics/thread_pool.hpp"

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

// A host engine's job system as a game might have one: persistent threads that pop single jobs
// from one locked queue; the thread that waits pops jobs too. Nothing of the built-in pool.
class HostJobSystem {
public:
  explicit HostJobSystem(unsigned threads) {
    for (unsigned t = 1; t < threads; ++t) threads_.emplace_back([this] { workLoop(); });
  }
  ~HostJobSystem() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
  }
  mane::physics::TaskRunner runner() {
    mane::physics::TaskRunner runner;
    runner.concurrency = static_cast<std::uint32_t>(threads_.size() + 1);
    runner.enqueue = [this](std::uint32_t count,
                            const mane::physics::TaskFunction& task) -> mane::Result<mane::physics::TaskGroup> {
      auto* left = new std::atomic<std::uint32_t>(count);
      {
        const std::lock_guard lock(mutex_);
        for (std::uint32_t i = 0; i < count; ++i) jobs_.push_back({&task, i, left});
      }
      wake_.notify_all();
      return left;
    };
    runner.wait = [this](mane::physics::TaskGroup group) -> mane::Result<void> {
      const std::unique_ptr<std::atomic<std::uint32_t>> left(static_cast<std::atomic<std::uint32_t>*>(group));
      while (left->load() != 0)
        if (!runOne()) std::this_thread::yield();
      return {};
    };
    return runner;
  }

private:
  struct Job {
    const mane::physics::TaskFunction* task;
    std::uint32_t index;
    std::atomic<std::uint32_t>* left;
  };
  bool runOne() {
    Job job;
    {
      const std::lock_guard lock(mutex_);
      if (jobs_.empty()) return false;
      job = jobs_.front();
      jobs_.pop_front();
    }
    (*job.task)(job.index);
    job.left->fetch_sub(1);
    return true;
  }
  void workLoop() {
    for (;;) {
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
        if (stop_) return;
      }
      while (runOne()) {
      }
    }
  }
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> jobs_;
  bool stop_ = false;
  std::vector<std::jthread> threads_;
};

// BM_HairFrameTasks/<workers>/<host>: the 10k × 32 groom's 1/60 s frame in one fixed step (AVX2
// kernel) through HairSettings::tasks: the built-in pool (host = 0) or the host job system above
// (1), both with <workers> threads.
void BM_HairFrameTasks(benchmark::State& state) {
  const auto workers = static_cast<unsigned>(state.range(0));
  static const std::vector<std::vector<glm::vec3>> strands = benchGroom();
  HostJobSystem host(workers);
  ThreadPool pool(workers);
  HairSettings settings;
  settings.strands = strands;
  settings.solver = benchFrameSettings(1);
  settings.tasks = state.range(1) != 0 ? host.runner() : pool.runner();
  auto hair = HairSystem::create(settings);
  if (!hair) {
    state.SkipWithError(hair.error().message.c_str());
    return;
  }
  int frame = 0;
  std::uint64_t particleSteps = 0;
  for (auto _ : state) {
    ++frame;
    const float sway = 0.002f * static_cast<float>(frame % 100 < 50 ? frame % 100 : 100 - frame % 100);
    (void)hair->setHeadTransform(glm::translate(glm::mat4(1.0f), glm::vec3(sway, 0.0f, 0.0f)));
    const auto before = hair->stepCount();
    if (!hair->advance(1.0 / 60.0)) {
      state.SkipWithError("advance failed");
      return;
    }
    particleSteps += (hair->stepCount() - before) * hair->particles().size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(particleSteps));
}
BENCHMARK(BM_HairFrameTasks)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Args({4, 0})
    ->Args({4, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

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

// Nalu's groom: 762 guides of 16 particles, 0.3 m, stepped at 1/120 s with 4 iterations.
mane::Result<HairSystem> naluHair() {
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
  return HairSystem::create(strands, settings);
}

void BM_NaluFrame(benchmark::State& state) {
  const bool collisions = state.range(0) != 0;
  auto hair = naluHair();
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

// The Nalu groom's frame (no colliders) on <threads> workers: at 762 guides the frame is short
// enough that starting threads for each parallel loop, rather than waking persistent ones, shows.
void BM_NaluFrameThreads(benchmark::State& state) {
  auto hair = naluHair();
  if (!hair) {
    state.SkipWithError(hair.error().message.c_str());
    return;
  }
  runSwayingFrames(state, *hair, static_cast<unsigned>(state.range(0)));
}
BENCHMARK(BM_NaluFrameThreads)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMicrosecond)->UseRealTime();

// A 48 × 48-vertex sheet, 0.4 m square, pinned along its top edge 2 cm above a 0.12 m ball and
// swung about the vertical at 2 rad/s, so it drapes over the ball and folds over itself; self
// collision off (arg 0) or at 3 mm (arg 1). One iteration: 1/30 s, four fixed steps of 1/120 s,
// 8 constraint iterations, one thread.
void BM_ClothFrame(benchmark::State& state) {
  constexpr int kN = 48;
  ClothSettings settings;
  settings.solver.fixedStep = 1.0 / 120.0;
  settings.solver.constraintIterations = 8;
  settings.selfCollisionThickness = state.range(0) == 1 ? 0.003f : 0.0f;
  settings.colliders.spheres.push_back({.centre = {0.0f, -0.14f, 0.0f}, .radius = 0.12f});
  settings.colliders.thickness = 0.003f;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      settings.positions.push_back({0.4f * (float(i) / (kN - 1) - 0.5f), 0.0f, 0.4f * (float(j) / (kN - 1) - 0.5f)});
      if (j == 0) settings.pinnedVertices.push_back(std::uint32_t(i));
    }
  for (int j = 0; j + 1 < kN; ++j)
    for (int i = 0; i + 1 < kN; ++i) {
      const auto a = std::uint32_t(j * kN + i), b = a + 1, c = a + kN, d = c + 1;
      settings.triangles.insert(settings.triangles.end(), {a, c, b, b, c, d});
    }
  settings.tasks = builtInTaskRunner(1);
  auto cloth = Cloth::create(settings);
  if (!cloth) {
    state.SkipWithError(cloth.error().message.c_str());
    return;
  }
  // Half a second untimed: the sheet has fallen onto the ball and started folding.
  int frame = 0;
  const auto advance = [&] {
    ++frame;
    (void)cloth->setBodyTransform(glm::rotate(glm::mat4(1.0f), 2.0f * float(frame) / 30.0f, {0, 1, 0}));
    return cloth->advance(1.0 / 30.0);
  };
  for (int warm = 0; warm < 15; ++warm) (void)advance();
  for (auto _ : state)
    if (auto advanced = advance(); !advanced) {
      state.SkipWithError(advanced.error().message.c_str());
      return;
    }
  state.counters["vertices"] = double(kN * kN);
}
BENCHMARK(BM_ClothFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

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

// ---- The sea: wave queries on the CPU (BM_OceanQueries) and a floating box (BM_FloatingBody). ----

// Queries of clear_sailing.json's sea (45 waves, choppiness 0.9): arg 0 the water resting at a
// point (OceanWaves::sample), arg 1 the water found over a point (surfaceAt, Newton's method),
// at points spread over 200 m; items per second are queries per second.
void BM_OceanQueries(benchmark::State& state) {
  const auto ocean = OceanWaves::create(
      {.windSpeed = 14.0f, .windDirection = {1.0f, 0.4f}, .choppiness = 0.9f, .shortestWavelength = 0.8f});
  if (!ocean) return state.SkipWithError(ocean.error().message.c_str());
  const bool surface = state.range(0) == 1;
  constexpr int kPoints = 1024;
  for (auto _ : state) {
    for (int i = 0; i < kPoints; ++i) {
      const glm::vec2 p(float(i % 32) * 6.3f - 100.0f, float(i / 32) * 6.1f - 100.0f);
      benchmark::DoNotOptimize(surface ? ocean->surfaceAt(p, 10.0) : ocean->sample(p, 10.0));
    }
  }
  state.SetItemsProcessed(state.iterations() * kPoints);
}
BENCHMARK(BM_OceanQueries)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One 1/120 s step of a 30 × 8 × 4 m box of 24 × 8 × 8 cells (192 columns, one surface query
// each) on that sea.
void BM_FloatingBody(benchmark::State& state) {
  const auto ocean = OceanWaves::create({.windSpeed = 14.0f, .choppiness = 0.9f, .shortestWavelength = 0.8f});
  if (!ocean) return state.SkipWithError(ocean.error().message.c_str());
  FloatingBodySettings settings{.mass = 1025.0f * 30.0f * 8.0f * 2.0f, .position = {0.0f, 0.0f, 0.0f}};
  const glm::vec3 size(30.0f, 4.0f, 8.0f);
  const glm::vec3 cell = size / glm::vec3(24.0f, 8.0f, 8.0f);
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 8; ++k)
        settings.hull.push_back({.centre = (glm::vec3(i, j, k) + 0.5f) * cell - 0.5f * size, .size = cell});
  auto body = FloatingBody::create(std::move(settings));
  if (!body) return state.SkipWithError(body.error().message.c_str());
  double time = 0.0;
  for (auto _ : state) {
    if (!body->step(*ocean, time, 1.0f / 120.0f, glm::vec3(0.0f))) return state.SkipWithError("the step failed");
    time += 1.0 / 120.0;
  }
}
BENCHMARK(BM_FloatingBody)->Unit(benchmark::kMicrosecond);

// ---- A character: a skinned head and its groom (BM_CharacterBind, BM_CharacterStep). ----

// A UV sphere of radius 0.1 m (125 stacks × 200 slices: 49,600 triangles, about the 50k of a
// detailed head), skinned to a neck joint (0) and a head joint (1) that blend between y = −0.09 m
// and y = −0.03 m.
mane::physics::SkinnedMeshData benchCharacterHead() {
  constexpr int kStacks = 125, kSlices = 200;
  constexpr float kPi = 3.14159265358979f;
  SkinnedMeshData head;
  head.influencesPerVertex = 2;
  head.jointCount = 2;
  for (int i = 0; i <= kStacks; ++i) {
    const float polar = kPi * static_cast<float>(i) / kStacks;
    for (int j = 0; j < kSlices; ++j) {
      const float azimuth = 2.0f * kPi * static_cast<float>(j) / kSlices;
      const glm::vec3 n(std::sin(polar) * std::cos(azimuth), std::cos(polar), std::sin(polar) * std::sin(azimuth));
      head.positions.push_back(0.1f * n);
      head.normals.push_back(n);
      const float w = std::clamp((0.1f * n.y + 0.09f) / 0.06f, 0.0f, 1.0f);
      head.joints.insert(head.joints.end(), {0u, 1u});
      head.weights.insert(head.weights.end(), {1.0f - w, w});
    }
  }
  for (std::uint32_t i = 0; i < kStacks; ++i)
    for (std::uint32_t j = 0; j < kSlices; ++j) {
      const std::uint32_t a = i * kSlices + j, b = i * kSlices + (j + 1) % kSlices, c = a + kSlices, d = b + kSlices;
      if (i > 0) head.indices.insert(head.indices.end(), {a, b, c});  // none at the poles: zero area
      if (i + 1 < kStacks) head.indices.insert(head.indices.end(), {b, d, c});
    }
  return head;
}

// 10,000 roots spread over the top of the head (y ≥ 0.02 m), on the sphere: a few 1e-5 m off
// its flat facets, as a groom authored on a smoother surface would be.
std::vector<glm::vec3> benchCharacterRoots() {
  std::vector<glm::vec3> roots;
  SplitMix64 rng(31);
  while (roots.size() < 10000) {
    // One draw per statement (the order of a call's arguments is open): z, y, x, the order the
    // recorded figures were measured with.
    const float z = rng.nextFloat(-1.0f, 1.0f);
    const float y = rng.nextFloat(-1.0f, 1.0f);
    const float x = rng.nextFloat(-1.0f, 1.0f);
    const glm::vec3 d(x, y, z);
    const float length = glm::length(d);
    if (length > 1.0f || length < 0.1f || d.y / length < 0.2f) continue;
    roots.push_back(0.1f * d / length);
  }
  return roots;
}

// The head joint's matrix in pose `k` of `kCharacterPoses`: a nod about the neck pivot.
constexpr int kCharacterPoses = 16;
glm::mat4 benchNod(int k) {
  const float angle = 0.05f * static_cast<float>(k < kCharacterPoses / 2 ? k : kCharacterPoses - k);
  const glm::vec3 pivot(0.0f, -0.1f, 0.0f);
  return glm::translate(glm::mat4(1.0f), pivot) * glm::rotate(glm::mat4(1.0f), angle, glm::vec3(1.0f, 0.0f, 0.0f)) *
         glm::translate(glm::mat4(1.0f), -pivot);
}

// Capsules bound to the neck joint (the identity here): the neck and the two shoulders.
const CapsuleCollider kCharacterCapsules[3] = {{{0.0f, -0.08f, 0.0f}, {0.0f, -0.3f, 0.0f}, 0.04f},
                                               {{0.04f, -0.3f, 0.0f}, {0.25f, -0.33f, 0.0f}, 0.05f},
                                               {{-0.04f, -0.3f, 0.0f}, {-0.25f, -0.33f, 0.0f}, 0.05f}};

void BM_CharacterBind(benchmark::State& state) {
  static const SkinnedMeshData head = benchCharacterHead();
  static const std::vector<glm::vec3> roots = benchCharacterRoots();
  for (auto _ : state) {
    auto binding = SurfaceBinding::create(head.positions, head.indices, roots);
    if (!binding) {
      state.SkipWithError(binding.error().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(binding->points().data());
  }
  state.counters["triangles"] = static_cast<double>(head.indices.size() / 3);
  state.counters["points"] = static_cast<double>(roots.size());
}
BENCHMARK(BM_CharacterBind)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_CharacterStep(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const auto threads = static_cast<unsigned>(state.range(0));
  static const SkinnedMeshData headData = benchCharacterHead();
  static const std::vector<glm::vec3> roots = benchCharacterRoots();
  auto head = SkinnedMesh::create(headData);
  auto binding = SurfaceBinding::create(headData.positions, headData.indices, roots);
  if (!head || !binding) {
    state.SkipWithError("character setup failed");
    return;
  }
  // The host's skinning is not what is measured: every pose is deformed up front.
  std::vector<DeformedSurface> poses(kCharacterPoses);
  for (int k = 0; k < kCharacterPoses; ++k) {
    const std::vector<glm::mat4> joints = {glm::mat4(1.0f), benchNod(k)};
    if (!head->deform(joints, {}, poses[static_cast<std::size_t>(k)])) {
      state.SkipWithError("deform failed");
      return;
    }
  }
  std::vector<glm::vec3> targets(roots.size()), normals(roots.size());
  (void)binding->evaluate(headData.positions, headData.normals, targets, normals, {});
  GroomSettings groom;
  groom.seed = 11;
  groom.particlesPerStrand = 32;
  groom.strandLength = 0.4f;
  auto strands = generateGroomFromRoots(groom, roots, normals);
  if (!strands) {
    state.SkipWithError(strands.error().message.c_str());
    return;
  }
  auto hair = HairSystem::create(*strands, benchFrameSettings(2));
  if (!hair || !hair->setRootRestNormals(normals)) {
    state.SkipWithError("hair setup failed");
    return;
  }

  double evaluateSeconds = 0.0, collidersSeconds = 0.0, targetsSeconds = 0.0, stepSeconds = 0.0;
  int k = 0;
  DeformedSurface skinned = poses[0];  // the host's skinning output, rewritten every step
  for (auto _ : state) {
    // As a host's skinning would, this step's mesh is written just before it is read (untimed).
    std::copy(poses[static_cast<std::size_t>(k)].positions.begin(), poses[static_cast<std::size_t>(k)].positions.end(),
              skinned.positions.begin());
    std::copy(poses[static_cast<std::size_t>(k)].normals.begin(), poses[static_cast<std::size_t>(k)].normals.end(),
              skinned.normals.begin());
    const glm::mat4 nod = benchNod(k);
    k = (k + 1) % kCharacterPoses;
    const auto start = Clock::now();
    (void)binding->evaluate(skinned.positions, skinned.normals, targets, normals, {});
    const auto evaluated = Clock::now();
    // The joint capsules in the head's frame: neck-joint space → world → head-local.
    const glm::mat4 toHead = glm::inverse(nod);
    ColliderSet colliders;
    for (const CapsuleCollider& c : kCharacterCapsules)
      colliders.capsules.push_back(
          {glm::vec3(toHead * glm::vec4(c.a, 1.0f)), glm::vec3(toHead * glm::vec4(c.b, 1.0f)), c.radius});
    colliders.friction = 0.3f;
    (void)hair->setHeadTransform(nod);
    (void)hair->setColliders(std::move(colliders));
    const auto collided = Clock::now();
    (void)hair->setRootTargets(targets, normals);
    const auto targeted = Clock::now();
    if (!hair->advance(1.0 / 120.0, threads)) {
      state.SkipWithError("advance failed");
      return;
    }
    const auto stepped = Clock::now();
    evaluateSeconds += std::chrono::duration<double>(evaluated - start).count();
    collidersSeconds += std::chrono::duration<double>(collided - evaluated).count();
    targetsSeconds += std::chrono::duration<double>(targeted - collided).count();
    stepSeconds += std::chrono::duration<double>(stepped - targeted).count();
  }
  const double n = static_cast<double>(state.iterations());
  const double update = evaluateSeconds + collidersSeconds + targetsSeconds;
  state.counters["evaluate_us"] = 1e6 * evaluateSeconds / n;
  state.counters["colliders_us"] = 1e6 * collidersSeconds / n;
  state.counters["targets_us"] = 1e6 * targetsSeconds / n;
  state.counters["update_us"] = 1e6 * update / n;
  state.counters["step_us"] = 1e6 * stepSeconds / n;
  state.counters["update_ratio"] = update / stepSeconds;
}
BENCHMARK(BM_CharacterStep)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
