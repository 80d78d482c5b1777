// Hair shadows of the real TressFX ponytail at full density, on the device mane picks (lavapipe
// without a GPU): what opacity shadow maps and deep opacity maps cost against a plain depth shadow
// map of the same strands, measured in the same run, and how far each is from the ray-cast
// reference.
//
// The groom: the four ponytail files (../shared/assets/hair/tressfx_ponytail/{front_top, side,
// back, tail}.tfx) placed as scenes/ponytail.json places them (z negated, `invert_z`; scaled by
// 0.01 to metres): 4,933 guides × 16 vertices, interpolated once on the device
// (StrandInterpolationPass, single guide, seed 1) into 50,000 strands × 16 vertices (750,000
// segments). The light: the key light of scenes/ponytail.json, towards the light
// normalize(0.3, 0.5, 0.8). Maps 512², strand radius r = 60 µm (a strand width of 1.2e-4 m),
// α = κ = 1.
//
//   BM_PonytailInterpolation: guides → 50,000 × 16 positions and tangents (upload + dispatch).
//   BM_PonytailShadow/0: depth shadow map (nearest hair depth only: the baseline)
//   BM_PonytailShadow/1: 16-slice opacity shadow map, graphics builder
//   BM_PonytailShadow/2: 16-slice opacity shadow map, compute builder
//   BM_PonytailShadow/3: deep opacity map (4 layers, Δ = 1/8 of the diameter)
//
// One build per iteration (record, submit, wait). Counters: gpu_ms, the GPU timestamps around the
// recorded work (render/gpu_timer.hpp), mean per iteration; vs_depth, gpu_ms over the depth
// shadow map's gpu_ms in the same run; error, the mean |T_map − T_ref| at 2,000 dense vertices
// drawn at random, T_map from the GLSL lookup (OpacityShadowMapPass::probe), T_ref from the ray-cast
// reference (render/passes/opacity_shadow_map_reference.hpp) filtered with the map's kernel at its texel size, rays
// ≤ 2r apart, as tests/render/opacity_shadow_map_test.cpp does; the reference runs on the CPU
// interpolation of the same strands (physics::interpolateDenseStrands, which the pass matches
// within 1e-5 relative; slow, so once, outside the timed loops). A summary goes to
// stderr at the end.
//
//   build/release/bench/mane_hair_shadow_bench --benchmark_min_time=2

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include "physics/interpolation.hpp"
#include "render/gpu_timer.hpp"
#include "render/passes/opacity_shadow_map_reference.hpp"
#include "render/passes/opacity_shadow_map_pass.hpp"
#include "render/passes/strand_interpolation_pass.hpp"
#include "scenes/assets.hpp"
#include "scenes/groom_loader.hpp"

namespace {

using namespace mane;

constexpr std::uint32_t kDenseStrands = 50000;
constexpr std::uint32_t kResolution = 512;
constexpr float kStrandRadius = 6e-5f;  // metres: half the 1.2e-4 m strand width
constexpr std::size_t kErrorPoints = 2000;
const glm::vec3 kTowardLight = glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f));  // −(−0.3, −0.5, −0.8)

constexpr std::size_t kModes = 4;
constexpr std::array<const char*, kModes> kLabels{"depth shadow map", "16-slice OSM, graphics", "16-slice OSM, compute",
                                                  "deep opacity map"};

struct Ponytail {
  std::unique_ptr<render::Device> device;
  std::string problem;            ///< why the groom could not be set up, else empty
  std::vector<glm::vec3> guides;  ///< guide after guide, metres
  std::uint32_t vertices = 0;     ///< per dense strand
  std::unique_ptr<render::StrandInterpolationPass> interpolation;
  std::vector<glm::vec4> positions;  ///< the dense strands on the CPU, for the reference
  render::BoundingSphere sphere;
  std::array<std::unique_ptr<render::OpacityShadowMapPass>, kModes> maps;
  std::vector<glm::vec3> errorPoints;
  std::vector<double> referenceTransmittance;  ///< T_ref at errorPoints
};

struct Measured {
  double gpuMilliseconds = 0.0;  ///< 0: not measured
  double error = -1.0;           ///< < 0: not measured
};
std::array<Measured, kModes> measured;

