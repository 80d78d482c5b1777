// The fur pass (render/passes/fur_pass.hpp) at the paper's scale: the Stanford bunny (69,451
// triangles) with 15 shells at 1280×720, against the bare bunny and an empty frame in the same run,
// and shells against shells + fins. The paper's figure (Ukaji et al., Table 1): a 34,832-vertex
// bunny with 15 layers at 137 fps on a GeForce GTX 285.
//
//   BM_EmptyFrame:         record, submit, wait: clear colour + depth only.
//   BM_FurFrame/<N>/<fins>: the pass's update (uniforms; the CPU silhouette search when fins are
//     on) and its draw: N = 1 is the bare bunny (the skin layer alone, the same shader), N = 15
//     the fur, with fins (1) or without (0).
//
// The bunny fills about half the frame's height. It has no uvs: they are a box projection by the
// normal's largest axis, the photo repeating every 3 cm (the bunny is 15 cm tall). Wall time
// around submit + wait (it agrees with timestamps for graphics, docs/lavapipe.md#timestamps). Needs
// ../shared/assets (the bunny and the cat-fur photo).
//
//   build/release/bench/mane_fur_bench --benchmark_min_time=2

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "render/passes/fur_pass.hpp"
#include "render/render_target.hpp"
#include "scenes/assets.hpp"
#include "scenes/image.hpp"
#include "scenes/obj_loader.hpp"

namespace {

using namespace mane;
using namespace mane::render;

constexpr vk::Extent2D kExtent{1280, 720};
constexpr float kFurThickness = 0.004f;  // h_b, metres: 4 mm of fur on a 15 cm bunny
constexpr float kUvPerMetre = 1.0f / 0.03f;

template <class T>
T orExit(Result<T> result, const char* what) {
  if (!result) {
    std::fprintf(stderr, "fur bench: %s: %s\n", what, result.error().message.c_str());
    std::exit(1);
  }
  return std::move(*result);
}

void orExit(Result<void> result, const char* what) {
  if (!result) {
    std::fprintf(stderr, "fur bench: %s: %s\n", what, result.error().message.c_str());
    std::exit(1);
  }
}

std::filesystem::path asset(const scenes::AssetResolver& resolver, const char* name) {
  return orExit(resolver.resolve(name), name);
}

struct Shared {
  std::unique_ptr<Device> device;
  std::unique_ptr<RenderTarget> target;
  scenes::Mesh bunny;
  scenes::Image photo;
  std::map<int, std::unique_ptr<FurPass>> passes;

  Shared() {
    device = orExit(Device::create(deviceSettingsFromEnvironment()), "device");
    target = std::make_unique<RenderTarget>(*device, RenderTargetSettings{kExtent});
    const scenes::AssetResolver resolver = orExit(scenes::AssetResolver::createDefault(), "asset resolver");
    bunny = orExit(scenes::loadObj(asset(resolver, "meshes/stanford-bunny.obj")), "bunny");
    if (bunny.normals.size() != bunny.positions.size()) scenes::computeSmoothNormals(bunny);
    scenes::boxProjectUvs(bunny, kUvPerMetre);
    photo = orExit(scenes::loadImage(asset(resolver, "fur/chelsea_forehead_fur_crop_110x80.png")), "photo");
  }

  FurPass& pass(std::uint32_t layers, bool fins) {
    auto& slot = passes[int(layers) * 2 + int(fins)];
    if (slot) return *slot;
    const TextureData texture{std::uint32_t(photo.width), std::uint32_t(photo.height), photo.rgba};
    slot = orExit(
        FurPass::create(
            *device, {.colorFormat = RenderTarget::kHdrFormat, .depthFormat = RenderTarget::kDepthFormat, .fins = fins},
            texture, {.layers = layers, .thickness = kFurThickness}),
        "fur pass");
    orExit(slot->setMesh(
               {.positions = bunny.positions, .normals = bunny.normals, .uvs = bunny.uvs, .indices = bunny.indices}),
           "bunny mesh");
    return *slot;
  }

  FurView view() const {
    const scenes::Bounds bounds = bunny.bounds();
    const glm::vec3 centre = bounds.centre();
    const Camera camera{.position = centre + glm::vec3(0.05f, 0.03f, 0.3f), .target = centre};
    const float aspect = float(kExtent.width) / float(kExtent.height);
    return {.viewProjection = camera.projection(aspect) * camera.view(),
            .eye = glm::vec4(camera.position, 1.0f),
            .extent = kExtent,
            .light = {.direction = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)), .intensity = 1.5f}};
  }
};

Shared& shared() {
  static Shared instance;
  return instance;
}

void BM_EmptyFrame(benchmark::State& state) {
  Shared& s = shared();
  for (auto _ : state) {
    s.device->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      s.target->beginScene(commands, {0.02f, 0.02f, 0.03f, 1.0f});
      commands.endRendering();
    });
  }
}

void BM_FurFrame(benchmark::State& state) {
  Shared& s = shared();
  FurPass& pass = s.pass(std::uint32_t(state.range(0)), state.range(1) != 0);
  const FurView view = s.view();
  for (auto _ : state) {
    orExit(pass.update(view), "update");
    s.device->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      s.target->beginScene(commands, {0.02f, 0.02f, 0.03f, 1.0f});
      pass.draw(commands);
      commands.endRendering();
    });
  }
  state.counters["triangles"] = double(s.bunny.triangleCount() * state.range(0) + 2 * pass.finCount());
  state.counters["fins"] = double(pass.finCount());
}

BENCHMARK(BM_EmptyFrame)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FurFrame)->Args({1, 0})->Args({15, 0})->Args({15, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
