// `mane sim`: the scene's physics only (no GPU), ending with the state hash.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cinttypes>
#include <cstdio>

#include "app/commands.hpp"
#include "app/scene_loading.hpp"

namespace mane::app {
namespace {

struct SimOptions {
  std::string scene = defaultScenePath().string();
  int steps = 120;
  unsigned threads = 1;
};

void run(const SimOptions& options) {
  auto world = loadWorld(options.scene, {.loadTextures = false});
  if (!world) return failWith(world.error().message);
  const double step = world->scene().simulation.stepSeconds;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < options.steps; ++i)
    if (auto advanced = world->advance(step, options.threads); !advanced) return failWith(advanced.error().message);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("simulated %d steps of %.6f s: %zu guide strands, %zu particles, %u thread%s, %.3f s wall\n",
              options.steps, step, world->guideStrandCount(), world->particleCount(), options.threads,
              options.threads == 1 ? "" : "s", seconds);
  std::printf("state-hash: %016" PRIx64 "\n", world->stateHash());
  succeed();
}

}  // namespace

void addSimCommand(CLI::App& app) {
  auto options = std::make_shared<SimOptions>();
  auto* command = app.add_subcommand("sim", "Simulate a scene's physics (no GPU) and print the state hash");
  command->add_option("scene", options->scene, "Scene file (JSON)")->capture_default_str();
  command->add_option("--steps", options->steps, "Fixed steps to simulate")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  command->add_option("--threads", options->threads, "Worker threads (the hash does not depend on it)")
      ->check(CLI::Range(1u, 256u))
      ->capture_default_str();
  command->callback([options] { run(*options); });
}

}  // namespace mane::app
