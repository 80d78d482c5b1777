// The shadow a fur casts on itself must be as continuous as the fur. It is cast through the hair
// shadow map by one two-point strand per mesh vertex; in a map whose texels are much finer than
// the spacing of those strands, they stand apart as lines, and the fur shadows itself in a
// lattice of dark dashes that follows the mesh's vertices (teapot.json showed one dash per quad
// of its body). Measured here on teapot.json, rendered with and without hair shadows, post
// processing off: the ratio of the two frames is the shadow's transmittance seen through the
// shading, and a hole of the lattice is a fur pixel whose ratio falls below half the median
// ratio of the fur around it (15 × 15 pixels, about half a column of the teapot's body).

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/frame_loop.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

constexpr vk::Extent2D kExtent{1280, 720};  // teapot.json's frame
constexpr int kWindow = 7;                  // half the side of the neighbourhood, pixels
// Below this luminance (of 255) a pixel of the unshadowed frame is background, not fur.
constexpr float kBackground = 40.0f;

class FurShadow : public mane::testing::VulkanTest {
protected:
  std::vector<float> luminance(render::HairShadowMode mode) {
    auto scene = loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "teapot.json");
    EXPECT_TRUE(scene.has_value()) << scene.error().message;
    if (!scene) return {};
    scene->post = {};
    scene->hairShadows.mode = mode;
    auto world = World::create(std::move(*scene), testing::sharedResolver());
    EXPECT_TRUE(world.has_value()) << world.error().message;
    if (!world) return {};
    auto renderer = render::Renderer::create(device(), {.extent = kExtent, .msaaSamples = 4});
    EXPECT_TRUE(renderer.has_value()) << renderer.error().message;
    if (!renderer) return {};
    auto loop = FrameLoop::create(*world, **renderer, {.imageSize = {kExtent.width, kExtent.height}});
    EXPECT_TRUE(loop.has_value()) << loop.error().message;
    if (!loop || !loop->setScene(world->staticScene())) return {};
    auto rendered = loop->renderFrame(world->frameInput(), Refinement::kKeep);
    EXPECT_TRUE(rendered.has_value()) << rendered.error().message;
    auto pixels = (*renderer)->readOutput();
    if (!pixels) return {};
    std::vector<float> result(std::size_t(kExtent.width) * kExtent.height);
    for (std::size_t i = 0; i < result.size(); ++i)
      result[i] = 0.2126f * (*pixels)[4 * i] + 0.7152f * (*pixels)[4 * i + 1] + 0.0722f * (*pixels)[4 * i + 2];
    return result;
  }
};

TEST_F(FurShadow, TheTeapotsGrassShadowsItselfWithoutALattice) {
  if (!testing::sharedResolver().resolve("meshes/teapot.obj"))
    MANE_SKIP_FOR_MISSING_ASSET("the teapot is not on this machine");
  const std::vector<float> lit = luminance(render::HairShadowMode::kOff);
  const std::vector<float> shadowed = luminance(render::HairShadowMode::kOpacityShadowMap);
  ASSERT_EQ(lit.size(), shadowed.size());
  ASSERT_FALSE(lit.empty());

  const int width = int(kExtent.width), height = int(kExtent.height);
  std::vector<float> ratio(lit.size(), -1.0f);  // −1: background
  for (std::size_t i = 0; i < lit.size(); ++i)
    if (lit[i] >= kBackground) ratio[i] = shadowed[i] / lit[i];

  std::size_t fur = 0, holes = 0;
  std::vector<float> around;
  for (int y = kWindow; y + kWindow < height; y += 2)
    for (int x = kWindow; x + kWindow < width; x += 2) {
      const float here = ratio[std::size_t(y) * width + x];
      if (here < 0.0f) continue;
      around.clear();
      for (int dy = -kWindow; dy <= kWindow; ++dy)
        for (int dx = -kWindow; dx <= kWindow; ++dx) {
          const float r = ratio[std::size_t(y + dy) * width + (x + dx)];
          if (r >= 0.0f) around.push_back(r);
        }
      if (around.size() < (2 * kWindow + 1) * (2 * kWindow + 1) / 2) continue;  // the silhouette
      std::nth_element(around.begin(), around.begin() + around.size() / 2, around.end());
      ++fur;
      if (here < 0.5f * around[around.size() / 2]) ++holes;
    }
  const double share = double(holes) / double(fur);
  std::printf("%zu fur pixels sampled, %.2f %% of them holes in the fur's own shadow\n", fur, 100.0 * share);
  ASSERT_GT(fur, 10000u);
  EXPECT_LT(share, 0.005);
}

}  // namespace
}  // namespace mane::scenes
