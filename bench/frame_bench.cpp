// The whole default frame: scenes/nalu.json through scenes::FrameLoop as `mane render` runs it —
// World::advance (animation and simulation, 2 threads), the cloth and hair guides handed to the
// renderer, then every pass with the scene's own post settings — at 1280×720 on the device mane
// picks (lavapipe without a GPU). Each iteration is one frame of 1/30 s, timed by the wall clock;
// the counters are medians over the iterations: frame_ms (the whole frame, and fps from it),
// sim_ms (World::advance), upload_ms (the hand-off to the renderer), refine_ms (the head's limit
// surface tessellated again for its new pose by World::refineForCamera, and re-uploaded), gpu_ms
// (the first pass's begin to the last one's end) and each pass's GPU time, the main pass
// (surfaces and furs, then the hair) also as the sum of its two halves.
//
//   BM_NaluFrame/variant:0  the scene as shipped (4,095 strands, pre-integrated skin), 1× MSAA
//   BM_NaluFrame/variant:1  the same at 4× MSAA (`mane render`'s default)
//   BM_NaluFrame/variant:2  texture-space diffusion (1024² irradiance) instead of pre-integrated skin
//   BM_NaluFrame/variant:3  deep opacity maps instead of opacity shadow maps
//   BM_NaluFrame/variant:4  50,000 dense strands from the same guides
//   BM_NaluFrame/variant:5  100,000 dense strands
//   BM_NaluFrame/variant:6  the furry creature without its shells and fins (FrameInput::furShells
//                           off: the bare mesh with the photo), to show what the fur costs
//   BM_NaluFrame/variant:7  the original Nalu demo's content: the scene without the creature
//   BM_NaluFrame/variant:8  the same, every hair segment drawn and shaded, hidden or not
//                           (RendererSettings::hideOccludedHair off)
//   BM_NaluFrame/variant:9  50,000 strands from 4× as far, through the level of detail
//   BM_NaluFrame/variant:10 the same, every strand drawn
//   BM_NaluFrame/variant:11 as shipped, under an environment (the Venice sunset panorama as
//                           timbury.json turns it): its irradiance on the surfaces, its
//                           background; its cost is this row over row 0
//   BM_NaluFrame/variant:12 as shipped without the surfaces' soft shadows
//                           (FrameInput::surfaceShadows off): their cost is row 0 over this row
//
// The same frame of scenes/robot.json: a glTF character skinned on the GPU (walking), its crest
// of hair and its cape simulated against it. The frozen rows empty the character's clips and
// morph tracks, so the body stands in its rest pose while the hair and the cloth are still
// simulated: the animated row over the frozen one is what the moving body costs.
//
//   BM_RobotFrame/variant:0  animated, 1× MSAA
//   BM_RobotFrame/variant:1  the body frozen, 1× MSAA
//   BM_RobotFrame/variant:2  animated, 4× MSAA (`mane render`'s default)
//   BM_RobotFrame/variant:3  the body frozen, 4× MSAA
//
// The same frame of scenes/clear_sailing.json: the sea (45 Gerstner waves on a projected grid
// of 100 × 150 cells, foam) and the 30 m ship floating on it, its cannon fired before the first
// frame so that its smoke is in every one. The row without the sea hands the renderer no ocean
// (the ship still floats): the first row over it is what the sea costs; the row without effects
// hands it no spray, smoke, rigging or debris (still simulated).
//
//   BM_ClearSailingFrame/variant:0  as shipped, 1× MSAA
//   BM_ClearSailingFrame/variant:1  the sea not drawn
//   BM_ClearSailingFrame/variant:2  the effects not drawn
//
//   build/release/bench/mane_frame_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "render/renderer.hpp"
#include "scenes/frame_loop.hpp"
#include "scenes/world.hpp"

