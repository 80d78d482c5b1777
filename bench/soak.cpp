// A long run of one scene's physics that watches for what a short test cannot see: a NaN that
// appears after hours, or energy that creeps up loop after loop until the groom explodes.
//
//   mane_soak [scene.json] [--steps N] [--threads T] [--bound B]
//
// Steps the scene's simulation N fixed steps (default 1,000,000: 2.3 hours of simulated time at
// 1/120 s) and checks after every step that each hair, cloth and fur particle is finite. The
// kinetic energy of the hair and cloth (Σ ½·m·|x − x_prev|² / h², position Verlet's implied
// velocity, in the solver's masses: 1 kg a hair particle, as only ratios matter there) is
// compared with its settled value: the largest energy of the motion's second loop, once the
// start-up transient has died out. Fails (exit 1) on the
// first non-finite particle or the first step whose energy exceeds B times the settled value
// (default 2). Prints one line per 10 % and a JSON summary at the end (exit 0: passed).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scenes/scene.hpp"
#include "scenes/world.hpp"

namespace {

using mane::physics::Particles;

struct Options {
  std::filesystem::path scene = std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json";
  std::uint64_t steps = 1'000'000;
  unsigned threads = 1;
  double bound = 2.0;  ///< the most kinetic energy allowed, as a multiple of the settled value
};

[[noreturn]] void usage(const char* problem) {
  std::fprintf(stderr, "mane_soak: %s\nusage: mane_soak [scene.json] [--steps N] [--threads T] [--bound B]\n", problem);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage((arg + " needs a value").c_str());
      return argv[++i];
    };
    if (arg == "--steps") options.steps = std::stoull(value());
    else if (arg == "--threads") options.threads = unsigned(std::stoul(value()));
    else if (arg == "--bound") options.bound = std::stod(value());
    else if (!arg.empty() && arg[0] == '-') usage(("unknown option " + arg).c_str());
    else options.scene = arg;
  }
  if (options.threads == 0) usage("--threads must be at least 1");
  if (!(options.bound > 1.0)) usage("--bound must be above 1");
  return options;
}

/// Kinetic energy of the movable particles in the solver's masses: Σ ½·m·|x − x_prev|² / h².
double kineticEnergy(const Particles& particles, double step) {
  double sum = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.inverseMasses[i] <= 0.0f) continue;
    const glm::dvec3 displacement = glm::dvec3(particles.positions[i]) - glm::dvec3(particles.previousPositions[i]);
    sum += 0.5 * glm::dot(displacement, displacement) / double(particles.inverseMasses[i]);
  }
  return sum / (step * step);
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// The first non-finite particle of `particles`, as "what, index", or empty.
std::string firstNonFinite(const Particles& particles, const std::string& what) {
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (!finite(particles.positions[i]) || !finite(particles.previousPositions[i]))
      return what + " particle " + std::to_string(i);
  return {};
}

struct Reading {
  double energy = 0.0;
  std::string nonFinite;  ///< empty: every particle finite
};

Reading read(const mane::scenes::World& world, double step) {
  Reading reading;
  for (std::size_t g = 0; g < world.simulatedGroomCount(); ++g) {
    const Particles& particles = world.simulatedGroom(g).particles();
    reading.energy += kineticEnergy(particles, step);
    if (reading.nonFinite.empty()) reading.nonFinite = firstNonFinite(particles, world.simulatedGroomName(g));
  }
  for (std::size_t c = 0; c < world.cloths().size(); ++c) {
    const Particles& particles = world.cloths()[c].cloth().particles();
    reading.energy += kineticEnergy(particles, step);
    if (reading.nonFinite.empty()) reading.nonFinite = firstNonFinite(particles, "cloth " + std::to_string(c));
  }
  for (const auto& fur : world.furLeans())
    for (std::size_t i = 0; i < fur.leans.size() && reading.nonFinite.empty(); ++i)
      if (!finite(fur.leans[i])) reading.nonFinite = "fur " + std::to_string(fur.fur) + " lean " + std::to_string(i);
  return reading;
}

