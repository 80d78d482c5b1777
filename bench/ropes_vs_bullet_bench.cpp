// mane vs Bullet soft bodies: the same ropes side by side in one run.
//
//   BM_RopesVsBullet/<ropes>/<particles>: <ropes> ropes of <particles> particles, 1 cm segments,
//     each hanging from a fixed root and released horizontally (along +x) at rest, so they swing
//     down under gravity and stretch. Simulated for kSimSeconds by
//       - Bullet: one btSoftBody per rope (btSoftBodyHelpers::CreateRope, root mass 0, node mass 1,
//         link stiffness kLST = 1, default "Positions" solver preset, m_cfg.piterations = N,
//         m_cfg.kDP = d) in a btSoftRigidDynamicsWorld stepped with stepSimulation(h, 0), i.e.
//         exactly one internal step of h per call; collisions off (broadphase mask 0, no
//         self-collision flags), no rigid bodies;
//       - mane: one HairSystem whose strands are the ropes (root pinned), the same h, N
//         constraintIterations and damping d, tethers OFF (like-for-like: only distance
//         constraints, as Bullet) and, separately, tethers ON; one thread (Bullet's soft-body
//         world is single-threaded).
//     Both integrate gravity −9.81 m/s² with damped position Verlet: Bullet's v ← (x − x_prev)/h ·
//     (1 − kDP), x ← x + h·(v + g·h) is mane's x ← x + (1 − d)(x − x_prev) + g·h², so kDP = d
//     gives the same damping (d = 0.01 per step). Both relax the links root → tip, Gauss–Seidel;
//     Bullet's projection is a sqrt-free first-order approximation, mane's is exact; Bullet's
//     moves a link stretched to (1 + e)·L by (1 + e)(2 + e)/(1 + (1 + e)²) ≈ 1 + e/2 times the
//     exact correction (1.2× at e = 1), an over-relaxation that lowers its stretch at few
//     iterations.
//
//   Only the stepping calls are timed (std::chrono::steady_clock around each step, manual
//   time); building the systems and measuring stretch after every step are not. Counters:
//     bullet_ms, mane_ms, mane_tethers_ms: wall milliseconds per simulated second;
//     bullet/mane, bullet/mane_tethers: the time ratios (goal ≥ 10);
//     *_stretch_end, *_stretch_max: largest relative segment stretch |x_i − x_{i−1}|/L − 1 over
//       all segments at the end, and over every step of the run (goal: mane's ≤ Bullet's);
//     bullet_bodies_ms, bullet_bodies/mane: Bullet stepped without the world (each body's
//       predictMotion, solveConstraints, integrateMotion, as btDefaultSoftBodySolver does): the
//       soft-body solver's own cost, for a ratio that does not count the world's overhead;
//     tip_gap_mm: largest distance between a rope's tip in mane (tethers off) and in Bullet at
//       the end. At 4 iterations the ropes stretch a lot and the two projection formulas part
//       ways (tens of cm for 128 particles); with 40 iterations the gap is below 1 mm for
//       1000 × 32, which checks that both simulate the same ropes.
//   Each benchmark iteration runs every engine once; each engine's figures are from its fastest
//   of kRounds runs (the runs are deterministic, only the times differ). The manual "Time"
//   column is the sum of the engines' stepping times per round. A summary is printed to stdout.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <btBulletDynamicsCommon.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include "physics/hair.hpp"
#include "physics/solver.hpp"