namespace {

using namespace mane;

render::Device& device() {
  static std::unique_ptr<render::Device> instance = [] {
    auto created = render::Device::create(render::deviceSettingsFromEnvironment());
    if (!created) {
      std::fprintf(stderr, "frame bench: %s\n", created.error().message.c_str());
      std::exit(1);
    }
    return std::move(*created);
  }();
  return *instance;
}

enum Variant : int {
  kShipped,
  kMsaa4,
  kTextureSpace,
  kDeepOpacity,
  kStrands50k,
  kStrands100k,
  kNoFurShells,
  kDemoContent,
  kDemoContentEveryStrand,
  kStrands50kFar,             // from 4× the camera's distance: the level of detail draws about half of them
  kStrands50kFarEveryStrand,  // the same without the level of detail
  kEnvironment,               // lit by a panorama, which is also the background
  kNoSurfaceShadows           // the surfaces without their soft shadows
};

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// What a row changes in how the frame is rendered, the scene itself aside.
struct FrameOptions {
  unsigned msaaSamples = 1;
  bool hideOccludedHair = true;
  bool furShells = true;
  bool surfaceShadows = true;
  /// Untimed frames before the timed ones: first-use work (pipeline compiles, the diffusion's
  /// first irradiance), and for a moving body, the hair and cloth catching up with its motion.
  int untimedFrames = 1;
  /// Techniques other than the scene's own (none: as the scene says).
  std::function<void(render::StaticScene&)> editStatics;
  bool effects = true;      ///< false: the frames hand the renderer no particles, lines or debris
  bool fireCannon = false;  ///< fire the scene's cannon before the first frame
};

/// Each iteration: one frame of 1/30 s of `scene` through scenes::FrameLoop at 1280×720, timed by
/// the wall clock; the counters are the medians described at the top of this file.
void measureFrames(benchmark::State& state, scenes::Scene scene, const FrameOptions& options) {
  auto resolver = scenes::AssetResolver::createDefault();
  if (!resolver) return state.SkipWithError(resolver.error().message.c_str());
  auto world = scenes::World::create(std::move(scene), *resolver);
  if (!world) return state.SkipWithError(world.error().message.c_str());
  // Fallbacks (a missing asset) change what is measured: say so beside the figures.
  for (const std::string& note : world->notes()) std::fprintf(stderr, "note: %s\n", note.c_str());

  if (options.fireCannon && !world->fireCannon()) return state.SkipWithError("the scene has no cannon");
  render::StaticScene statics = world->staticScene();
  if (options.editStatics) options.editStatics(statics);
  auto renderer = render::Renderer::create(device(), {.extent = {1280, 720},
                                                      .msaaSamples = options.msaaSamples,
                                                      .hideOccludedHair = options.hideOccludedHair});
  if (!renderer) return state.SkipWithError(renderer.error().message.c_str());
  auto loop = scenes::FrameLoop::create(*world, **renderer, {.imageSize = {1280, 720}, .threads = 2});
  if (!loop) return state.SkipWithError(loop.error().message.c_str());
  if (auto set = loop->setScene(statics); !set) return state.SkipWithError(set.error().message.c_str());

  constexpr double kFrameSeconds = 1.0 / 30.0;
  const auto since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<double> simulationMs, uploadMs, refineMs;
  const auto frame = [&](bool timed) -> Result<std::vector<render::PassTiming>> {
    if (auto advanced = loop->advance(kFrameSeconds); !advanced) return std::unexpected(advanced.error());
    render::FrameInput input = world->frameInput();
    input.post.frameSeconds = float(kFrameSeconds);
    if (!options.furShells) input.furShells = false;
    if (!options.surfaceShadows) input.surfaceShadows = false;
    if (!options.effects) input.effects = {};
    auto timings = loop->renderFrame(input);
    if (timed) {
      const scenes::FrameStageTimes& stages = loop->lastStageTimes();
      simulationMs.push_back(stages.simulateMs);
      uploadMs.push_back(stages.uploadMs);
      refineMs.push_back(stages.refineMs);
    }
    return timings;
  };
  for (int untimed = 0; untimed < options.untimedFrames; ++untimed)
    if (auto done = frame(false); !done) return state.SkipWithError(done.error().message.c_str());

  std::vector<double> frameMs, gpuMs, hiddenShare;
  using render::PassName;
  std::vector<PassName> order;
  std::map<PassName, std::vector<double>> passMs;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto timings = frame(true);
    if (!timings) return state.SkipWithError(timings.error().message.c_str());
    frameMs.push_back(since(start));
    // The main pass: one timer where the skin is deferred (the Renderer shades the hair before
    // it), else its two halves, the surfaces' and the hair's (each ends its rendering, so
    // lavapipe's rasterizing falls within its own timer), summed.
    double frameEnd = 0.0, mainPass = 0.0;
    for (const render::PassTiming& timing : *timings) {
      frameEnd = std::max(frameEnd, timing.startMilliseconds + timing.milliseconds);
      const PassName pass = timing.pass;
      if (pass == PassName::kSurfaces || pass == PassName::kHair || pass == PassName::kMainPass)
        mainPass += timing.milliseconds;
      if (pass == PassName::kMainPass) continue;
      if (!passMs.contains(pass)) order.push_back(pass);
      passMs[pass].push_back(timing.milliseconds);
    }
    passMs[PassName::kMainPass].push_back(mainPass);
    double hidden = 0.0, vertices = 0.0;
    const std::vector<render::HairPrimitiveChoice> choices = (*renderer)->hairChoices();
    for (std::size_t g = 0; g < statics.grooms.size(); ++g) {
      hidden += choices[g].hiddenVertices;
      vertices += double(statics.grooms[g].layout.strands.size()) * statics.grooms[g].layout.vertexCount;
    }
    hiddenShare.push_back(vertices > 0.0 ? hidden / vertices : 0.0);
    gpuMs.push_back(frameEnd);
  }
  state.counters["frame_ms"] = median(frameMs);
  state.counters["fps"] = 1000.0 / median(frameMs);
  state.counters["sim_ms"] = median(simulationMs);
  state.counters["upload_ms"] = median(uploadMs);
  state.counters["refine_ms"] = median(refineMs);
  state.counters["gpu_ms"] = median(gpuMs);
  state.counters["hidden_hair"] = median(hiddenShare);  // share of the dense vertices hidden
  order.push_back(PassName::kMainPass);
  for (const PassName pass : order) {
    std::string name(pass.name());
    std::replace(name.begin(), name.end(), ' ', '_');
    state.counters[name + "_ms"] = median(passMs[pass]);
  }
  std::size_t strands = 0;
  for (const render::HairGroomData& groom : statics.grooms) strands += groom.layout.strands.size();
  state.counters["strands"] = double(strands);
  state.SetLabel(device().info().name);
}

