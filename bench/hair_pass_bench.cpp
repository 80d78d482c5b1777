// The hair ribbon pass (render/passes/hair_pass.hpp) at a Nalu-sized groom: 4,096 strands ×
// 32 vertices (4,096 × 31 × 2 = 254k triangles) at 1280×720, against an empty frame (clear, and
// the MSAA resolve where there is one) in the same run, so the difference is the hair's cost.
//
//   BM_EmptyFrame/<samples>/0: record, submit, wait: begin rendering (clear colour + depth), end
//     (resolve at 4×).
//   BM_HairFrame/<samples>/<lights>/<width>: the same with the hair: the per-vertex shading
//     dispatch (render/passes/hair_lighting_pass.hpp, blonde Marschner LUTs, no shadow maps) with
//     a key and a back light (lights 2) or ambient only (lights 0), the choice of primitive, then
//     the hair draw, premultiplied-alpha blending. Width in µm: 800, strands up to ~1.3 pixels wide, drawn
//     as ribbons (lines would leave about a quarter of their width uncovered); 400, up to ~0.65
//     pixels, drawn as 1-pixel lines (render/passes/hair_pass.hpp, "Lines"). The counters say
//     which was drawn.
//
// The groom: strands hanging from a half-sphere "scalp" (radius 0.1 m), 0.3 m down and flaring
// out, seen from 0.6 m: about a third of the frame. Wall time around submit + wait (it agrees with
// timestamps for graphics, docs/lavapipe.md#timestamps).
//
//   build/release/bench/mane_hair_pass_bench --benchmark_min_time=2

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "render/luts/marschner_lut.hpp"
#include "render/passes/hair_lighting_pass.hpp"
#include "render/passes/hair_pass.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/render_target.hpp"

namespace {

using namespace mane;
using namespace mane::render;

constexpr std::uint32_t kStrands = 4096;
constexpr std::uint32_t kVertices = 32;
constexpr vk::Extent2D kExtent{1280, 720};

template <class T>
T orExit(Result<T> result, const char* what) {
  if (!result) {
    std::fprintf(stderr, "hair pass bench: %s: %s\n", what, result.error().message.c_str());
    std::exit(1);
  }
  return std::move(*result);
}

void orExit(Result<void> result, const char* what) {
  if (!result) {
    std::fprintf(stderr, "hair pass bench: %s: %s\n", what, result.error().message.c_str());
    std::exit(1);
  }
}

struct Groom {
  Buffer positions;
  Buffer tangents;
};

Groom makeGroom(const Device& device) {
  std::vector<glm::vec4> positions, tangents;
  positions.reserve(kStrands * kVertices);
  const float golden = std::numbers::pi_v<float> * (3.0f - std::sqrt(5.0f));
  for (std::uint32_t s = 0; s < kStrands; ++s) {
    // Roots spread evenly over the upper half-sphere (Fibonacci lattice), falling outwards then down.
    const float y = 1.0f - float(s) / float(kStrands);
    const float ring = std::sqrt(1.0f - y * y);
    const float azimuth = golden * float(s);
    const glm::vec3 normal(ring * std::cos(azimuth), y, ring * std::sin(azimuth));
    const glm::vec3 root = 0.1f * normal;
    const glm::vec3 outwards = glm::normalize(glm::vec3(normal.x, 0.0f, normal.z) + glm::vec3(1e-3f));
    std::vector<glm::vec3> points(kVertices);
    for (std::uint32_t i = 0; i < kVertices; ++i) {
      const float t = float(i) / float(kVertices - 1);
      // A little out along the scalp normal, then down and outwards past the sphere.
      points[i] = root + t * (0.04f * normal + glm::vec3(0.0f, -0.3f, 0.0f) + 0.08f * t * outwards);
    }
    for (std::uint32_t i = 0; i < kVertices; ++i) {
      const glm::vec3 tangent = glm::normalize(points[std::min(i + 1, kVertices - 1)] - points[i == 0 ? 0 : i - 1]);
      positions.emplace_back(points[i], float(i) / float(kVertices - 1));
      tangents.emplace_back(tangent, 0.0f);
    }
  }
  const auto usage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer;
  return {Buffer::withData(device, std::as_bytes(std::span(positions)), usage),
          Buffer::withData(device, std::as_bytes(std::span(tangents)), usage)};
}

constexpr int kRibbonWidth = 800;  // µm
constexpr int kLineWidth = 400;

struct Setup {
  std::unique_ptr<RenderTarget> target;
  std::unique_ptr<HairLightingPass> lighting;
  std::unique_ptr<HairPass> pass;
};

struct Shared {
  std::unique_ptr<Device> device;
  std::unique_ptr<MarschnerLut> lut;
  std::unique_ptr<HairShadowPass> shadows;  // none: the empty map
  Groom groom;
  std::map<int, Setup> setups;

