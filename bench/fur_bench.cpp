// The fur pass (render/passes/fur_pass.hpp) at the paper's scale: the Stanford bunny (69,451
// triangles) with 15 shells at 1280×720, against the bare bunny and an empty frame in the same run,
// and shells against shells + fins. The paper's figure (Ukaji et al., Table 1): a 34,832-vertex
// bunny with 15 layers at 137 fps on a GeForce GTX 285.
//
//   BM_EmptyFrame:         record, submit, wait: clear colour + depth only.
//   BM_FurFrame/<N>/<fins>: the pass's update (uniforms; the CPU silhouette search when fins are
//     on) and its draw: N = 1 is the bare bunny (the skin layer alone, the same shader), N = 15
//     the fur, with fins (1) or without (0). Both faces drawn, every shell.
//   BM_NaluBunny/<case>: the bunny as scenes/nalu.json draws it, small on screen (simplified to
//     3,000 triangles, scaled by 0.7, 0.71 m from the camera, 30° field of view: about 200 pixels
//     tall, its 4 mm fur about 8 pixels), with fins: case 0 the skin layer alone, 1 all 15 shells
//     and both faces, 2 the back faces culled (the material's double_sided: false), 3 also one
//     shell per pixel of fur height (pixels_per_layer 1), as nalu.json ships.
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
#include "scenes/mesh_simplify.hpp"
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
  scenes::Mesh smallBunny;  // as nalu.json simplifies it
  scenes::Image photo;
  std::map<int, std::unique_ptr<FurPass>> passes;
  std::unique_ptr<FurPass> naluPass;

  Shared() {
    device = orExit(Device::create(deviceSettingsFromEnvironment()), "device");
    target = std::make_unique<RenderTarget>(*device, RenderTargetSettings{kExtent});
    const scenes::AssetResolver resolver = orExit(scenes::AssetResolver::createDefault(), "asset resolver");
    bunny = orExit(scenes::loadObj(asset(resolver, "meshes/stanford-bunny.obj")), "bunny");
    if (bunny.normals.size() != bunny.positions.size()) scenes::computeSmoothNormals(bunny);
    scenes::boxProjectUvs(bunny, kUvPerMetre);
    smallBunny = orExit(scenes::simplifyMesh(bunny, {.targetTriangles = 3000}), "simplified bunny").mesh;
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

  FurPass& naluBunny() {
    if (naluPass) return *naluPass;
    const TextureData texture{std::uint32_t(photo.width), std::uint32_t(photo.height), photo.rgba};
    naluPass = orExit(
        FurPass::create(
            *device, {.colorFormat = RenderTarget::kHdrFormat, .depthFormat = RenderTarget::kDepthFormat, .fins = true},
            texture, {.layers = 15, .thickness = kFurThickness}),
        "fur pass");
    orExit(naluPass->setMesh({.positions = smallBunny.positions,
                              .normals = smallBunny.normals,
                              .uvs = smallBunny.uvs,
                              .indices = smallBunny.indices}),
           "small bunny mesh");
    return *naluPass;
  }

  // nalu.json's bunny: scaled by 0.7, seen from 0.71 m with a 30° field of view.
  FurView naluView() const {
    const glm::vec3 centre = smallBunny.bounds().centre() * 0.7f;
    const Camera camera{.position = centre + glm::vec3(0.48f, 0.16f, 0.5f),
                        .target = centre,
                        .verticalFovRadians = glm::radians(30.0f)};
    const float aspect = float(kExtent.width) / float(kExtent.height);
    return {.model = glm::mat4(glm::mat3(0.7f)),
            .viewProjection = camera.projection(aspect) * camera.view(),
            .eye = glm::vec4(camera.position, 1.0f),
            .extent = kExtent,
            .light = {.direction = glm::normalize(glm::vec3(-0.25f, 0.4f, 0.88f)), .intensity = 2.2f}};
  }

  FurView view() const {
    const scenes::Bounds bounds = bunny.bounds();
    const glm::vec3 centre = bounds.centre();
    const Camera camera{.position = centre + glm::vec3(0.05f, 0.03f, 0.3f), .target = centre};
    const float aspect = float(kExtent.width) / float(kExtent.height);
    return {.viewProjection = camera.projection(aspect) * camera.view(),
            .eye = glm::vec4(camera.position, 1.0f),
            .extent = kExtent,
            .light = {.direction = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)), .intensity = 1.5f},
            .look = {.pixelsPerLayer = 0.0f}};
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

// The pass's update and its draw into a cleared frame, submitted and waited for, per iteration.
void drawFrames(benchmark::State& state, FurPass& pass, const FurView& view) {
  Shared& s = shared();
  for (auto _ : state) {
    orExit(pass.update(view), "update");
    s.device->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      s.target->beginScene(commands, {0.02f, 0.02f, 0.03f, 1.0f});
      pass.draw(commands);
      commands.endRendering();
    });
  }
}

void BM_FurFrame(benchmark::State& state) {
  Shared& s = shared();
  FurPass& pass = s.pass(std::uint32_t(state.range(0)), state.range(1) != 0);
  const FurView view = s.view();
  drawFrames(state, pass, view);
  state.counters["triangles"] = double(s.bunny.triangleCount() * state.range(0) + 2 * pass.finCount());
  state.counters["fins"] = double(pass.finCount());
}

void BM_NaluBunny(benchmark::State& state) {
  Shared& s = shared();
  FurPass& pass = s.naluBunny();
  if (auto set = pass.setShells(state.range(0) == 0 ? 1 : 15, kFurThickness); !set)
    return state.SkipWithError(set.error().message.c_str());
  FurView view = s.naluView();
  view.look.doubleSided = state.range(0) < 2;
  view.look.pixelsPerLayer = state.range(0) == 3 ? 1.0f : 0.0f;
  drawFrames(state, pass, view);
  state.counters["shells"] = double(pass.drawnLayers());
  state.counters["fins"] = double(pass.finCount());
}

BENCHMARK(BM_EmptyFrame)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_NaluBunny)->ArgName("case")->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FurFrame)->Args({1, 0})->Args({15, 0})->Args({15, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
