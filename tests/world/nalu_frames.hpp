#pragma once
// Helpers for the tests that render scenes/nalu.json twice, with a renderer setting on and off,
// and compare the two frames channel by channel.

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/frame_loop.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"

namespace mane::scenes::testing {

/// nalu's world 20 frames into its animation (the head turned, the hair over it moving), without
/// the settling, its scene first changed by `edit`; nothing when it does not load (the failure is
/// recorded).
inline std::optional<World> naluIntoItsAnimation(const std::function<void(Scene&)>& edit = {}) {
  auto scene = loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json");
  EXPECT_TRUE(scene.has_value()) << scene.error().message;
  if (!scene) return std::nullopt;
  scene->simulation.settleSeconds = 0.0f;
  if (edit) edit(*scene);
  auto world = World::create(std::move(*scene), sharedResolver());
  EXPECT_TRUE(world.has_value()) << world.error().message;
  if (!world) return std::nullopt;
  for (int frame = 0; frame < 20; ++frame) {
    auto advanced = world->advance(1.0 / 30.0, 2);
    EXPECT_TRUE(advanced.has_value()) << advanced.error().message;
    if (!advanced) return std::nullopt;
  }
  return std::move(*world);
}

/// nalu.json's head alone, changed by `edit`: no bunny, fins or post-processing, and no hair
/// shadows, so that its hair changes only the pixels it covers; nothing when it does not load
/// (the failure is recorded).
inline std::optional<Scene> naluHeadAlone(const std::function<void(Scene&)>& edit = {}) {
  auto scene = loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json");
  EXPECT_TRUE(scene.has_value()) << scene.error().message;
  if (!scene) return std::nullopt;
  std::erase_if(scene->meshes, [](const MeshInstance& mesh) { return mesh.name != "head"; });
  scene->cloths.clear();
  scene->post = {};
  scene->hairShadows.mode = render::HairShadowMode::kOff;
  if (edit) edit(*scene);
  return std::move(*scene);
}

/// The frame of `world` a renderer made with `settings` draws, as RGBA8 (empty on failure, which
/// is recorded), with the hair shadows in `shadows` mode (the scene's by default); `inspect`
/// sees the renderer after it.
inline std::vector<std::uint8_t> renderFrame(const render::Device& device, World& world,
                                             const render::RendererSettings& settings,
                                             const std::function<void(const render::Renderer&)>& inspect = {},
                                             std::optional<render::HairShadowMode> shadows = std::nullopt) {
  auto renderer = render::Renderer::create(device, settings);
  EXPECT_TRUE(renderer.has_value()) << renderer.error().message;
  if (!renderer) return {};
  auto loop = FrameLoop::create(world, **renderer, {.imageSize = {settings.extent.width, settings.extent.height}});
  EXPECT_TRUE(loop.has_value()) << loop.error().message;
  if (!loop) return {};
  render::StaticScene statics = world.staticScene();
  if (shadows) statics.hairShadows.mode = *shadows;
  auto set = loop->setScene(statics);
  EXPECT_TRUE(set.has_value()) << set.error().message;
  // The triangles the world was loaded with: the frames compared differ in one renderer setting.
  auto rendered = loop->renderFrame(world.frameInput(), Refinement::kKeep);
  EXPECT_TRUE(rendered.has_value()) << rendered.error().message;
  auto pixels = (*renderer)->readOutput();
  EXPECT_TRUE(pixels.has_value());
  if (inspect) inspect(**renderer);
  return pixels ? *pixels : std::vector<std::uint8_t>{};
}

/// How many channels of two frames differ, and by how much at most.
struct ChannelDifferences {
  std::size_t differing = 0;
  int largest = 0;
};

inline ChannelDifferences compareChannels(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  ChannelDifferences result;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    const int difference = std::abs(int(a[i]) - int(b[i]));
    result.differing += difference != 0 ? 1 : 0;
    result.largest = std::max(result.largest, difference);
  }
  return result;
}

}  // namespace mane::scenes::testing
