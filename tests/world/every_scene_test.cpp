// Every scene file shipped in scenes/ loads and renders one small frame: scene file → World (assets
// through the resolver, procedural fallbacks where they are missing) → Renderer on lavapipe with
// validation on → one 96×54 frame with the scene's own post settings, its cloth, hair and fur
// uploaded as `mane render` does.
//
// The oracle is independent of how the scene should look: a frame with nothing drawn is one
// colour (the background, tone-mapped; glow and auto gain keep a uniform image uniform, and a
// dark background emits no god rays), so the frame must hold a clear share of pixels away from
// its most common colour. A smoke test, kept fast: no settling before the first frame, grooms
// drawn with at most kSmokeDenseStrands strands, voxel translucency tables of kSmokeVoxelResolution³
// cells, the subdivided meshes tessellated for the small frame. (Malformed scene files are
// tests/scenes/scene_tests.cpp's and the CLI test's.) Two more frames of each scene's animation
// must compile no shader on lavapipe, and the three frames must match their golden hashes.

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "physics/hash.hpp"
#include "render/renderer.hpp"
#include "scenes/frame_loop.hpp"
#include "scenes/world.hpp"
#include "tests/support/jit_compile_counter.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

constexpr std::uint32_t kWidth = 96;
constexpr std::uint32_t kHeight = 54;
/// The ponytail asks for 50,000 strands; about a quarter of the default 4,095 shows hair as well.
constexpr int kSmokeDenseStrands = 1000;
/// Voxel translucency tables cost O(N⁴) to build on the first frame; 16 cells per axis still
/// exercise them.
constexpr int kSmokeVoxelResolution = 16;
/// A 96×54 frame with a sphere, a head or a chess board in it: some hundreds of pixels at the
/// least; a blank frame has none.
constexpr double kMinDrawnFraction = 0.01;

std::vector<std::filesystem::path> sceneFiles() {
  std::vector<std::filesystem::path> files;
  for (const auto& item : std::filesystem::directory_iterator(std::filesystem::path(MANE_SOURCE_DIR) / "scenes"))
    if (item.path().extension() == ".json" && item.path().filename() != "assets.json") files.push_back(item.path());
  std::sort(files.begin(), files.end());
  return files;
}

class EveryScene : public testing::VulkanTest, public ::testing::WithParamInterface<std::filesystem::path> {};

// Share of pixels whose RGB differs by more than `tolerance` (summed over channels) from the
// frame's most common colour.
double fractionAwayFromMostCommonColour(const std::vector<std::uint8_t>& rgba, int tolerance) {
  std::map<std::uint32_t, std::size_t> counts;
  for (std::size_t i = 0; i < rgba.size(); i += 4) ++counts[rgba[i] | rgba[i + 1] << 8 | rgba[i + 2] << 16];
  const std::uint32_t common = std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
                                 return a.second < b.second;
                               })->first;
  std::size_t away = 0;
  for (std::size_t i = 0; i < rgba.size(); i += 4) {
    const int difference = std::abs(int(rgba[i]) - int(common & 0xff)) +
                           std::abs(int(rgba[i + 1]) - int(common >> 8 & 0xff)) +
                           std::abs(int(rgba[i + 2]) - int(common >> 16 & 0xff));
    if (difference > tolerance) ++away;
  }
  return double(away) / double(rgba.size() / 4);
}

// The scene file as a World at the smoke test's size, a renderer holding its statics, and the
// frame loop over both (one simulation thread).
struct SmokeScene {
  std::unique_ptr<World> world;
  std::unique_ptr<render::Renderer> renderer;
  FrameLoop loop;
};

Result<SmokeScene> loadSmokeScene(const std::filesystem::path& file, render::Device& device) {
  auto scene = loadScene(file);
  if (!scene) return std::unexpected(scene.error());
  scene->simulation.settleSeconds = 0.0f;
  scene->output.width = int(kWidth);
  scene->output.height = int(kHeight);
  for (Groom& groom : scene->grooms)
    if (groom.rendering.denseStrands == 0 || groom.rendering.denseStrands > kSmokeDenseStrands)
      groom.rendering.denseStrands = kSmokeDenseStrands;
  for (Material& material : scene->materials)
    material.translucency.voxelResolution = std::min(material.translucency.voxelResolution, kSmokeVoxelResolution);
  auto resolver = AssetResolver::createDefault();
  if (!resolver) return std::unexpected(resolver.error());
  auto created = World::create(std::move(*scene), *resolver);
  if (!created) return std::unexpected(created.error());
  for (const std::string& note : created->notes()) std::cout << "note: " << note << '\n';
  auto world = std::make_unique<World>(std::move(*created));
  auto renderer = render::Renderer::create(device, {.extent = {kWidth, kHeight}, .msaaSamples = 1});
  if (!renderer) return std::unexpected(renderer.error());
  auto loop = FrameLoop::create(*world, **renderer, {.imageSize = {kWidth, kHeight}, .threads = 1});
  if (!loop) return std::unexpected(loop.error());
  if (auto set = loop->setScene(world->staticScene()); !set) return std::unexpected(set.error());
  return SmokeScene{std::move(world), std::move(*renderer), std::move(*loop)};
}