namespace {

using namespace mane::physics;
using Clock = std::chrono::steady_clock;

constexpr double kStep = 1.0 / 120.0;   // s, both engines
constexpr int kIterations = 4;          // constraint sweeps per step, both engines
constexpr float kDamping = 0.01f;       // velocity damping per step, both engines
constexpr float kGravity = -9.81f;      // m/s², along y
constexpr float kSegment = 0.01f;       // m, rest length of every link
constexpr double kSimSeconds = 2.0;     // simulated per engine and case
constexpr float kRootSpacing = 0.05f;   // m, between roots on a square grid in the xz plane
constexpr int kRounds = 5;              // each engine's time is its fastest of this many runs

// Rope r, particle i (root first): roots on a grid, ropes horizontal along +x.
glm::vec3 restPosition(std::size_t rope, std::size_t side, std::size_t i) {
  const glm::vec3 root{kRootSpacing * static_cast<float>(rope % side), 1.0f,
                       kRootSpacing * static_cast<float>(rope / side)};
  return root + glm::vec3(kSegment * static_cast<float>(i), 0.0f, 0.0f);
}

struct Ropes {
  std::size_t count = 0;
  std::size_t particles = 0;
  std::size_t side = 0;
};

struct RunResult {
  double seconds = 0.0;     // stepping wall time
  double stretchEnd = 0.0;  // at the last step
  double stretchMax = 0.0;  // over all steps
  std::vector<glm::vec3> tips;
  int steps = 0;
};

// Largest relative stretch of the consecutive segments in positions [first, first + n).
template <class Get>
double ropeStretch(std::size_t n, Get&& position) {
  double worst = -1.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double len = glm::length(position(i) - position(i - 1));
    worst = std::max(worst, len / kSegment - 1.0);
  }
  return worst;
}

// ---- mane -----------------------------------------------------------------------------------

RunResult runMane(const Ropes& ropes, bool tethers) {
  std::vector<std::vector<glm::vec3>> strands(ropes.count);
  for (std::size_t r = 0; r < ropes.count; ++r)
    for (std::size_t i = 0; i < ropes.particles; ++i) strands[r].push_back(restPosition(r, ropes.side, i));
  SolverSettings settings;
  settings.fixedStep = kStep;
  settings.gravity = {0.0f, kGravity, 0.0f};
  settings.damping = kDamping;
  settings.constraintIterations = kIterations;
  settings.tethers = tethers;
  settings.shapeStiffness = 0.0f;
  auto hair = HairSystem::create(strands, settings);
  if (!hair) {
    std::fprintf(stderr, "HairSystem::create: %s\n", hair.error().message.c_str());
    std::abort();
  }
  RunResult result;
  const int steps = static_cast<int>(std::lround(kSimSeconds / kStep));
  for (int s = 0; s < steps; ++s) {
    const auto start = Clock::now();
    const auto ok = hair->advance(kStep, 1);
    result.seconds += std::chrono::duration<double>(Clock::now() - start).count();
    if (!ok) {
      std::fprintf(stderr, "HairSystem::advance: %s\n", ok.error().message.c_str());
      std::abort();
    }
    double stretch = -1.0;
    for (std::size_t r = 0; r < ropes.count; ++r) {
      const auto p = hair->strandPositions(r);
      stretch = std::max(stretch, ropeStretch(p.size(), [&](std::size_t i) { return p[i]; }));
    }
    result.stretchMax = std::max(result.stretchMax, stretch);
    result.stretchEnd = stretch;
  }
  result.steps = static_cast<int>(hair->stepCount());
  for (std::size_t r = 0; r < ropes.count; ++r) result.tips.push_back(hair->strandPositions(r).back());
  return result;
}

// ---- Bullet ---------------------------------------------------------------------------------