void BM_NaluFrame(benchmark::State& state) {
  const auto variant = static_cast<Variant>(state.range(0));
  auto scene = scenes::loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json");
  if (!scene) return state.SkipWithError(scene.error().message.c_str());
  if (variant == kDemoContent || variant == kDemoContentEveryStrand)
    std::erase_if(scene->meshes, [](const scenes::MeshInstance& mesh) { return mesh.name == "bunny"; });
  const bool far = variant == kStrands50kFar || variant == kStrands50kFarEveryStrand;
  if (far) scene->camera.position = scene->camera.target + (scene->camera.position - scene->camera.target) * 4.0f;
  for (scenes::Groom& groom : scene->grooms) {
    if (variant == kStrands50k || far) groom.rendering.denseStrands = 50'000;
    if (variant == kStrands100k) groom.rendering.denseStrands = 100'000;
    if (variant == kStrands50kFarEveryStrand) groom.rendering.settings.lodPixelWidth = 0.0f;
  }
  if (variant == kEnvironment)
    scene->environment = scenes::Environment{.file = "env/venice_sunset_1k.hdr", .rotationDegrees = -40.0f};
  measureFrames(state, std::move(*scene),
                {.msaaSamples = variant == kMsaa4 ? 4u : 1u,
                 .hideOccludedHair = variant != kDemoContentEveryStrand,
                 .furShells = variant != kNoFurShells,
                 .surfaceShadows = variant != kNoSurfaceShadows,
                 .editStatics = [variant](render::StaticScene& statics) {
                   for (render::MaterialData& material : statics.materials)
                     if (variant == kTextureSpace && material.shading == render::SurfaceShading::kSkin)
                       material.skin.diffusion = render::SkinDiffusion::kTextureSpace;
                   if (variant == kDeepOpacity) statics.hairShadows.mode = render::HairShadowMode::kDeepOpacityMap;
                 }});
}