// A frame of the world as it is now, with the triangles tessellated at load for the small frame.
Result<std::vector<render::PassTiming>> renderCurrentFrame(SmokeScene& smoke) {
  return smoke.loop.renderFrame(smoke.world->frameInput(), Refinement::kKeep);
}

TEST_P(EveryScene, LoadsAndRendersOneSmallFrameThatIsNotBlank) {
  auto smoke = loadSmokeScene(GetParam(), device());
  ASSERT_TRUE(smoke.has_value()) << smoke.error().message;
  const render::StaticScene statics = smoke->world->staticScene();
  ASSERT_FALSE(smoke->world->frameInput().instances.empty() && statics.grooms.empty()) << "the scene draws nothing";
  auto timings = renderCurrentFrame(*smoke);
  ASSERT_TRUE(timings.has_value()) << timings.error().message;
  using render::PassName;
  const auto ran = [&](PassName pass) {
    return std::any_of(timings->begin(), timings->end(), [&](const auto& t) { return t.pass == pass; });
  };
  // A main pass in two halves, or in one where the deferred skin lets the hair be shaded before it.
  EXPECT_NE(ran(PassName::kSurfaces), ran(PassName::kMainPass));
  EXPECT_EQ(ran(PassName::kHairLighting), !smoke->world->hairGuides().empty())
      << "hair is shaded exactly when the scene has grooms";
  EXPECT_EQ(ran(PassName::kHair) || ran(PassName::kMainPass), ran(PassName::kHairLighting))
      << "and drawn after the surfaces";
  auto pixels = smoke->renderer->readOutput();
  ASSERT_TRUE(pixels.has_value()) << pixels.error().message;
  ASSERT_EQ(pixels->size(), std::size_t(kWidth) * kHeight * 4);
  // 12: well above the rounding of a uniform image's 8-bit values, far below any drawn object's contrast.
  EXPECT_GT(fractionAwayFromMostCommonColour(*pixels, 12), kMinDrawnFraction) << "the frame looks blank";
}

// After the first frame, which creates every pipeline, the animation's frames compile no shader
// on lavapipe (tests/support/jit_compile_counter.hpp: a shader that branches on uniforms alone
// is compiled again each time it is bound).
TEST_P(EveryScene, LaterFramesCompileNoShaderOnLavapipe) {
  if (device().info().name.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "not lavapipe";
  auto smoke = loadSmokeScene(GetParam(), device());
  ASSERT_TRUE(smoke.has_value()) << smoke.error().message;
  const std::size_t beforeFirst = mane::testing::jitCompiles();
  ASSERT_TRUE(renderCurrentFrame(*smoke).has_value());
  ASSERT_GT(mane::testing::jitCompiles(), beforeFirst) << "the counter saw the first frame compile nothing";
  for (int frame = 1; frame <= 2; ++frame) {
    const std::size_t before = mane::testing::jitCompiles();
    ASSERT_TRUE(smoke->loop.advance(1.0 / 30.0).has_value());
    auto timings = renderCurrentFrame(*smoke);
    ASSERT_TRUE(timings.has_value()) << timings.error().message;
    EXPECT_EQ(mane::testing::jitCompiles() - before, 0u)
        << "shaders compiled again for frame " << frame << ": does one branch on uniform values alone?";
  }
}

// The first three frames of each scene, byte for byte: the FNV-1a hash of each frame's RGBA
// bytes against tests/golden/frames/<scene>.txt, written by the binary before a change that must
// not move a pixel (a refactor). An intended change of the picture regenerates them with
// MANE_UPDATE_GOLDEN=1, after the pictures have been looked at. Pinned to lavapipe, like the
// golden images.
TEST_P(EveryScene, RendersItsGoldenFramesByteForByte) {
  if (device().info().name.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "not lavapipe";
  auto smoke = loadSmokeScene(GetParam(), device());
  ASSERT_TRUE(smoke.has_value()) << smoke.error().message;
  std::string hashes;
  for (int frame = 0; frame < 3; ++frame) {
    if (frame > 0) {
      ASSERT_TRUE(smoke->loop.advance(1.0 / 30.0).has_value());
    }
    ASSERT_TRUE(renderCurrentFrame(*smoke).has_value());
    auto pixels = smoke->renderer->readOutput();
    ASSERT_TRUE(pixels.has_value()) << pixels.error().message;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(physics::fnv1a(std::as_bytes(std::span(*pixels)))));
    hashes += std::string(hex) + "\n";
  }
  const std::filesystem::path golden =
      std::filesystem::path(MANE_SOURCE_DIR) / "tests/golden/frames" / (GetParam().stem().string() + ".txt");
  if (std::getenv("MANE_UPDATE_GOLDEN")) {
    std::filesystem::create_directories(golden.parent_path());
    std::ofstream(golden) << hashes;
    GTEST_SKIP() << "wrote " << golden;
  }
  std::ifstream file(golden);
  ASSERT_TRUE(file) << golden << ": missing; write it with MANE_UPDATE_GOLDEN=1";
  const std::string expected((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_EQ(hashes, expected) << "the frames of " << GetParam().filename() << " changed (hashes of frames 0, 1, 2)";
}

INSTANTIATE_TEST_SUITE_P(Scenes, EveryScene, ::testing::ValuesIn(sceneFiles()), [](const auto& info) {
  std::string name = info.param.stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

}  // namespace
}  // namespace mane::scenes