class BulletRopes {
public:
  explicit BulletRopes(const Ropes& ropes)
      : config_(std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>()),
        dispatcher_(std::make_unique<btCollisionDispatcher>(config_.get())),
        broadphase_(std::make_unique<btDbvtBroadphase>()),
        solver_(std::make_unique<btSequentialImpulseConstraintSolver>()),
        world_(std::make_unique<btSoftRigidDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                          config_.get())) {
    const btVector3 gravity(0, kGravity, 0);
    world_->setGravity(gravity);
    btSoftBodyWorldInfo& info = world_->getWorldInfo();
    info.m_gravity = gravity;
    info.air_density = 0;
    info.m_sparsesdf.Initialize();
    for (std::size_t r = 0; r < ropes.count; ++r) {
      const glm::vec3 a = restPosition(r, ropes.side, 0);
      const glm::vec3 b = restPosition(r, ropes.side, ropes.particles - 1);
      // res = intermediate nodes; fixeds = 1 pins node 0 (mass 0). Node masses are 1.
      btSoftBody* rope = btSoftBodyHelpers::CreateRope(info, btVector3(a.x, a.y, a.z), btVector3(b.x, b.y, b.z),
                                                       static_cast<int>(ropes.particles) - 2, 1);
      rope->m_materials[0]->m_kLST = 1;  // full linear stiffness
      rope->m_cfg.piterations = kIterations;
      rope->m_cfg.kDP = kDamping;
      rope->m_cfg.collisions = 0;  // no self / soft-soft / soft-rigid collision
      // Broadphase group 1, mask 0: the rope never forms a collision pair.
      world_->addSoftBody(rope, 1, 0);
      ropes_.emplace_back(rope);
    }
  }
  ~BulletRopes() {
    for (auto& rope : ropes_) world_->removeSoftBody(rope.get());
  }
  BulletRopes(const BulletRopes&) = delete;
  BulletRopes& operator=(const BulletRopes&) = delete;

  // One internal step of exactly h (maxSubSteps = 0: variable-step mode, one step).
  void step() { world_->stepSimulation(static_cast<btScalar>(kStep), 0); }

  // The same step without the world (no broadphase, dispatcher or rigid-body solver): only what
  // btDefaultSoftBodySolver does per body, in the world's order. Same positions as step().
  void stepBodiesOnly() {
    const auto h = static_cast<btScalar>(kStep);
    for (auto& rope : ropes_) rope->predictMotion(h);
    for (auto& rope : ropes_) rope->solveConstraints();
    for (auto& rope : ropes_) rope->integrateMotion();
  }

  [[nodiscard]] const std::vector<std::unique_ptr<btSoftBody>>& ropes() const { return ropes_; }

private:
  std::unique_ptr<btSoftBodyRigidBodyCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btSoftRigidDynamicsWorld> world_;
  std::vector<std::unique_ptr<btSoftBody>> ropes_;
};

