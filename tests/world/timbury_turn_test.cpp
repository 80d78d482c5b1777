// scenes/timbury.json turns its camera from the promenade towards the setting sun: the frame grows
// brighter (its log-average luminance, measured by the auto gain, at least doubles) and the
// auto gain closes down as it adapts (the gain at least halves), as the seed's Timbury demo does
// when its camera turns to the window.

#include <cmath>

#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

class TimburyTurn : public mane::testing::VulkanTest {};

TEST_F(TimburyTurn, TheGainClosesDownAsTheCameraTurnsTowardsTheSun) {
  MANE_RESOLVE_OR_SKIP(panorama, "env/venice_sunset_1k.hdr");
  auto scene = loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "timbury.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  ASSERT_TRUE(scene->camera.orbit.has_value());
  const double turnSeconds = scene->camera.orbit->seconds;
  auto world = World::create(std::move(*scene), testing::sharedResolver());
  ASSERT_TRUE(world.has_value()) << world.error().message;
  auto renderer = render::Renderer::create(device(), {.extent = {320, 180}, .msaaSamples = 1});
  ASSERT_TRUE(renderer.has_value()) << renderer.error().message;
  ASSERT_TRUE((*renderer)->setScene(world->staticScene()).has_value());

  // The first frame sets the adapted luminance to its own; later ones, a minute apart, adapt
  // fully (1 − exp(−60/τ) of the way).
  const auto render = [&](float frameSeconds) {
    render::FrameInput frame = world->frameInput();
    frame.post.frameSeconds = frameSeconds;
    auto rendered = (*renderer)->render(frame);
    EXPECT_TRUE(rendered.has_value()) << rendered.error().message;
    return (*renderer)->post().readExposure();
  };
  const render::PostExposure promenade = render(1.0f / 30.0f);
  ASSERT_TRUE(world->showTime(turnSeconds).has_value());
  render(60.0f);
  const render::PostExposure sunset = render(60.0f);
  EXPECT_GT(sunset.frameLogLuminance, promenade.frameLogLuminance + std::log(2.0f));
  EXPECT_LT(sunset.gain, 0.5f * promenade.gain);
}

}  // namespace
}  // namespace mane::scenes