BENCHMARK(BM_NaluFrame)
    ->ArgName("variant")
    ->DenseRange(kShipped, kNoSurfaceShadows)
    ->Iterations(9)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

enum RobotVariant : int { kRobotAnimated, kRobotFrozen, kRobotAnimatedMsaa4, kRobotFrozenMsaa4 };

void BM_RobotFrame(benchmark::State& state) {
  const auto variant = static_cast<RobotVariant>(state.range(0));
  auto scene = scenes::loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "robot.json");
  if (!scene) return state.SkipWithError(scene.error().message.c_str());
  if (variant == kRobotFrozen || variant == kRobotFrozenMsaa4)
    for (scenes::CharacterInstance& character : scene->characters) {
      character.clips.clear();
      character.morphs.clear();
    }
  // Half a second untimed: past the first-use work, with the crest and the cape already swinging
  // with the walk rather than starting from the settled rest.
  measureFrames(state, std::move(*scene),
                {.msaaSamples = variant == kRobotAnimatedMsaa4 || variant == kRobotFrozenMsaa4 ? 4u : 1u,
                 .untimedFrames = 15});
}

BENCHMARK(BM_RobotFrame)
    ->ArgName("variant")
    ->DenseRange(kRobotAnimated, kRobotFrozenMsaa4)
    ->Iterations(9)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

enum TimburyVariant : int { kTimburyShipped, kTimburyWithoutGlasses };

// Timbury under the Venice panorama, with and without his glasses: what the lenses' refraction and
// the frame cost, as the ratio of the two.
void BM_TimburyFrame(benchmark::State& state) {
  auto scene = scenes::loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "timbury.json");
  if (!scene) return state.SkipWithError(scene.error().message.c_str());
  if (state.range(0) == kTimburyWithoutGlasses) scene->glasses.clear();
  measureFrames(state, std::move(*scene), {});
}

BENCHMARK(BM_TimburyFrame)
    ->ArgName("variant")
    ->DenseRange(kTimburyShipped, kTimburyWithoutGlasses)
    ->Iterations(9)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

enum ClearSailingVariant : int { kClearSailingShipped, kClearSailingWithoutSea, kClearSailingWithoutEffects };

void BM_ClearSailingFrame(benchmark::State& state) {
  auto scene = scenes::loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "clear_sailing.json");
  if (!scene) return state.SkipWithError(scene.error().message.c_str());
  const bool withoutSea = state.range(0) == kClearSailingWithoutSea;
  measureFrames(state, std::move(*scene),
                {.editStatics =
                     [withoutSea](render::StaticScene& statics) {
                       if (withoutSea) statics.ocean.reset();
                     },
                 .effects = state.range(0) != kClearSailingWithoutEffects,
                 .fireCannon = true});
}

BENCHMARK(BM_ClearSailingFrame)
    ->ArgName("variant")
    ->DenseRange(kClearSailingShipped, kClearSailingWithoutEffects)
    ->Iterations(9)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