/// The period of the head's motion, s (0 when it does not repeat).
double loopSeconds(const mane::scenes::Scene& scene) {
  const mane::scenes::HeadMotion& motion = scene.headMotion;
  using Kind = mane::scenes::HeadMotionKind;
  if (motion.kind == Kind::keyframes && motion.loop && !motion.keyframes.empty())
    return double(motion.keyframes.back().timeSeconds - motion.keyframes.front().timeSeconds);
  if (motion.kind != Kind::none && motion.kind != Kind::keyframes && motion.frequencyHz > 0.0f)
    return 1.0 / double(motion.frequencyHz);
  return 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  auto scene = mane::scenes::loadScene(options.scene);
  if (!scene) return std::fprintf(stderr, "mane_soak: %s\n", scene.error().message.c_str()), 2;
  auto resolver = mane::scenes::AssetResolver::createDefault();
  if (!resolver) return std::fprintf(stderr, "mane_soak: %s\n", resolver.error().message.c_str()), 2;
  auto world = mane::scenes::World::create(std::move(*scene), *resolver);
  if (!world) return std::fprintf(stderr, "mane_soak: %s\n", world.error().message.c_str()), 2;
  for (const std::string& note : world->notes()) std::fprintf(stderr, "note: %s\n", note.c_str());

  const double step = world->scene().simulation.stepSeconds;
  // The settled value: the largest energy over the second loop of the motion (the first lets the
  // start-up transient die out; the scene's settle time was simulated at load), or over the
  // second 2 s of a scene that does not loop.
  const double loop = std::max(loopSeconds(world->scene()), 2.0);
  const auto settledFrom = std::uint64_t(std::ceil(loop / step));
  const auto settledTo = std::uint64_t(std::ceil(2.0 * loop / step));
  if (options.steps <= settledTo) usage(("--steps must exceed " + std::to_string(settledTo) + ", the settling window").c_str());

  double settled = 0.0, largest = 0.0, largestAfterSettling = 0.0;
  std::uint64_t largestStep = 0;
  const auto start = std::chrono::steady_clock::now();
  auto fail = [&](std::uint64_t k, const std::string& why) {
    std::printf("FAILED at step %llu: %s\n", static_cast<unsigned long long>(k), why.c_str());
    return 1;
  };
  for (std::uint64_t k = 1; k <= options.steps; ++k) {
    if (auto advanced = world->advance(step, options.threads); !advanced) return fail(k, advanced.error().message);
    const Reading reading = read(*world, step);
    if (!reading.nonFinite.empty()) return fail(k, reading.nonFinite + " is not finite");
    largest = std::max(largest, reading.energy);
    if (k >= settledFrom && k <= settledTo) settled = std::max(settled, reading.energy);
    if (k > settledTo) {
      if (reading.energy > options.bound * settled)
        return fail(k, "kinetic energy " + std::to_string(reading.energy) + " is over " +
                           std::to_string(options.bound) + " × the settled " + std::to_string(settled));
      if (reading.energy > largestAfterSettling) largestAfterSettling = reading.energy, largestStep = k;
    }
    if (k % (options.steps / 10) == 0)
      std::printf("step %llu: energy %.3e (settled %.3e, largest since %.3e)\n", static_cast<unsigned long long>(k),
                  reading.energy, settled, largestAfterSettling);
    std::fflush(stdout);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json report = {{"scene", options.scene.string()},
                                 {"steps", options.steps},
                                 {"simulated_seconds", double(options.steps) * step},
                                 {"threads", options.threads},
                                 {"particles", world->particleCount()},
                                 {"settled_energy", settled},
                                 {"settled_window_steps", {settledFrom, settledTo}},
                                 {"largest_energy_after_settling", largestAfterSettling},
                                 {"largest_at_step", largestStep},
                                 {"largest_over_settled", settled > 0.0 ? largestAfterSettling / settled : 0.0},
                                 {"bound", options.bound},
                                 {"largest_energy", largest},
                                 {"wall_seconds", seconds},
                                 {"all_finite", true}};
  std::printf("%s\n", report.dump(2).c_str());
  return 0;
}
