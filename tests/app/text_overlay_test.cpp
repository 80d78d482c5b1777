// The text overlay `mane view` draws its frame time with (render/passes/text_overlay_pass.hpp): the
// font's coverage, the layout's rectangles, and the pass on lavapipe against the layout, pixel for
// pixel.

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/passes/text_overlay_pass.hpp"
#include "render/render_target.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

std::size_t litPixels(char character) {
  std::size_t lit = 0;
  for (std::uint32_t row = 0; row < kGlyphHeight; ++row)
    for (std::uint32_t column = 0; column < kGlyphWidth; ++column) lit += glyphPixel(character, column, row);
  return lit;
}

bool contains(const vk::Rect2D& outer, const vk::Rect2D& inner) {
  return inner.offset.x >= outer.offset.x && inner.offset.y >= outer.offset.y &&
         inner.offset.x + std::int64_t(inner.extent.width) <= outer.offset.x + std::int64_t(outer.extent.width) &&
         inner.offset.y + std::int64_t(inner.extent.height) <= outer.offset.y + std::int64_t(outer.extent.height);
}

TEST(TextOverlayFont, EveryCharacterAStatusLineUsesHasItsOwnGlyph) {
  // '?' stands for characters without a glyph: nothing a status line prints may fall back to it.
  const std::string used = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:/-+=%()";
  for (char c : used) {
    EXPECT_GT(litPixels(c), 0u) << c;
    if (c != '?') {
      bool differs = false;
      for (std::uint32_t row = 0; row < kGlyphHeight; ++row)
        for (std::uint32_t column = 0; column < kGlyphWidth; ++column)
          differs |= glyphPixel(c, column, row) != glyphPixel('?', column, row);
      EXPECT_TRUE(differs) << c << " draws as '?'";
    }
  }
  EXPECT_EQ(litPixels(' '), 0u);
  // "1": the stem's 7 pixels, its flag's 1 and its base's 2 beside the stem.
  EXPECT_EQ(litPixels('1'), 10u);
  EXPECT_EQ(litPixels('-'), 5u);
}

TEST(TextOverlayFont, LowerCaseDrawsAsCapitalsAndUnknownsAsQuestionMarks) {
  for (char c = 'a'; c <= 'z'; ++c)
    for (std::uint32_t row = 0; row < kGlyphHeight; ++row)
      for (std::uint32_t column = 0; column < kGlyphWidth; ++column)
        ASSERT_EQ(glyphPixel(c, column, row), glyphPixel(char(c - 'a' + 'A'), column, row)) << c;
  for (std::uint32_t row = 0; row < kGlyphHeight; ++row)
    for (std::uint32_t column = 0; column < kGlyphWidth; ++column)
      EXPECT_EQ(glyphPixel('~', column, row), glyphPixel('?', column, row));
  EXPECT_FALSE(glyphPixel('8', kGlyphWidth, 0));
  EXPECT_FALSE(glyphPixel('8', 0, kGlyphHeight));
}

TEST(TextOverlayLayout, RunsCoverExactlyTheLitFontPixelsScaled) {
  const std::vector<std::string> lines{"12.5 MS", "K SKIN PRE"};
  const TextOverlaySettings settings{.scale = 3, .origin = {5, 7}};
  const TextLayout layout = layoutText(lines, settings, {400, 100});
  std::size_t lit = 0;
  for (const std::string& line : lines)
    for (char c : line) lit += litPixels(c);
  std::size_t area = 0;
  for (const vk::Rect2D& run : layout.text) {
    area += std::size_t(run.extent.width) * run.extent.height;
    EXPECT_EQ(run.extent.height, 3u) << "one font row per run";
    EXPECT_TRUE(contains(layout.panel, run));
  }
  EXPECT_EQ(area, lit * 9);
  // Panel: the longest line (10 characters × 6 − 1) and two lines (2 × 9 − 2), plus 2 on each side.
  EXPECT_EQ(layout.panel.offset.x, 5);
  EXPECT_EQ(layout.panel.offset.y, 7);
  EXPECT_EQ(layout.panel.extent.width, (10u * 6 - 1 + 4) * 3);
  EXPECT_EQ(layout.panel.extent.height, (2u * 9 - 2 + 4) * 3);
}

