// Fur in the frame: a scene's fur material through the World and the Renderer,
// on scenes/bunny.json (the Stanford bunny, no uvs, with the cat-fur photo). Checked against
// what the scene says and against the same frame drawn another way:
//  - the World grows fur on the pair the scene names, with box-projected uvs in metres × the
//    material's uv_scale;
//  - shells off draws the fur material exactly as a Lambert material with the same photo;
//  - shells on cover every pixel the bare body covers (the skin layer is opaque) and more;
//  - a fur material drawn on a mesh the scene grows no fur on is an error, not a blank.

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

const std::filesystem::path kBunny = std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "bunny.json";
constexpr vk::Extent2D kExtent{160, 90};

class FurScene : public mane::testing::VulkanTest {
protected:
  // The bunny scene's World, or none when its assets are absent (the test is then skipped).
  std::optional<World> loadBunny() {
    auto scene = loadScene(kBunny);
    EXPECT_TRUE(scene.has_value()) << scene.error().message;
    if (!scene) return std::nullopt;
    auto world = World::create(std::move(*scene), testing::sharedResolver());
    EXPECT_TRUE(world.has_value()) << world.error().message;
    if (!world) return std::nullopt;
    return std::move(*world);
  }

  std::vector<std::uint8_t> render(const render::StaticScene& statics, const render::FrameInput& frame) {
    auto renderer = render::Renderer::create(device(), {.extent = kExtent});
    EXPECT_TRUE(renderer.has_value());
    auto set = (*renderer)->setScene(statics);
    EXPECT_TRUE(set.has_value()) << set.error().message;
    auto rendered = (*renderer)->render(frame);
    EXPECT_TRUE(rendered.has_value()) << rendered.error().message;
    auto pixels = (*renderer)->readOutput();
    EXPECT_TRUE(pixels.has_value());
    return pixels ? *pixels : std::vector<std::uint8_t>{};
  }

  // Pixels that differ from the background (the frame's first pixel: a corner the bunny misses).
  static std::vector<bool> covered(const std::vector<std::uint8_t>& rgba) {
    std::vector<bool> result(rgba.size() / 4);
    for (std::size_t i = 0; i < result.size(); ++i)
      for (int c = 0; c < 3; ++c) result[i] = result[i] || rgba[4 * i + c] != rgba[c];
    return result;
  }
};

#define MANE_FUR_ASSETS_OR_SKIP()                                               \
  MANE_RESOLVE_OR_SKIP(photoPath_, "fur/chelsea_forehead_fur_crop_110x80.png"); \
  MANE_RESOLVE_OR_SKIP(bunnyPath_, "meshes/stanford-bunny.obj")

TEST_F(FurScene, TheWorldGrowsFurOnTheBunnyWithUvsInMetres) {
  MANE_FUR_ASSETS_OR_SKIP();
  auto world = loadBunny();
  ASSERT_TRUE(world);
  const render::StaticScene statics = world->staticScene();
  ASSERT_EQ(statics.furs.size(), 1u);
  EXPECT_EQ(statics.furs[0].mesh, 0u);
  EXPECT_EQ(statics.furs[0].material, 0u);
  const render::MaterialData& material = statics.materials[0];
  EXPECT_EQ(material.shading, render::SurfaceShading::kFur);
  EXPECT_EQ(material.fur.layers, 15u);
  EXPECT_FLOAT_EQ(material.fur.thickness, 0.004f);
  ASSERT_TRUE(material.albedo.has_value());
  EXPECT_EQ(material.albedo->width, 110u);
  // Box projection: the two coordinates across the normal's largest axis, metres × uv_scale 33.
  const render::MeshData& mesh = statics.meshes[0];
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); i += 997) {
    const glm::vec3 n = glm::abs(mesh.normals[i]);
    const glm::vec3 p = mesh.positions[i] * 33.0f;
    const glm::vec2 expected = n.x >= n.y && n.x >= n.z ? glm::vec2(p.z, p.y)
                               : n.y >= n.z             ? glm::vec2(p.x, p.z)
                                                        : glm::vec2(p.x, p.y);
    EXPECT_EQ(mesh.uvs[i], expected) << "vertex " << i;
  }
  EXPECT_TRUE(std::ranges::any_of(
      world->notes(), [](const std::string& note) { return note.find("box projection") != std::string::npos; }));
}

TEST_F(FurScene, ShellsOffDrawTheFurAsALambertSurfaceWithThePhoto) {
  MANE_FUR_ASSETS_OR_SKIP();
  auto world = loadBunny();
  ASSERT_TRUE(world);
  render::FrameInput frame = world->frameInput();
  frame.furShells = false;
  const auto bare = render(world->staticScene(), frame);
  render::StaticScene lambert = world->staticScene();
  lambert.materials[0].shading = render::SurfaceShading::kLambert;
  lambert.furs.clear();
  const auto reference = render(lambert, world->frameInput());
  ASSERT_FALSE(bare.empty());
  EXPECT_EQ(bare, reference);
}

TEST_F(FurScene, ShellsCoverTheBareBodyAndGrowBeyondIt) {
  MANE_FUR_ASSETS_OR_SKIP();
  auto world = loadBunny();
  ASSERT_TRUE(world);
  render::FrameInput frame = world->frameInput();
  const auto furred = covered(render(world->staticScene(), frame));
  frame.furShells = false;
  const auto bare = covered(render(world->staticScene(), frame));
  ASSERT_EQ(furred.size(), bare.size());
  std::size_t bareCount = 0, furOnly = 0, lost = 0;
  for (std::size_t i = 0; i < bare.size(); ++i) {
    bareCount += bare[i];
    furOnly += furred[i] && !bare[i];
    lost += bare[i] && !furred[i];
  }
  EXPECT_GT(bareCount, 1000u) << "the bunny fills part of the frame";
  EXPECT_EQ(lost, 0u) << "the skin layer covers the body";
  EXPECT_GT(furOnly, 20u) << "fur beyond the bare silhouette";
}

TEST_F(FurScene, AFurMaterialOnAMeshWithoutFurIsAnError) {
  MANE_FUR_ASSETS_OR_SKIP();
  auto world = loadBunny();
  ASSERT_TRUE(world);
  render::StaticScene statics = world->staticScene();
  statics.furs.clear();
  auto renderer = render::Renderer::create(device(), {.extent = kExtent});
  ASSERT_TRUE(renderer.has_value());
  ASSERT_TRUE((*renderer)->setScene(statics).has_value());
  auto rendered = (*renderer)->render(world->frameInput());
  ASSERT_FALSE(rendered.has_value());
  EXPECT_NE(rendered.error().message.find("instance 0"), std::string::npos) << rendered.error().message;
  EXPECT_NE(rendered.error().message.find("fur"), std::string::npos) << rendered.error().message;
}

}  // namespace
}  // namespace mane::scenes
