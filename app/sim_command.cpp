// `mane sim`: the scene's physics only (no GPU), ending with the state hash. Beside it, for
// deterministic tests and render farms: a per-step hash trace, states saved at chosen steps,
// a simulation cache of the frames `mane render --cache` renders, and a JSON summary.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/scene_loading.hpp"
#include "app/sim_outputs.hpp"
#include "physics/hash.hpp"
#include "scenes/sim_cache.hpp"

namespace mane::app {
namespace {

struct SimOptions {
  std::string scene = defaultScenePath().string();
  int steps = 120;
  unsigned threads = 1;
  std::string trace;              // empty: no trace
  std::string save;               // empty: nothing saved
  std::vector<std::uint64_t> at;  // steps to save at
  std::string cache;              // empty: no cache; else frames of 1/fps instead of fixed steps
  int frames = 1;
  double fps = 30.0;
  std::uint64_t perturb = 0;  // 0: none; else the step before which a particle is moved
  bool json = false;
  bool strict = false;  // every groom strict
};

/// How far the tests' --perturb moves a particle, metres: far above rounding, far below anything
/// a person would see.
constexpr float kPerturbMetres = 1e-4f;

/// --perturb: the tip of the first groom's first guide moved along x, its previous position
/// alike (no velocity added), through the solver's own state setter.
Result<void> perturbOneParticle(scenes::World& world) {
  if (world.simulatedGroomCount() == 0) return fail("--perturb moves a guide particle; the scene simulates no groom");
  physics::HairSystem& hair = world.simulatedGroomMutable(0);
  std::vector<glm::vec3> positions = hair.particles().positions;
  std::vector<glm::vec3> previous = hair.particles().previousPositions;
  const physics::GuideStrand& strand = hair.strands().front();
  const std::size_t tip = strand.firstParticle + strand.particleCount - 1;
  positions[tip].x += kPerturbMetres;
  previous[tip].x += kPerturbMetres;
  return hair.setParticleState(positions, previous);
}

void run(const SimOptions& options) {
  const bool caching = !options.cache.empty();
  // A cache's frames carry the leans of the furs the renderer draws, which need their photos.
  auto world = loadWorld(options.scene, {.loadTextures = caching, .strictGrooms = options.strict}, !options.json);
  if (!world) return failWith(world.error().message);
  // The loop's unit: one fixed step, or with --cache one frame of 1/fps (several fixed steps),
  // the World::advance calls `mane render` makes.
  const double step = caching ? 1.0 / options.fps : world->scene().simulation.stepSeconds;
  const std::uint64_t steps = caching ? std::uint64_t(options.frames - 1) : std::uint64_t(options.steps);
  for (std::uint64_t at : options.at)
    if (at > steps)
      return failWith("--at " + std::to_string(at) + " is past the last " + (caching ? "frame " : "step ") +
                      std::to_string(steps));
  if (options.perturb > steps)
    return failWith("--perturb " + std::to_string(options.perturb) + " is past the last step " + std::to_string(steps));

  std::optional<StateTrace> trace;
  if (!options.trace.empty()) {
    auto opened = StateTrace::open(options.trace);
    if (!opened) return failWith(opened.error().message);
    trace = std::move(*opened);
  }
  std::vector<std::filesystem::path> saved;
  scenes::SimCacheManifest manifest{.scene = std::filesystem::absolute(options.scene).lexically_normal().string(),
                                    .fps = options.fps};
  // Everything asked of the state after `k` advances.
  auto record = [&](std::uint64_t k) -> Result<void> {
    const std::uint64_t hash = world->stateHash();
    if (trace)
      if (auto recorded = trace->record(k, hash); !recorded) return recorded;
    if (std::find(options.at.begin(), options.at.end(), k) != options.at.end()) {
      auto written = saveState(*world, k, options.save);
      if (!written) return std::unexpected(written.error());
      saved.insert(saved.end(), written->begin(), written->end());
    }
    if (caching) {
      const auto frame = static_cast<std::uint32_t>(k);
      auto written = scenes::writeSimulatedState(scenes::cacheFramePath(options.cache, frame),
                                                 scenes::captureSimulatedState(*world, k));
      if (!written) return written;
      manifest.stateHashes.push_back(hash);
      manifest.frames = frame + 1;
    }
    return {};
  };

  const auto start = std::chrono::steady_clock::now();
  if (auto recorded = record(0); !recorded) return failWith(recorded.error().message);
  for (std::uint64_t k = 1; k <= steps; ++k) {
    if (k == options.perturb)
      if (auto moved = perturbOneParticle(*world); !moved) return failWith(moved.error().message);
    if (auto advanced = world->advance(step, options.threads); !advanced) return failWith(advanced.error().message);
    if (auto recorded = record(k); !recorded) return failWith(recorded.error().message);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (trace)
    if (auto closed = trace->close(); !closed) return failWith(closed.error().message);
  if (caching)
    if (auto written = scenes::writeCacheManifest(options.cache, manifest); !written)
      return failWith(written.error().message);

  if (options.json) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& path : saved) files.push_back(path.string());
    const nlohmann::json report = {
        {"command", "sim"},
        {"scene", manifest.scene},
        {"steps", steps},
        {"step_seconds", step},
        {"unit", caching ? "frame" : "fixed step"},
        {"threads", options.threads},
        {"guide_strands", world->guideStrandCount()},
        {"particles", world->particleCount()},
        {"wall_seconds", seconds},
        {"steps_per_second", seconds > 0.0 ? double(steps) / seconds : 0.0},
        {"state_hash", physics::hashText(world->stateHash())},
        {"notes", world->notes()},
        {"saved", files},
        {"trace", options.trace.empty() ? nlohmann::json() : nlohmann::json(options.trace)},
        {"cache", caching
                      ? nlohmann::json({{"folder", options.cache}, {"frames", manifest.frames}, {"fps", options.fps}})
                      : nlohmann::json()}};
    std::cout << report.dump(2) << '\n';
    return succeed();
  }
  for (const auto& path : saved) std::printf("wrote %s\n", path.string().c_str());
  if (caching) std::printf("wrote %u frames at %g fps to %s\n", manifest.frames, options.fps, options.cache.c_str());
  std::printf("simulated %" PRIu64 " %s of %.6f s: %zu guide strands, %zu particles, %u thread%s, %.3f s wall\n", steps,
              caching ? "frames" : "steps", step, world->guideStrandCount(), world->particleCount(), options.threads,
              options.threads == 1 ? "" : "s", seconds);
  std::printf("state-hash: %s\n", physics::hashText(world->stateHash()).c_str());
  succeed();
}

}  // namespace

