// The HDR post chain (render/passes/post_pass.hpp) at 1280×720 against the output pass alone, in
// one run.
//
//   BM_OutputOnly: record, submit, wait: clear the HDR frame, then the output pass with the
//     defaults (linear exposure, no glow, no auto gain) — the frame without the chain.
//   BM_PostChain/<glow>/<auto gain>/<tone map>/<god rays>: the same with the chain's passes that
//     the arguments switch on (downsample, auto gain, four glow blurs, god rays around a light at
//     frame uv (0.5, 0.4): bright pass, polar transform, radial blur, inverse), the overlay they
//     hand to the output pass, and the specialised output pass (tone map 1: Reinhard).
//
// Counters, from GPU timestamps of the same frames (median of the iterations): each pass's
// milliseconds, and `vs_output` = (post passes + output) / output: what the chain costs relative to
// the output pass it extends. The HDR frame is a clear to an HDR colour: every pass here runs the
// same work whatever the pixels hold (no branch depends on them). Wall time around submit + wait.
//
//   build/release/bench/mane_post_bench --benchmark_min_time=2

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "render/gpu_timer.hpp"
#include "render/passes/output_pass.hpp"
#include "render/passes/post_pass.hpp"
#include "render/render_target.hpp"

namespace {

using namespace mane;
using namespace mane::render;

constexpr vk::Extent2D kExtent{1280, 720};

// What each frame times; the counters are named after them (name_ms).
constexpr PassName kClear("clear");
constexpr PassName kDownsample("downsample");
constexpr PassName kAutoGain("auto_gain");
constexpr PassName kGlow("glow");
constexpr PassName kGodRays("god_rays");
constexpr PassName kOverlay("overlay");
constexpr PassName kOutput("output");

struct Shared {
  std::unique_ptr<Device> device;
  std::unique_ptr<RenderTarget> target;
  std::unique_ptr<PostPass> post;
  std::unique_ptr<OutputPass> output;
  std::unique_ptr<GpuTimer> timer;

  Shared() {
    auto created = Device::create(deviceSettingsFromEnvironment());
    if (!created) {
      std::fprintf(stderr, "post bench: device: %s\n", created.error().message.c_str());
      std::exit(1);
    }
    device = std::move(*created);
    target = std::make_unique<RenderTarget>(*device, RenderTargetSettings{.extent = kExtent});
    post = std::make_unique<PostPass>(*device, target->hdr());
    output = std::make_unique<OutputPass>(*device, *target, *post);
    timer = std::make_unique<GpuTimer>(*device, 8);
  }
};

Shared& shared() {
  static Shared instance;
  return instance;
}

// One frame: the HDR clear, the post passes `settings` asks for, the output pass; each timed.
void frame(Shared& s, const PostSettings& settings) {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  s.device->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    s.timer->reset(commands);
    s.timer->begin(commands, kClear);
    s.target->beginScene(commands, {2.0f, 1.5f, 1.0f, 1.0f});
    commands.endRendering();
    s.timer->end(commands);
    transition(commands, s.target->hdr(), Layout::eColorAttachmentOptimal, Layout::eShaderReadOnlyOptimal,
               Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite,
               Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead);
    if (PostPass::runs(settings)) {
      s.timer->begin(commands, kDownsample);
      s.post->recordDownsample(commands);
      s.timer->end(commands);
      if (settings.autoGain) {
        s.timer->begin(commands, kAutoGain);
        s.post->recordAutoGain(commands, settings, 1.0f);
        s.timer->end(commands);
      }
      if (settings.glowStrength > 0.0f) {
        s.timer->begin(commands, kGlow);
        s.post->recordGlow(commands);
        s.timer->end(commands);
      }
      if (settings.godRays > 0.0f) {
        s.timer->begin(commands, kGodRays);
        s.post->recordGodRays(commands, settings, {0.5f, 0.4f});
        s.timer->end(commands);
      }
      s.timer->begin(commands, kOverlay);
      s.post->recordHandOff(commands, settings, 1.0f);
      s.timer->end(commands);
    }
    transition(commands, s.target->output(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
               Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
    s.timer->begin(commands, kOutput);
    s.output->record(commands, *s.target, 1.0f, settings);
    s.timer->end(commands);
  });
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

void run(benchmark::State& state, const PostSettings& settings) {
  Shared& s = shared();
  frame(s, settings);  // warm: pipelines made, caches filled
  std::map<PassName, std::vector<double>> times;
  for (auto _ : state) {
    frame(s, settings);
    for (const PassTiming& timing : s.timer->results()) times[timing.pass].push_back(timing.milliseconds);
  }
  double post = 0.0;
  for (const auto& [pass, values] : times) {
    state.counters[std::string(pass.name()) + "_ms"] = median(values);
    if (pass != kClear) post += median(values);
  }
  if (times.count(kOutput)) state.counters["vs_output"] = post / median(times[kOutput]);
}

void BM_OutputOnly(benchmark::State& state) {
  run(state, PostSettings{});
}

void BM_PostChain(benchmark::State& state) {
  run(state, PostSettings{.toneMapping = state.range(2) ? ToneMapping::kReinhard : ToneMapping::kLinear,
                          .autoGain = state.range(1) != 0,
                          .glowStrength = state.range(0) ? 0.5f : 0.0f,
                          .godRays = state.range(3) ? 0.5f : 0.0f});
}

BENCHMARK(BM_OutputOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PostChain)
    ->Args({1, 1, 1, 0})
    ->Args({0, 1, 1, 0})
    ->Args({1, 0, 0, 0})
    ->Args({0, 0, 1, 0})
    ->Args({0, 0, 0, 1})
    ->Args({1, 1, 1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