Ponytail load() {
  Ponytail p;
  auto device = render::Device::create(render::deviceSettingsFromEnvironment());
  if (!device) {
    std::fprintf(stderr, "hair shadow bench: %s\n", device.error().message.c_str());
    std::exit(1);
  }
  p.device = std::move(*device);
  auto resolver = scenes::AssetResolver::createDefault();
  if (!resolver) {
    p.problem = resolver.error().message;
    return p;
  }
  std::vector<std::vector<glm::vec3>> guides;
  for (const char* name : {"hair/tressfx_ponytail/front_top.tfx", "hair/tressfx_ponytail/side.tfx",
                           "hair/tressfx_ponytail/back.tfx", "hair/tressfx_ponytail/tail.tfx"}) {
    auto found = resolver->lookup(name);
    if (!found || !found->path) {
      p.problem = std::string(name) + ": " + (found ? found->missingReason : found.error().message);
      return p;
    }
    auto loaded = scenes::loadGroomFile(*found->path);
    if (!loaded) {
      p.problem = loaded.error().message;
      return p;
    }
    for (std::vector<glm::vec3>& strand : loaded->strands) {
      for (glm::vec3& point : strand) point *= glm::vec3(0.01f, 0.01f, -0.01f);  // metres, invert_z
      guides.push_back(std::move(strand));
    }
  }
  physics::DenseGroomSettings settings;
  settings.strandCount = kDenseStrands;
  auto layout = physics::buildDenseStrandLayout(guides, settings);
  if (!layout) {
    p.problem = layout.error().message;
    return p;
  }
  for (const auto& guide : guides) p.guides.insert(p.guides.end(), guide.begin(), guide.end());
  p.vertices = layout->vertexCount;

  auto pass = render::StrandInterpolationPass::create(*p.device, *layout);
  if (!pass) {
    p.problem = pass.error().message;
    return p;
  }
  p.interpolation = std::move(*pass);
  if (auto updated = p.interpolation->updateGuides(p.guides); !updated) {
    p.problem = updated.error().message;
    return p;
  }
  p.device->submitAndWait([&](const vk::raii::CommandBuffer& commands) { p.interpolation->record(commands); });

  std::vector<glm::vec3> dense(layout->vertexTotal());
  if (auto done = physics::interpolateDenseStrands(p.guides, *layout, dense, {}, 2); !done) {
    p.problem = done.error().message;
    return p;
  }
  for (const glm::vec3& point : dense) p.positions.emplace_back(point, 0.0f);
  auto sphere = render::boundingSphere(p.positions);
  if (!sphere) {
    p.problem = sphere.error().message;
    return p;
  }
  p.sphere = *sphere;
  std::fprintf(stderr, "hair shadow bench: %zu guides × %u → %u strands × %u vertices, bounding radius %.3f m\n",
               guides.size(), layout->guideVertexCount, kDenseStrands, p.vertices, double(p.sphere.radius));
  return p;
}

Ponytail& ponytail() {
  static Ponytail instance = load();
  return instance;
}

// T_ref at kErrorPoints random dense vertices, once: the reference filtered with the map's kernel
// at its texel size, rays ≤ 2r apart (as the accuracy tests), on all hardware threads.
void computeReference(Ponytail& p) {
  if (!p.referenceTransmittance.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  auto reference = render::OpacityReference::create({.positions = p.positions,
                                                     .strandCount = kDenseStrands,
                                                     .verticesPerStrand = p.vertices,
                                                     .strandRadius = kStrandRadius},
                                                    kTowardLight);
  if (!reference) {
    std::fprintf(stderr, "hair shadow bench: %s\n", reference.error().message.c_str());
    std::exit(1);
  }
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (std::size_t i = 0; i < kErrorPoints; ++i) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    p.errorPoints.emplace_back(p.positions[(state >> 11) % p.positions.size()]);
  }
  const double texel = 2.0 * p.sphere.radius / kResolution;
  const int raysPerTexel = int(std::ceil(texel / kStrandRadius / 2.0));
  p.referenceTransmittance.resize(kErrorPoints);
  const unsigned workers = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> threads;
  for (unsigned w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      for (std::size_t i = w; i < kErrorPoints; i += workers)
        p.referenceTransmittance[i] =
            reference->transmittance(reference->filteredOpacity(glm::dvec3(p.errorPoints[i]), texel, raysPerTexel));
    });
  for (std::thread& thread : threads) thread.join();
  double mean = 0.0;
  for (const double t : p.referenceTransmittance) mean += t / double(kErrorPoints);
  std::fprintf(stderr, "hair shadow bench: ray-cast reference at %zu points, %d² rays each, mean T %.3f, %.1f s\n",
               kErrorPoints, 3 * raysPerTexel, mean,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

// Runs `record` once per iteration between GPU timestamps; returns the mean GPU milliseconds.
template <class Record>
double timeIterations(benchmark::State& state, const render::Device& device, Record record) {
  render::GpuTimer timer(device, 1);
  double total = 0.0;
  for (auto _ : state) {
    device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      timer.reset(commands);
      timer.begin(commands, render::PassName("pass"));
      record(commands);
      timer.end(commands);
    });
    const std::vector<render::PassTiming> timings = timer.results();
    if (!timings.empty()) total += timings[0].milliseconds;
  }
  return state.iterations() > 0 ? total / double(state.iterations()) : 0.0;
}

