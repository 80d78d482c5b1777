// Dense strand interpolation on the GPU (render/passes/strand_interpolation_pass.hpp) against its
// CPU reference (physics::interpolateDenseStrands), the same case in the same run, so
// docs/performance.md can quote the ratio, which is steadier across machines than milliseconds.
//
//   BM_StrandInterpolationGpu/<dense strands>/<blend>: one frame of the pass on the device mane
//     picks (lavapipe without a GPU): guide upload (updateGuides), record, submit, wait.
//     Positions and tangents. blend 0 = single guide, 1 = barycentric (3 guides). items/s =
//     dense vertices/s.
//   BM_StrandInterpolationCpu/<dense strands>/<blend>/<threads>: the CPU reference for the same
//     layout and guides, positions and tangents.
//
// Guides: the Nalu-sized generated groom (762 guides × 16 vertices, as interpolation_bench).
// Dense counts: 4,095 (Nalu, 762 → 4,095) and 100,000, 16 vertices each.
//
//   build/release/bench/mane_strand_interpolation_gpu_bench --benchmark_min_time=1

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "physics/groom_generator.hpp"
#include "physics/interpolation.hpp"
#include "render/passes/strand_interpolation_pass.hpp"

namespace {

using namespace mane;

constexpr std::size_t kVertices = 16;

const std::vector<std::vector<glm::vec3>>& naluGuides() {
  static const std::vector<std::vector<glm::vec3>> guides = [] {
    physics::GroomSettings groom;
    groom.seed = 5;
    groom.strandCount = 762;
    groom.particlesPerStrand = kVertices;
    groom.strandLength = 0.3f;
    groom.curlRadius = 0.01f;
    return *physics::generateGroom(groom);
  }();
  return guides;
}

std::vector<glm::vec3> flatGuides() {
  std::vector<glm::vec3> flat;
  for (const auto& guide : naluGuides()) flat.insert(flat.end(), guide.begin(), guide.end());
  return flat;
}

DenseStrandLayout layoutFor(std::size_t strands, physics::GuideBlend blend) {
  physics::DenseGroomSettings settings;
  settings.strandCount = strands;
  settings.blend = blend;
  auto layout = physics::buildDenseStrandLayout(naluGuides(), settings);
  if (!layout) {
    std::fprintf(stderr, "strand interpolation bench: %s\n", layout.error().message.c_str());
    std::exit(1);
  }
  return std::move(*layout);
}

render::Device& device() {
  static const std::unique_ptr<render::Device> instance = [] {
    auto created = render::Device::create(render::deviceSettingsFromEnvironment());
    if (!created) {
      std::fprintf(stderr, "strand interpolation bench: %s\n", created.error().message.c_str());
      std::exit(1);
    }
    return std::move(*created);
  }();
  return *instance;
}

void BM_StrandInterpolationGpu(benchmark::State& state) {
  const DenseStrandLayout layout =
      layoutFor(static_cast<std::size_t>(state.range(0)), static_cast<physics::GuideBlend>(state.range(1)));
  auto pass = render::StrandInterpolationPass::create(device(), layout);
  if (!pass) return state.SkipWithError(pass.error().message.c_str());
  const std::vector<glm::vec3> guides = flatGuides();
  for (auto _ : state) {
    if (!(*pass)->updateGuides(guides)) return state.SkipWithError("guide upload failed");
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(layout.vertexTotal()));
  state.SetLabel(device().info().name);
}
BENCHMARK(BM_StrandInterpolationGpu)
    ->ArgsProduct({{4095, 100000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_StrandInterpolationCpu(benchmark::State& state) {
  const DenseStrandLayout layout =
      layoutFor(static_cast<std::size_t>(state.range(0)), static_cast<physics::GuideBlend>(state.range(1)));
  const std::vector<glm::vec3> guides = flatGuides();
  std::vector<glm::vec3> positions(layout.vertexTotal()), tangents(layout.vertexTotal());
  for (auto _ : state) {
    if (!physics::interpolateDenseStrands(guides, layout, positions, tangents, static_cast<unsigned>(state.range(2))))
      return state.SkipWithError("interpolation failed");
    benchmark::DoNotOptimize(positions.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(layout.vertexTotal()));
}
BENCHMARK(BM_StrandInterpolationCpu)
    ->ArgsProduct({{4095, 100000}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
