// Frame time of the default scene's head on the device mane picks (lavapipe without a GPU), against
// baselines measured in the same run: the same passes with nothing to draw (clear + output pass),
// and the same head shaded Lambert instead of skin. docs/performance.md reports the ratios, which
// are steadier across machines than milliseconds. The hair is not drawn (no guides are handed to
// the renderer), nor the fins and the furred bunny.
//
//   BM_NaluFrame/scene:0: nothing drawn; scene:1: the head, Lambert; scene:2: the head, skin
//   (pre-integrated diffuse, blurred normals, Kelemen/Szirmay-Kalos specular); scene:3 and 4:
//   skin with texture-space diffusion at 1024² and 2048² (irradiance, 12 blurs, then the head);
//   scene:5: pre-integrated skin with depth-map translucency (the light's depth map, then the
//   head reading it); scene:6: the same with the voxel thickness table (N = 32, built before
//   the timed frames).
//
//   BM_TranslucentCube/method:0..2: scenes/translucent_cube.json at 1280×720, its cube drawn
//   without translucency (the baseline), with the depth-map method and with the voxel table
//   (N = 32, built before the timed frames).
//
//   BM_EnvironmentPreparation/stage:0..3: what a scene's environment costs when it is set (once
//   per environment): the 1k Venice panorama resampled into a 256-texel cube (CPU), that cube's
//   irradiance projected on nine harmonics on the CPU (the reference), the cube uploaded with its
//   mips and its specular chain baked (GPU, 8 levels from 128 texels), and the harmonics
//   projected on the GPU (what the renderer runs).
//
//   build/release/bench/mane_render_bench --benchmark_min_time=2

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "render/environment/harmonics_projection.hpp"
#include "render/environment/specular_chain.hpp"
#include "render/environment/spherical_harmonics.hpp"
#include "render/renderer.hpp"
#include "scenes/assets.hpp"
#include "scenes/environment_image.hpp"
#include "scenes/world.hpp"

namespace {

using namespace mane;

render::Device& device() {
  static std::unique_ptr<render::Device> instance = [] {
    auto created = render::Device::create(render::deviceSettingsFromEnvironment());
    if (!created) {
      std::fprintf(stderr, "render bench: %s\n", created.error().message.c_str());
      std::exit(1);
    }
    return std::move(*created);
  }();
  return *instance;
}

scenes::World loadWorld(const char* file) {
  auto scene = scenes::loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / file);
  auto resolver = scenes::AssetResolver::createDefault();
  if (!scene || !resolver) {
    std::fprintf(stderr, "render bench: cannot load scenes/%s\n", file);
    std::exit(1);
  }
  auto world = scenes::World::create(std::move(*scene), *resolver);
  if (!world) {
    std::fprintf(stderr, "render bench: %s\n", world.error().message.c_str());
    std::exit(1);
  }
  return std::move(*world);
}

// Renders `statics` with `frame` for every iteration of `state`.
void renderFrames(benchmark::State& state, const render::StaticScene& statics, const render::FrameInput& frame,
                  std::uint32_t samples) {
  auto renderer = render::Renderer::create(device(), {.extent = {1280, 720}, .msaaSamples = samples});
  if (!renderer || !(*renderer)->setScene(statics)) return state.SkipWithError("renderer setup failed");
  // Untimed: first-use work (the voxel table's build, pipeline compiles).
  if (!(*renderer)->render(frame)) return state.SkipWithError("render failed");
  for (auto _ : state)
    if (!(*renderer)->render(frame)) return state.SkipWithError("render failed");
  state.SetLabel(device().info().name);
}