glm::vec3 toGlm(const btVector3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

RunResult runBullet(const Ropes& ropes, bool bodiesOnly) {
  BulletRopes world(ropes);
  RunResult result;
  const int steps = static_cast<int>(std::lround(kSimSeconds / kStep));
  for (int s = 0; s < steps; ++s) {
    const auto start = Clock::now();
    if (bodiesOnly)
      world.stepBodiesOnly();
    else
      world.step();
    result.seconds += std::chrono::duration<double>(Clock::now() - start).count();
    double stretch = -1.0;
    for (const auto& rope : world.ropes()) {
      const auto& nodes = rope->m_nodes;
      stretch = std::max(stretch, ropeStretch(static_cast<std::size_t>(nodes.size()), [&](std::size_t i) {
                           return toGlm(nodes[static_cast<int>(i)].m_x);
                         }));
    }
    result.stretchMax = std::max(result.stretchMax, stretch);
    result.stretchEnd = stretch;
  }
  result.steps = steps;
  for (const auto& rope : world.ropes()) result.tips.push_back(toGlm(rope->m_nodes[rope->m_nodes.size() - 1].m_x));
  return result;
}

// ---- the benchmark --------------------------------------------------------------------------

void BM_RopesVsBullet(benchmark::State& state) {
  Ropes ropes;
  ropes.count = static_cast<std::size_t>(state.range(0));
  ropes.particles = static_cast<std::size_t>(state.range(1));
  ropes.side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(ropes.count))));
  // Every benchmark iteration is one round: each engine simulates the whole run afresh, one
  // after the other. The runs are deterministic, so only the times differ between rounds; each
  // engine's figure is its fastest round (the least disturbed by other load on the machine).
  RunResult bullet, bulletBodies, mane, maneTethers;
  const auto keepFastest = [](RunResult& best, RunResult run) {
    if (best.steps == 0 || run.seconds < best.seconds) best = std::move(run);
  };
  for (auto _ : state) {
    double round = 0.0;
    for (auto [engine, best] : {std::pair{0, &bullet}, {1, &bulletBodies}, {2, &mane}, {3, &maneTethers}}) {
      RunResult run = engine < 2 ? runBullet(ropes, engine == 1) : runMane(ropes, engine == 3);
      round += run.seconds;
      keepFastest(*best, std::move(run));
    }
    state.SetIterationTime(round);
  }
  if (bullet.steps != mane.steps || mane.steps != maneTethers.steps) {
    state.SkipWithError("engines ran different step counts");
    return;
  }
  double tipGap = 0.0, bodiesGap = 0.0;
  for (std::size_t r = 0; r < ropes.count; ++r) {
    tipGap = std::max(tipGap, static_cast<double>(glm::length(mane.tips[r] - bullet.tips[r])));
    bodiesGap = std::max(bodiesGap, static_cast<double>(glm::length(bulletBodies.tips[r] - bullet.tips[r])));
  }
  if (bodiesGap != 0.0) {
    state.SkipWithError("Bullet without the world does not reproduce Bullet in the world");
    return;
  }

  const double simulated = kSimSeconds;
  const double bulletMs = 1e3 * bullet.seconds / simulated;
  const double bulletBodiesMs = 1e3 * bulletBodies.seconds / simulated;
  const double maneMs = 1e3 * mane.seconds / simulated;
  const double maneTethersMs = 1e3 * maneTethers.seconds / simulated;
  state.counters["bullet_ms"] = bulletMs;
  state.counters["bullet_bodies_ms"] = bulletBodiesMs;
  state.counters["mane_ms"] = maneMs;
  state.counters["mane_tethers_ms"] = maneTethersMs;
  state.counters["bullet/mane"] = bulletMs / maneMs;
  state.counters["bullet/mane_tethers"] = bulletMs / maneTethersMs;
  state.counters["bullet_bodies/mane"] = bulletBodiesMs / maneMs;
  state.counters["bullet_stretch_end"] = bullet.stretchEnd;
  state.counters["bullet_stretch_max"] = bullet.stretchMax;
  state.counters["mane_stretch_end"] = mane.stretchEnd;
  state.counters["mane_stretch_max"] = mane.stretchMax;
  state.counters["mane_tethers_stretch_end"] = maneTethers.stretchEnd;
  state.counters["mane_tethers_stretch_max"] = maneTethers.stretchMax;
  state.counters["tip_gap_mm"] = 1e3 * tipGap;
  std::printf(
      "ropes %zu x %zu particles, h = 1/%.0f s, %d iterations, damping %.2f/step, %.1f s simulated (%d steps):\n"
      "  Bullet btSoftBody      %9.2f ms per sim s   stretch end %.3e  max %.3e\n"
      "  Bullet bodies only     %9.2f ms per sim s   (same positions, no world)   Bullet bodies/mane %.1fx\n"
      "  mane (tethers off)     %9.2f ms per sim s   stretch end %.3e  max %.3e   Bullet/mane %.1fx\n"
      "  mane (tethers on)      %9.2f ms per sim s   stretch end %.3e  max %.3e   Bullet/mane %.1fx\n"
      "  largest tip gap mane (tethers off) vs Bullet at the end: %.3f mm\n",
      ropes.count, ropes.particles, 1.0 / kStep, kIterations, static_cast<double>(kDamping), simulated, mane.steps,
      bulletMs, bullet.stretchEnd, bullet.stretchMax, bulletBodiesMs, bulletBodiesMs / maneMs, maneMs, mane.stretchEnd, mane.stretchMax, bulletMs / maneMs,
      maneTethersMs, maneTethers.stretchEnd, maneTethers.stretchMax, bulletMs / maneTethersMs, 1e3 * tipGap);
  std::fflush(stdout);
}
BENCHMARK(BM_RopesVsBullet)
    ->Args({1000, 32})
    ->Args({100, 128})
    ->Iterations(kRounds)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