TEST(TextOverlayLayout, ClipsToTheImageAndDrawsNothingForNoText) {
  const std::vector<std::string> lines{"A LINE LONGER THAN THE IMAGE IS WIDE"};
  const TextLayout layout = layoutText(lines, {.scale = 2}, {64, 20});
  EXPECT_EQ(layout.panel.offset.x + layout.panel.extent.width, 64u);
  EXPECT_EQ(layout.panel.offset.y + layout.panel.extent.height, 20u);
  for (const vk::Rect2D& run : layout.text) {
    EXPECT_GT(run.extent.width * run.extent.height, 0u);
    EXPECT_LE(run.offset.x + run.extent.width, 64u);
    EXPECT_LE(run.offset.y + run.extent.height, 20u);
  }
  EXPECT_FALSE(layout.text.empty());
  const std::vector<std::string> none{""};
  EXPECT_EQ(layoutText(none, {}, {64, 20}).panel.extent.width, 0u);
  EXPECT_EQ(layoutText({}, {}, {64, 20}).text.size(), 0u);
}

class TextOverlayPass : public testing::VulkanTest {};

TEST_F(TextOverlayPass, DrawsWhiteGlyphsOnABlackPanelAndLeavesTheRestOfTheImage) {
  // An output-like image cleared to grey, then the overlay: every pixel must be white on a lit
  // font pixel, black elsewhere on the panel and still grey outside it. Exact: clears write the
  // values 0 and 1 (sRGB-encoded 0 and 255) and leave other pixels untouched.
  constexpr vk::Extent2D kExtent{120, 40};
  const Image image(device(),
                    {.extent = kExtent,
                     .format = RenderTarget::kOutputFormat,
                     .usage = vk::ImageUsageFlagBits::eColorAttachment | vk::ImageUsageFlagBits::eTransferSrc});
  const std::vector<std::string> lines{"9.5 MS", "OK?"};
  const TextOverlaySettings settings{.scale = 2, .origin = {3, 4}};
  const TextLayout layout = layoutText(lines, settings, kExtent);
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    using Stage = vk::PipelineStageFlagBits2;
    using Access = vk::AccessFlagBits2;
    transition(commands, image, vk::ImageLayout::eUndefined, vk::ImageLayout::eColorAttachmentOptimal, Stage::eNone,
               Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
    const vk::RenderingAttachmentInfo color{
        .imageView = *image.view(),
        .imageLayout = vk::ImageLayout::eColorAttachmentOptimal,
        .loadOp = vk::AttachmentLoadOp::eClear,
        .storeOp = vk::AttachmentStoreOp::eStore,
        .clearValue = {.color = {.float32 = std::array{0.2f, 0.2f, 0.2f, 1.0f}}}};
    commands.beginRendering(vk::RenderingInfo{
        .renderArea = {.extent = kExtent}, .layerCount = 1, .colorAttachmentCount = 1, .pColorAttachments = &color});
    commands.endRendering();
    transition(commands, image, vk::ImageLayout::eColorAttachmentOptimal, vk::ImageLayout::eTransferSrcOptimal,
               Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eTransfer, Access::eTransferRead);
    recordTextOverlay(commands, image, layout, settings);
  });
  const std::vector<std::byte> pixels = readBack(device(), image, 4);
  ASSERT_EQ(pixels.size(), std::size_t(kExtent.width) * kExtent.height * 4);
  const auto lit = [&](std::uint32_t x, std::uint32_t y) {
    // Font pixel under image pixel (x, y): 2 margin font pixels, then 6 per character, 9 per line.
    const std::int64_t fx = (std::int64_t(x) - 3) / 2 - 2, fy = (std::int64_t(y) - 4) / 2 - 2;
    if (std::int64_t(x) < 3 + 4 || std::int64_t(y) < 4 + 4) return false;
    const std::size_t line = std::size_t(fy / 9), character = std::size_t(fx / 6);
    if (line >= lines.size() || character >= lines[line].size()) return false;
    return glyphPixel(lines[line][character], std::uint32_t(fx % 6), std::uint32_t(fy % 9));
  };
  std::size_t white = 0, wrong = 0;
  for (std::uint32_t y = 0; y < kExtent.height; ++y)
    for (std::uint32_t x = 0; x < kExtent.width; ++x) {
      const auto* p = reinterpret_cast<const std::uint8_t*>(pixels.data()) + (std::size_t(y) * kExtent.width + x) * 4;
      const bool onPanel = contains(layout.panel, {.offset = {std::int32_t(x), std::int32_t(y)}, .extent = {1, 1}});
      const std::uint8_t expected = !onPanel ? 124 : lit(x, y) ? 255 : 0;  // 0.2 linear → sRGB 124
      if (expected == 255) ++white;
      if (std::abs(int(p[0]) - expected) > 1 || p[0] != p[1] || p[1] != p[2]) ++wrong;
    }
  EXPECT_EQ(wrong, 0u);
  std::size_t expectedWhite = 0;
  for (const std::string& line : lines)
    for (char c : line) expectedWhite += litPixels(c) * 4;
  EXPECT_EQ(white, expectedWhite);
}

}  // namespace
}  // namespace mane::render
