// Frame time of the default scene's head on the device mane picks (lavapipe here), against
// baselines measured in the same run: the same passes with nothing to draw (clear + output
// pass), and the same head shaded Lambert instead of skin. The README reports the ratios, which
// are steadier across machines than milliseconds. The hair is not drawn (no guides are handed
// to the renderer).
//
//   BM_NaluFrame/scene:0: nothing drawn; scene:1: the head, Lambert; scene:2: the head, skin
//   (pre-integrated diffuse, blurred normals, Kelemen/Szirmay-Kalos specular); scene:3 and 4:
//   skin with texture-space diffusion at 1024² and 2048² (irradiance, 12 blurs, then the head).
//
//   build/release/bench/mane_render_bench --benchmark_min_time=2

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

#include "render/renderer.hpp"
#include "scenes/world.hpp"

namespace {

using namespace mane;

struct Fixture {
  std::unique_ptr<render::Device> device;
  std::optional<scenes::World> world;
};

Fixture& fixture() {
  static Fixture instance = [] {
    Fixture result;
    auto device = render::Device::create(render::deviceSettingsFromEnvironment());
    if (!device) {
      std::fprintf(stderr, "render bench: %s\n", device.error().message.c_str());
      std::exit(1);
    }
    result.device = std::move(*device);
    auto scene = scenes::loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json");
    auto resolver = scenes::AssetResolver::createDefault();
    if (!scene || !resolver) {
      std::fprintf(stderr, "render bench: cannot load scenes/nalu.json\n");
      std::exit(1);
    }
    auto world = scenes::World::create(std::move(*scene), *resolver);
    if (!world) {
      std::fprintf(stderr, "render bench: %s\n", world.error().message.c_str());
      std::exit(1);
    }
    result.world = std::move(*world);
    return result;
  }();
  return instance;
}

// state.range(0): 0 draws nothing (the baseline), 1 the head as Lambert, 2 as skin, 3 and 4 as
// texture-space skin (1024², 2048²). range(1): MSAA samples.
void BM_NaluFrame(benchmark::State& state) {
  Fixture& f = fixture();
  auto renderer = render::Renderer::create(
      *f.device, {.extent = {1280, 720}, .msaaSamples = static_cast<std::uint32_t>(state.range(1))});
  render::StaticScene statics = f.world->staticScene();
  for (render::MaterialData& material : statics.materials) {
    if (state.range(0) == 1) material.shading = render::SurfaceShading::kLambert;
    if (state.range(0) >= 3) {
      material.skin.diffusion = render::SkinDiffusion::kTextureSpace;
      material.skin.irradianceSize = state.range(0) == 3 ? 1024 : 2048;
    }
  }
  if (!renderer || !(*renderer)->setScene(statics)) return state.SkipWithError("renderer setup failed");
  render::FrameInput frame = f.world->frameInput();
  if (state.range(0) == 0) frame.instances.clear();
  for (auto _ : state)
    if (!(*renderer)->render(frame)) return state.SkipWithError("render failed");
  state.SetLabel(f.device->info().name);
}
BENCHMARK(BM_NaluFrame)
    ->ArgNames({"scene", "msaa"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({3, 1})
    ->Args({4, 1})
    ->Args({1, 4})
    ->Args({2, 4})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
