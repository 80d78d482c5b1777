// A subdivided mesh followed by the camera end to end: World::refineForCamera tessellates the limit
// surface again for each new camera position and Renderer::replaceMesh uploads the new triangles,
// under the validation layers (VulkanTest fails on any message).
//
// Oracle: a sphere of radius R seen from distance d covers a disc of angular radius asin(R/d),
// so the count of lit pixels follows tan²(asin(R/d)): ×4.4 from 0.8 m to 0.4 m and ×0.24 from
// 0.8 m to 1.6 m for R = 0.1 m. Counts are of whole pixels on a 160 × 120 image (the disc's
// rim is a few % of its area at these sizes, and the coarse cage's limit is a sphere within a
// few %): within 15 %.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

class WorldRefineRender : public mane::testing::VulkanTest {};

constexpr vk::Extent2D kExtent{160, 120};

std::size_t litPixels(const std::vector<std::uint8_t>& rgba) {
  std::size_t lit = 0;
  for (std::size_t i = 0; i < rgba.size(); i += 4) lit += rgba[i] > 100 ? 1 : 0;
  return lit;
}

/// A latitude-longitude quad cage of the unit sphere as OBJ text (12 quads around, 6 bands,
/// triangle fans at the poles): coarse, so that how finely its limit is cut depends on the view.
std::string coarseSphereObj() {
  constexpr int kSegments = 12, kRings = 6;
  std::string obj = "v 0 -1 0\n";
  for (int r = 1; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      const double latitude = -M_PI / 2 + M_PI * r / kRings, longitude = 2.0 * M_PI * s / kSegments;
      obj += "v " + std::to_string(std::cos(latitude) * std::sin(longitude)) + " " +
             std::to_string(std::sin(latitude)) + " " + std::to_string(std::cos(latitude) * std::cos(longitude)) + "\n";
    }
  obj += "v 0 1 0\n";
  const auto at = [](int ring, int s) { return std::to_string(2 + (ring - 1) * kSegments + (s % kSegments)); };
  for (int s = 0; s < kSegments; ++s) {
    obj += "f 1 " + at(1, s + 1) + " " + at(1, s) + "\n";
    for (int r = 1; r + 1 < kRings; ++r)
      obj += "f " + at(r, s) + " " + at(r, s + 1) + " " + at(r + 1, s + 1) + " " + at(r + 1, s) + "\n";
    obj += "f " + std::to_string(2 + (kRings - 1) * kSegments) + " " + at(kRings - 1, s) + " " + at(kRings - 1, s + 1) +
           "\n";
  }
  return obj;
}

TEST_F(WorldRefineRender, TheSubdividedMeshFollowsTheCameraInAndOut) {
  testing::ScratchDir dir;
  dir.write("ball.obj", coarseSphereObj());
  auto scene = parseScene(R"({"name": "ball", "output": {"width": 160, "height": 120},
      "camera": {"position": [0, 0, 0.8], "target": [0, 0, 0], "near": 0.01, "far": 10},
      "lights": [{"kind": "directional", "direction": [0, 0, -1], "intensity": 2}],
      "materials": [{"name": "skin", "kind": "skin"}],
      "meshes": [{"name": "ball", "source": "ball.obj", "material": "skin", "transform": {"scale": 0.1},
                  "subdivision": {"max_pixel_error": 0.5}}]})",
                          dir.path() / "ball.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  auto world = World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  auto renderer = render::Renderer::create(device(), {.extent = kExtent});
  ASSERT_TRUE(renderer.has_value()) << renderer.error().message;
  ASSERT_TRUE((*renderer)->setScene(world->staticScene()).has_value());

  // Renders the world from `distance` metres after refining it for that camera.
  const auto shoot = [&](float distance, std::size_t& triangles) -> std::size_t {
    render::FrameInput frame = world->frameInput();
    frame.camera.position = {0.0f, 0.0f, distance};
    auto changed = world->refineForCamera(frame.camera, {kExtent.width, kExtent.height});
    EXPECT_TRUE(changed.has_value()) << changed.error().message;
    for (const std::size_t mesh : *changed) {
      auto replaced = (*renderer)->replaceMesh(mesh, world->meshData(mesh));
      EXPECT_TRUE(replaced.has_value()) << replaced.error().message;
    }
    triangles = world->meshData(0).indices.size() / 3;
    auto rendered = (*renderer)->render(frame);
    if (!rendered) {
      ADD_FAILURE() << rendered.error().message;
      return 0;
    }
    auto rgba = (*renderer)->readOutput();
    EXPECT_TRUE(rgba.has_value());
    return rgba ? litPixels(*rgba) : 0;
  };
  const auto discRatio = [](float from, float to) {
    const auto tanSquared = [](float d) { return std::pow(std::tan(std::asin(0.1 / d)), 2.0); };
    return tanSquared(to) / tanSquared(from);
  };
  std::size_t atScene = 0, near = 0, far = 0;
  const std::size_t sceneLit = shoot(0.8f, atScene);
  ASSERT_GT(sceneLit, 200u);
  const std::size_t nearLit = shoot(0.4f, near);
  EXPECT_GT(near, atScene) << "nearer: more triangles";
  EXPECT_NEAR(double(nearLit) / double(sceneLit), discRatio(0.8f, 0.4f), 0.15 * discRatio(0.8f, 0.4f));
  const std::size_t farLit = shoot(1.6f, far);
  EXPECT_LT(far, atScene) << "farther: fewer triangles";
  EXPECT_NEAR(double(farLit) / double(sceneLit), discRatio(0.8f, 1.6f), 0.15 * discRatio(0.8f, 1.6f));
}

}  // namespace
}  // namespace mane::scenes