// state.range(0): 0 draws nothing (the baseline), 1 the head as Lambert, 2 as skin, 3 and 4 as
// texture-space skin (1024², 2048²), 5 and 6 skin with translucency from the depth map and from
// the voxel table (N = 32). range(1): MSAA samples.
void BM_NaluFrame(benchmark::State& state) {
  static const scenes::World world = loadWorld("nalu.json");
  render::StaticScene statics = world.staticScene();
  render::FrameInput frame = world.frameInput();
  // The head alone: the instances drawn with skin (not the fins or the furred bunny).
  const auto skin = [&](std::size_t material) {
    return statics.materials[material].shading == render::SurfaceShading::kSkin;
  };
  std::erase_if(frame.instances, [&](const render::MeshInstance& instance) { return !skin(instance.material); });
  frame.post.godRays = 0.0f;  // timed in mane_post_bench and mane_frame_bench, not part of the head
  if (state.range(0) == 0) frame.instances.clear();
  for (render::MaterialData& material : statics.materials) {
    if (material.shading != render::SurfaceShading::kSkin) continue;
    if (state.range(0) == 1) material.shading = render::SurfaceShading::kLambert;
    if (state.range(0) == 3 || state.range(0) == 4) {
      material.skin.diffusion = render::SkinDiffusion::kTextureSpace;
      material.skin.irradianceSize = state.range(0) == 3 ? 1024 : 2048;
    }
    if (state.range(0) >= 5)
      material.translucency.method =
          state.range(0) == 5 ? render::TranslucencyMethod::kDepthMap : render::TranslucencyMethod::kVoxelLut;
  }
  renderFrames(state, statics, frame, static_cast<std::uint32_t>(state.range(1)));
}
BENCHMARK(BM_NaluFrame)
    ->ArgNames({"scene", "msaa"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({3, 1})
    ->Args({4, 1})
    ->Args({5, 1})
    ->Args({6, 1})
    ->Args({1, 4})
    ->Args({2, 4})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// state.range(0): the cube's TranslucencyMethod (0 none, 1 depth map, 2 voxel table).
void BM_TranslucentCube(benchmark::State& state) {
  static const scenes::World world = loadWorld("translucent_cube.json");
  render::StaticScene statics = world.staticScene();
  for (render::MaterialData& material : statics.materials)
    material.translucency.method = static_cast<render::TranslucencyMethod>(state.range(0));
  renderFrames(state, statics, world.frameInput(), 1);
}
BENCHMARK(BM_TranslucentCube)->ArgName("method")->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

// state.range(0): 0 the panorama → cube, 1 the harmonics on the CPU (the reference), 2 the upload
// and the specular chain, 3 the harmonics on the GPU (what the renderer runs).
void BM_EnvironmentPreparation(benchmark::State& state) {
  static const render::EquirectImage panorama = [] {
    const auto failed = [](const std::string& message) {
      std::fprintf(stderr, "render bench: %s\n", message.c_str());
      std::exit(1);
    };
    auto resolver = scenes::AssetResolver::createDefault();
    if (!resolver) failed(resolver.error().message);
    auto file = resolver->resolve("env/venice_sunset_1k.hdr");
    if (!file) failed(file.error().message);
    auto loaded = scenes::loadEnvironmentImage(*file);
    if (!loaded) failed(loaded.error().message);
    return loaded->image;
  }();
  static const render::CubeMap cube = render::cubeFromEquirect(panorama, 256);
  const vk::raii::Sampler sampler = render::makeLinearSampler(device(), vk::SamplerAddressMode::eClampToEdge, 1.0f);
  const render::Image uploaded = render::uploadCubeWithMips(device(), cube);
  for (auto _ : state) {
    if (state.range(0) == 0) benchmark::DoNotOptimize(render::cubeFromEquirect(panorama, 256));
    if (state.range(0) == 1) benchmark::DoNotOptimize(render::projectRadiance(cube));
    if (state.range(0) == 2) {
      const render::Image source = render::uploadCubeWithMips(device(), cube);
      benchmark::DoNotOptimize(render::SpecularChain::bake(device(), source, sampler, 128).has_value());
    }
    if (state.range(0) == 3) benchmark::DoNotOptimize(render::projectRadianceOnGpu(device(), uploaded).has_value());
  }
}
BENCHMARK(BM_EnvironmentPreparation)->ArgName("stage")->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
