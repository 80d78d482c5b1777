// Effects drawn over the scene: lines and discs.
//
// Oracles: a line of width w pixels, white under a white ambient light over black, adds up to w
// across it, whether it is wider than a pixel or thinner (drawn a pixel wide and fainter); a
// disc's sum is its area times its profile's mean, at any size; effects out of range are
// refused by name.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{96, 64};
constexpr float kFov = 0.6f;
constexpr float kDistance = 10.0f;

class EffectsRender : public testing::VulkanTest {
protected:
  void SetUp() override {
    VulkanTest::SetUp();
    auto renderer = Renderer::create(device(), {.extent = kExtent});
    ASSERT_TRUE(renderer) << renderer.error().message;
    renderer_ = std::move(*renderer);
    ASSERT_TRUE(renderer_->setScene(StaticScene{}));
  }

  // Looking down −z at the origin from kDistance, under a white ambient light, over black.
  static FrameInput frame() {
    FrameInput input;
    input.camera = {
        .position = {0.0f, 0.0f, kDistance}, .verticalFovRadians = kFov, .nearPlane = 0.1f, .farPlane = 100.0f};
    input.ambient = glm::vec3(1.0f);
    input.background = glm::vec3(0.0f);
    return input;
  }

  // Metres a pixel spans at kDistance.
  static float pixelMetres() { return 2.0f * std::tan(0.5f * kFov) * kDistance / float(kExtent.height); }

  // The red channel of the HDR image, row by row.
  std::vector<float> draw(const FrameInput& input) {
    auto rendered = renderer_->render(input);
    EXPECT_TRUE(rendered) << (rendered ? "" : rendered.error().message);
    const auto hdr = renderer_->readHdrOutput();
    EXPECT_TRUE(hdr);
    std::vector<float> red(kExtent.width * kExtent.height);
    for (std::size_t i = 0; i < red.size(); ++i) red[i] = glm::unpackHalf1x16((*hdr)[4 * i]);
    return red;
  }

  std::unique_ptr<Renderer> renderer_;
};

TEST_F(EffectsRender, ALineAddsUpToItsWidthInPixelsThinOrWide) {
  for (float pixels : {0.2f, 0.6f, 1.5f, 5.0f}) {
    FrameInput input = frame();
    // Across the image, a little off the pixels' rows.
    input.effects.lines.push_back({.from = {-20.0f, 0.13f * pixelMetres(), 0.0f},
                                   .to = {20.0f, 0.13f * pixelMetres(), 0.0f},
                                   .width = pixels * pixelMetres(),
                                   .colour = glm::vec3(1.0f)});
    const std::vector<float> red = draw(input);
    double sum = 0.0;
    int columns = 0;
    for (std::uint32_t x = 8; x + 8 < kExtent.width; ++x, ++columns)
      for (std::uint32_t y = 0; y < kExtent.height; ++y) sum += red[y * kExtent.width + x];
    EXPECT_NEAR(sum / columns / pixels, 1.0, 0.03) << pixels << " pixels wide";
  }
}

TEST_F(EffectsRender, ADiscAddsUpToItsAreaTimesItsProfileAtAnySize) {
  // The profile (1 − r²)² over the unit disc (shaders/effects.frag): π/3.
  const double profile = std::numbers::pi / 3.0;
  for (float pixels : {0.3f, 0.8f, 6.0f}) {
    FrameInput input = frame();
    input.effects.sprites.push_back(
        {.centre = {0.1f * pixelMetres(), 0.2f * pixelMetres(), 0.0f}, .radius = pixels * pixelMetres()});
    const std::vector<float> red = draw(input);
    double sum = 0.0;
    for (float v : red) sum += v;
    // Lit from all round by the ambient alone: its albedo of 1 shows 1.
    EXPECT_NEAR(sum / (profile * pixels * pixels), 1.0, 0.15) << pixels << " pixels in radius";
  }
}

TEST_F(EffectsRender, RefusesEffectsOutOfRangeByName) {
  FrameInput input = frame();
  input.effects.sprites = {{.radius = 1.0f}, {.radius = -1.0f}};
  auto rendered = renderer_->render(input);
  ASSERT_FALSE(rendered);
  EXPECT_NE(rendered.error().message.find("sprite 1's radius"), std::string::npos) << rendered.error().message;
  input = frame();
  input.effects.lines = {{.to = {1.0f, 0.0f, 0.0f}, .opacity = 2.0f}};
  rendered = renderer_->render(input);
  ASSERT_FALSE(rendered);
  EXPECT_NE(rendered.error().message.find("line 0's opacity"), std::string::npos) << rendered.error().message;
}

}  // namespace
}  // namespace mane::render