void BM_PonytailInterpolation(benchmark::State& state) {
  Ponytail& p = ponytail();
  if (!p.problem.empty()) return state.SkipWithError(p.problem.c_str());
  bool uploaded = true;
  const double gpu = timeIterations(state, *p.device, [&](const vk::raii::CommandBuffer& commands) {
    uploaded = uploaded && p.interpolation->updateGuides(p.guides).has_value();
    p.interpolation->record(commands);
  });
  if (!uploaded) return state.SkipWithError("guide upload failed");
  state.counters["gpu_ms"] = gpu;
  state.SetItemsProcessed(state.iterations() * std::int64_t(p.interpolation->vertexTotal()));
  state.SetLabel(p.device->info().name);
}
BENCHMARK(BM_PonytailInterpolation)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PonytailShadow(benchmark::State& state) {
  Ponytail& p = ponytail();
  if (!p.problem.empty()) return state.SkipWithError(p.problem.c_str());
  const auto mode = static_cast<std::size_t>(state.range(0));
  std::unique_ptr<render::OpacityShadowMapPass>& map = p.maps[mode];
  if (!map) {
    render::OpacityShadowSettings settings{.resolution = kResolution, .strandRadius = kStrandRadius};
    if (mode == 0) settings.mode = render::OpacityShadowMode::kDepthShadowMap;
    if (mode == 2) settings.builder = render::OpacityShadowBuilder::kCompute;
    if (mode == 3) settings.mode = render::OpacityShadowMode::kDeepOpacityMap;
    auto created = render::OpacityShadowMapPass::create(
        *p.device, {&p.interpolation->positions(), kDenseStrands, p.vertices}, settings);
    if (!created) return state.SkipWithError(created.error().message.c_str());
    if (auto lit = (*created)->setLight(kTowardLight, p.sphere); !lit)
      return state.SkipWithError(lit.error().message.c_str());
    map = std::move(*created);
    // One build untimed: lavapipe compiles its shader variants at the first draw.
    p.device->submitAndWait([&](const vk::raii::CommandBuffer& commands) { map->record(commands); });
  }
  const double gpu =
      timeIterations(state, *p.device, [&](const vk::raii::CommandBuffer& commands) { map->record(commands); });
  measured[mode].gpuMilliseconds = gpu;
  if (measured[mode].error < 0.0) {  // the map from the last iteration, once
    computeReference(p);
    const std::vector<glm::vec2> got = map->probe(p.errorPoints);
    double sum = 0.0;
    for (std::size_t i = 0; i < got.size(); ++i) sum += std::abs(double(got[i].y) - p.referenceTransmittance[i]);
    measured[mode].error = sum / double(got.size());
  }
  state.counters["gpu_ms"] = gpu;
  if (measured[0].gpuMilliseconds > 0.0) state.counters["vs_depth"] = gpu / measured[0].gpuMilliseconds;
  state.counters["error"] = measured[mode].error;
  state.SetItemsProcessed(state.iterations() * std::int64_t(map->segmentCount()));
  state.SetLabel(kLabels[mode]);
}
BENCHMARK(BM_PonytailShadow)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

void printSummary() {
  if (measured[0].gpuMilliseconds <= 0.0) return;
  std::fprintf(stderr,
               "\nhair shadow bench: GPU time against the depth shadow map (%.1f ms), mean |ΔT| against the "
               "ray-cast reference at %zu dense vertices\n",
               measured[0].gpuMilliseconds, kErrorPoints);
  for (std::size_t mode = 0; mode < kModes; ++mode)
    if (measured[mode].gpuMilliseconds > 0.0)
      std::fprintf(stderr, "  %-24s %8.1f ms  %5.2f× depth  error %.4f\n", kLabels[mode],
                   measured[mode].gpuMilliseconds, measured[mode].gpuMilliseconds / measured[0].gpuMilliseconds,
                   measured[mode].error);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  printSummary();
  benchmark::Shutdown();
  return 0;
}
