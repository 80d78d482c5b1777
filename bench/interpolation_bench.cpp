// Dense strand interpolation benchmarks (physics/interpolation.hpp).
//
//   BM_Interpolate/<dense strands>/<blend>/<threads>: one interpolation of dense strands × 16
//     vertices from the Nalu-sized guide groom (762 guides × 16 vertices), positions only;
//     blend 0 = single guide, 1 = barycentric (3 guides). items/s = dense vertices per second.
//   BM_InterpolateWithTangents/<dense strands>/<threads>: the same, barycentric, with tangents.
//   BM_CopyBaseline/<dense strands>: a plain copy (memcpy) of as many vertices from a buffer of
//     the same size: the memory-bound floor, so docs/performance.md can quote interpolation /
//     copy.
//
// Dense counts: 4,095 (Nalu, 762 → 4,095) and 100,000.

#include <cstdint>
#include <cstring>
#include <vector>

#include <benchmark/benchmark.h>

#include "physics/groom_generator.hpp"
#include "physics/interpolation.hpp"

namespace {

using namespace mane::physics;

constexpr std::size_t kVertices = 16;

const std::vector<std::vector<glm::vec3>>& naluGuides() {
  static const std::vector<std::vector<glm::vec3>> guides = [] {
    GroomSettings groom;
    groom.seed = 5;
    groom.strandCount = 762;
    groom.particlesPerStrand = kVertices;
    groom.strandLength = 0.3f;
    groom.curlRadius = 0.01f;
    return *generateGroom(groom);
  }();
  return guides;
}

std::vector<glm::vec3> flatGuides() {
  std::vector<glm::vec3> flat;
  for (const auto& guide : naluGuides()) flat.insert(flat.end(), guide.begin(), guide.end());
  return flat;
}

void run(benchmark::State& state, std::size_t strands, GuideBlend blend, unsigned threads, bool withTangents) {
  DenseGroomSettings settings;
  settings.strandCount = strands;
  settings.blend = blend;
  const auto layout = buildDenseStrandLayout(naluGuides(), settings);
  if (!layout) {
    state.SkipWithError(layout.error().message.c_str());
    return;
  }
  const std::vector<glm::vec3> guides = flatGuides();
  std::vector<glm::vec3> positions(layout->vertexTotal());
  std::vector<glm::vec3> tangents(withTangents ? layout->vertexTotal() : 0);
  for (auto _ : state) {
    if (!interpolateDenseStrands(guides, *layout, positions, tangents, threads)) {
      state.SkipWithError("interpolation failed");
      return;
    }
    benchmark::DoNotOptimize(positions.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(layout->vertexTotal()));
  state.counters["vertices"] = static_cast<double>(layout->vertexTotal());
}

void BM_Interpolate(benchmark::State& state) {
  run(state, static_cast<std::size_t>(state.range(0)), static_cast<GuideBlend>(state.range(1)),
      static_cast<unsigned>(state.range(2)), false);
}
BENCHMARK(BM_Interpolate)->ArgsProduct({{4095, 100000}, {0, 1}, {1, 2}})->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_InterpolateWithTangents(benchmark::State& state) {
  run(state, static_cast<std::size_t>(state.range(0)), GuideBlend::kBarycentric, static_cast<unsigned>(state.range(1)),
      true);
}
BENCHMARK(BM_InterpolateWithTangents)
    ->ArgsProduct({{4095, 100000}, {1, 2}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

void BM_CopyBaseline(benchmark::State& state) {
  const std::size_t vertices = static_cast<std::size_t>(state.range(0)) * kVertices;
  std::vector<glm::vec3> source(vertices, glm::vec3(0.25f));
  std::vector<glm::vec3> target(vertices);
  for (auto _ : state) {
    std::memcpy(target.data(), source.data(), vertices * sizeof(glm::vec3));
    benchmark::DoNotOptimize(target.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(vertices));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(vertices * sizeof(glm::vec3)));
}
BENCHMARK(BM_CopyBaseline)->Arg(4095)->Arg(100000)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