  Shared() {
    device = orExit(Device::create(deviceSettingsFromEnvironment()), "device");
    lut = std::make_unique<MarschnerLut>(orExit(MarschnerLut::create(*device, blondeHairParams()), "LUT"));
    shadows = orExit(HairShadowPass::create(*device), "shadows");
    groom = makeGroom(*device);
  }

  Setup& setup(vk::SampleCountFlagBits samples, std::size_t lights, int widthMicrometres) {
    auto [it, inserted] = setups.try_emplace(widthMicrometres * 100 + int(samples) * 10 + int(lights));
    if (!inserted) return it->second;
    it->second.target = std::make_unique<RenderTarget>(*device, RenderTargetSettings{kExtent, samples});
    it->second.lighting =
        orExit(HairLightingPass::create(*device, *lut, *shadows, groom.positions, groom.tangents, kStrands, kVertices),
               "hair lighting");
    it->second.pass = orExit(HairPass::create(*device, {.colorFormat = RenderTarget::kHdrFormat,
                                                        .depthFormat = RenderTarget::kDepthFormat,
                                                        .samples = samples}),
                             "hair pass");
    orExit(it->second.pass->setStrands({.positions = *groom.positions.buffer(),
                                        .tangents = *groom.tangents.buffer(),
                                        .radiance = *it->second.lighting->radiance().buffer(),
                                        .strandCount = kStrands,
                                        .verticesPerStrand = kVertices}),
           "strands");
    FrameInput frame{
        .camera = {.position = {0.0f, -0.05f, 0.6f}, .target = {0.0f, -0.05f, 0.0f}},
        .lights = {DirectionalLight{.direction = glm::normalize(glm::vec3(0.4f, 0.6f, 0.7f)), .intensity = 2.0f},
                   DirectionalLight{.direction = glm::normalize(glm::vec3(-0.2f, 0.3f, -0.9f)), .intensity = 1.0f}}};
    frame.lights.resize(lights);
    const float aspect = float(kExtent.width) / float(kExtent.height);
    orExit(it->second.lighting->update(frame.camera.projection(aspect) * frame.camera.view(), frame.lights,
                                       frame.ambient, shadows->uniforms()),
           "lighting");
    orExit(it->second.pass->update(frame, kExtent,
                                   HairGroomSettings{.width = float(widthMicrometres) * 1e-6f, .opacity = 0.9f}),
           "update");
    return it->second;
  }
};

Shared& shared() {
  static Shared instance;
  return instance;
}

void frame(const Device& device, const RenderTarget& target, const Setup* hair) {
  const HairPass* pass = hair ? hair->pass.get() : nullptr;
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    if (hair) hair->lighting->record(commands);
    if (pass) pass->record(commands);
    target.beginScene(commands, {0.02f, 0.02f, 0.03f, 1.0f});
    if (pass) pass->draw(commands);
    commands.endRendering();
  });
}

vk::SampleCountFlagBits samplesOf(const benchmark::State& state) {
  return state.range(0) == 4 ? vk::SampleCountFlagBits::e4 : vk::SampleCountFlagBits::e1;
}

void BM_EmptyFrame(benchmark::State& state) {
  Setup& setup = shared().setup(samplesOf(state), std::size_t(state.range(1)), kRibbonWidth);
  for (auto _ : state) frame(*shared().device, *setup.target, nullptr);
}

void BM_HairFrame(benchmark::State& state) {
  Setup& setup = shared().setup(samplesOf(state), std::size_t(state.range(1)), int(state.range(2)));
  for (auto _ : state) frame(*shared().device, *setup.target, &setup);
  state.counters["triangles"] = double(setup.pass->ribbonIndexCount() / 3);
  const HairPrimitiveChoice choice = setup.pass->lastChoice();
  state.counters["lines"] = choice.primitive == HairPrimitive::kLines ? 1.0 : 0.0;
  state.counters["uncovered_by_lines"] = choice.uncoveredByLines;
}

BENCHMARK(BM_EmptyFrame)->Args({1, 0})->Args({4, 0})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_HairFrame)
    ->Args({1, 2, kRibbonWidth})
    ->Args({4, 2, kRibbonWidth})
    ->Args({1, 0, kRibbonWidth})
    ->Args({1, 2, kLineWidth})
    ->Args({4, 2, kLineWidth})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