void addSimCommand(CLI::App& app) {
  auto options = std::make_shared<SimOptions>();
  auto* command = app.add_subcommand("sim", "Simulate a scene's physics (no GPU) and print the state hash");
  command->add_option("scene", options->scene, "Scene file (JSON)")->capture_default_str();
  auto* steps = command->add_option("--steps", options->steps, "Fixed steps to simulate")
                    ->check(CLI::Range(0, 100000000))
                    ->capture_default_str();
  command->add_option("--threads", options->threads, "Worker threads (the hash does not depend on it)")
      ->check(CLI::Range(1u, 256u))
      ->capture_default_str();
  command
      ->add_option("--trace", options->trace,
                   "Write the state hash after every step to FILE, one line \"STEP HASH\" each, step 0 the "
                   "loaded state: diff two runs' traces to find their first differing step")
      ->type_name("FILE");
  auto* save = command
                   ->add_option("--save", options->save,
                                "Write the hair, cloth and fur state at each step of --at to FILE_SSSSSS.msim "
                                "(docs/sim-state-format.md), each groom also to FILE_SSSSSS_GROOM.hair")
                   ->type_name("FILE");
  auto* at = command->add_option("--at", options->at, "Steps to --save at, e.g. 0,60,120 (0: the loaded state)")
                 ->delimiter(',')
                 ->type_name("STEPS");
  save->needs(at);
  at->needs(save);
  auto* cache = command
                    ->add_option("--cache", options->cache,
                                 "Write a simulation cache of --frames frames at --fps to FOLDER for `mane render "
                                 "--cache` (frame f: the world after f advances of 1/fps, as `mane render` "
                                 "simulates); steps are then frames")
                    ->type_name("FOLDER");
  auto* frames = command->add_option("--frames", options->frames, "Frames to cache (with --cache)")
                     ->check(CLI::Range(1, 1000000))
                     ->capture_default_str();
  auto* fps = command->add_option("--fps", options->fps, "Frames per second of the cache (with --cache)")
                  ->check(CLI::Range(1.0, 1000.0))
                  ->capture_default_str();
  frames->needs(cache);
  fps->needs(cache);
  cache->excludes(steps);
  command
      ->add_option("--perturb", options->perturb,
                   "For determinism tests: move one guide particle by 0.1 mm before step STEP, so that the "
                   "trace first differs there (scenes with a groom)")
      ->type_name("STEP")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100000000}))
      ->group("Testing");
  command->add_flag("--strict", options->strict, kStrictGroomsHelp);
  command->add_flag("--json", options->json, "Print a JSON summary (steps, times, state hash) instead of text");
  command->callback([options] { run(*options); });
}

}  // namespace mane::app
