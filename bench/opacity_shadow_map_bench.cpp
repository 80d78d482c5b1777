// Opacity shadow maps on the device mane picks (lavapipe without a GPU): one build of the map per
// iteration (record, submit, wait), for 4,096 strands × 32 vertices (126,976 segments) at 512², a
// Nalu-sized groom (the one docs/lavapipe.md#calibration measures).
//
//   BM_OpacityShadowMap/0: 16 slices, graphics builder (one draw into 4 RGBA16F targets)
//   BM_OpacityShadowMap/1: 16 slices, compute builder (fixed-point atomics + prefix-sum resolve)
//   BM_OpacityShadowMap/2: deep opacity map (depth pass + 4-layer pass)
//
// The groom: wavy strands 25 cm long, centres in a ball of 8 cm, r = 40 µm.
//
//   build/release/bench/mane_opacity_shadow_map_bench --benchmark_min_time=2

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include "render/passes/opacity_shadow_map_pass.hpp"

namespace {

using namespace mane;

constexpr std::uint32_t kStrands = 4096;
constexpr std::uint32_t kVertices = 32;

std::vector<glm::vec4> groom() {
  std::vector<glm::vec4> positions;
  std::uint64_t state = 0x2545F4914F6CDD1Dull;
  const auto uniform = [&] {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return double(state >> 11) * 0x1.0p-53 * 2.0 - 1.0;  // [−1, 1)
  };
  const auto inBall = [&] {
    for (;;) {
      const glm::dvec3 p(uniform(), uniform(), uniform());
      if (glm::dot(p, p) <= 1.0 && glm::dot(p, p) > 0.01) return p;
    }
  };
  for (std::uint32_t s = 0; s < kStrands; ++s) {
    const glm::dvec3 centre = 0.08 * inBall();
    const glm::dvec3 along = glm::normalize(inBall());
    const glm::dvec3 wave = glm::normalize(glm::cross(along, inBall()));
    for (std::uint32_t i = 0; i < kVertices; ++i) {
      const double t = double(i) / (kVertices - 1);
      const glm::dvec3 p = centre + (t - 0.5) * 0.25 * along + 0.004 * std::sin(6.0 * std::numbers::pi * t) * wave;
      positions.emplace_back(glm::vec3(p), float(t));
    }
  }
  return positions;
}

template <class T>
T orExit(Result<T> result) {
  if (!result) {
    std::fprintf(stderr, "opacity shadow map bench: %s\n", result.error().message.c_str());
    std::exit(1);
  }
  return std::move(*result);
}

void BM_OpacityShadowMap(benchmark::State& state) {
  static const std::unique_ptr<render::Device> device =
      orExit(render::Device::create(render::deviceSettingsFromEnvironment()));
  const std::vector<glm::vec4> positions = groom();
  const render::Buffer buffer =
      render::Buffer::withData(*device, std::as_bytes(std::span(positions)),
                               vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer);
  render::OpacityShadowSettings settings{.resolution = 512};
  if (state.range(0) == 1) settings.builder = render::OpacityShadowBuilder::kCompute;
  if (state.range(0) == 2) settings.mode = render::OpacityShadowMode::kDeepOpacityMap;
  const auto map = orExit(render::OpacityShadowMapPass::create(*device, {&buffer, kStrands, kVertices}, settings));
  const render::BoundingSphere sphere = orExit(render::boundingSphere(positions));
  if (auto lit = map->setLight(glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)), sphere); !lit) {
    std::fprintf(stderr, "opacity shadow map bench: %s\n", lit.error().message.c_str());
    std::exit(1);
  }
  for (auto _ : state) device->submitAndWait([&](const vk::raii::CommandBuffer& commands) { map->record(commands); });
  state.SetItemsProcessed(std::int64_t(state.iterations()) * map->segmentCount());
  state.SetLabel(state.range(0) == 0   ? "16 slices, graphics"
                 : state.range(0) == 1 ? "16 slices, compute"
                                       : "deep, 4 layers");
}
BENCHMARK(BM_OpacityShadowMap)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
