// The default scene end to end: scene file → World (assets through the resolver) → Renderer on
// lavapipe with validation on → image.
//
// Two checks. An independent one: the head covers a plausible part of the frame, is lit on the
// side facing the key light and is skin-coloured where lit (red > green > blue, as in the
// albedo map), so a black, blank or untextured frame fails whatever the golden says. Then the
// golden image (tests/golden/nalu_head.png, lavapipe, Mesa 22.3.6) within a tolerance that
// allows rasterizer rounding, not a changed picture. The groom's guides are not handed to the
// renderer (Renderer::updateHair), so the hair is not drawn and the skin stays in view; the hair
// has its own test in world_test.cpp.

#include <algorithm>
#include <functional>

#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/world.hpp"
#include "tests/support/image_compare.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

constexpr std::uint32_t kWidth = 320;
constexpr std::uint32_t kHeight = 180;

/// The default scene's head and hair alone, as the goldens show them: its other meshes (the
/// furred bunny), its cloth fins and its post-processing left out.
void keepOnlyTheHead(Scene& scene) {
  std::erase_if(scene.meshes, [](const MeshInstance& mesh) { return mesh.name != "head"; });
  scene.cloths.clear();
  scene.post = {};
}

class NaluHead : public testing::VulkanTest {
protected:
  /// The default scene's head with its skin diffused `diffusion`, against golden `golden`.
  void renderAndCompare(render::SkinDiffusion diffusion, const std::string& golden);
  /// The default scene's head, its material and frame changed by `change`, rendered to RGBA8.
  std::vector<std::uint8_t> render(const std::function<void(Scene&)>& changeScene,
                                   const std::function<void(render::FrameInput&)>& changeFrame);
};

TEST_F(NaluHead, RendersTheLitTexturedHead) {
  renderAndCompare(render::SkinDiffusion::kPreintegrated, "nalu_head");
}

TEST_F(NaluHead, RendersTheHeadWithTextureSpaceDiffusion) {
  renderAndCompare(render::SkinDiffusion::kTextureSpace, "nalu_head_texture_space");
}

TEST_F(NaluHead, BackLitSkinGlowsRedThroughTheDepthMap) {
  // The key light moved behind the head (its direction mirrored through the view plane), the
  // fill lights off: without translucency the face is dark but for the ambient; with it, light 0
  // comes through the thin parts (the nose, the ears' rims) by skin's transmittance, which keeps
  // red longest (SkinProfile::transmittance): what is added must be red > green > blue.
  const auto backLit = [](render::FrameInput& frame) {
    const glm::vec3 view = glm::normalize(frame.camera.target - frame.camera.position);
    render::DirectionalLight light = frame.lights.at(0);
    light.direction = glm::normalize(light.direction - 2.0f * glm::dot(light.direction, -view) * -view);
    frame.lights = {light};
  };
  const std::vector<std::uint8_t> opaque = render([](Scene&) {}, backLit);
  const std::vector<std::uint8_t> translucent = render(
      [](Scene& scene) { scene.materials[0].translucency.method = render::TranslucencyMethod::kDepthMap; }, backLit);
  ASSERT_EQ(opaque.size(), translucent.size());
  ASSERT_FALSE(opaque.empty());
  glm::dvec3 added(0.0);
  std::size_t glowing = 0;
  for (std::size_t i = 0; i < opaque.size(); i += 4) {
    const glm::dvec3 difference(translucent[i] - opaque[i], translucent[i + 1] - opaque[i + 1],
                                translucent[i + 2] - opaque[i + 2]);
    EXPECT_GE(std::min({difference.r, difference.g, difference.b}), -1.0) << "translucency only adds light";
    added += difference;
    if (difference.r >= 8.0) ++glowing;
  }
  EXPECT_GT(added.r, added.g);
  EXPECT_GT(added.g, added.b);
  EXPECT_GT(glowing, kWidth * kHeight / 200) << "some of the head must glow";
  const auto comparison = testing::compareWithGolden("nalu_head_translucent", {kWidth, kHeight, translucent},
                                                     {.maxChannelDifference = 6, .maxFailingFraction = 0.005});
  EXPECT_TRUE(comparison.passed) << comparison.message;
}

std::vector<std::uint8_t> NaluHead::render(const std::function<void(Scene&)>& changeScene,
                                           const std::function<void(render::FrameInput&)>& changeFrame) {
  auto scene = loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json");
  EXPECT_TRUE(scene.has_value()) << scene.error().message;
  auto resolver = AssetResolver::createDefault();
  if (!scene || !resolver) return {};
  keepOnlyTheHead(*scene);
  changeScene(*scene);
  auto world = World::create(std::move(*scene), *resolver);
  EXPECT_TRUE(world.has_value()) << world.error().message;
  auto renderer = render::Renderer::create(device(), {.extent = {kWidth, kHeight}, .msaaSamples = 4});
  if (!world || !renderer || !(*renderer)->setScene(world->staticScene())) return {};
  render::FrameInput frame = world->frameInput();
  changeFrame(frame);
  if (!(*renderer)->render(frame)) return {};
  auto pixels = (*renderer)->readOutput();
  return pixels ? *pixels : std::vector<std::uint8_t>{};
}

void NaluHead::renderAndCompare(render::SkinDiffusion diffusion, const std::string& golden) {
  auto scene = loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  ASSERT_EQ(scene->materials.at(0).kind, MaterialKind::skin);
  keepOnlyTheHead(*scene);
  scene->materials[0].skin.diffusion = diffusion;
  auto resolver = AssetResolver::createDefault();
  ASSERT_TRUE(resolver.has_value()) << resolver.error().message;
  auto world = World::create(std::move(*scene), *resolver);
  ASSERT_TRUE(world.has_value()) << world.error().message;
  ASSERT_TRUE(world->notes().empty()) << "assets missing: " << world->notes().front();

  auto renderer = render::Renderer::create(device(), {.extent = {kWidth, kHeight}, .msaaSamples = 4});
  ASSERT_TRUE(renderer.has_value()) << renderer.error().message;
  ASSERT_TRUE((*renderer)->setScene(world->staticScene()).has_value());
  const render::FrameInput frame = world->frameInput();
  ASSERT_TRUE((*renderer)->render(frame).has_value());
  auto pixels = (*renderer)->readOutput();
  ASSERT_TRUE(pixels.has_value());

  // Pixels that differ clearly from the background belong to the head.
  const auto background = pixels->begin();  // the top-left corner is background in this framing
  std::size_t head = 0, skinLike = 0;
  for (std::size_t i = 0; i < pixels->size(); i += 4) {
    const int r = (*pixels)[i], g = (*pixels)[i + 1], b = (*pixels)[i + 2];
    if (std::abs(r - background[0]) + std::abs(g - background[1]) + std::abs(b - background[2]) < 12) continue;
    ++head;
    if (r > 60 && r > g && g > b) ++skinLike;
  }
  const double coverage = double(head) / (kWidth * kHeight);
  EXPECT_GT(coverage, 0.10) << "the head should fill a good part of the frame";
  EXPECT_LT(coverage, 0.90) << "the background should still show";
  EXPECT_GT(double(skinLike) / double(head), 0.5) << "lit skin is red > green > blue";

  const auto comparison = testing::compareWithGolden(golden, {kWidth, kHeight, *pixels},
                                                     {.maxChannelDifference = 6, .maxFailingFraction = 0.005});
  EXPECT_TRUE(comparison.passed) << comparison.message;
}

}  // namespace
}  // namespace mane::scenes
