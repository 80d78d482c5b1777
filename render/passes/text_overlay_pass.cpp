#include "render/passes/text_overlay_pass.hpp"

#include <algorithm>
#include <array>

namespace mane::render {
namespace {

// A glyph drawn as its seven rows, top first, '#' lit, separated by spaces.
struct GlyphPicture {
  char character;
  std::string_view rows;
};

// Capitals, digits and the punctuation a status line needs, after the classic 5×7 LCD fonts.
constexpr std::array kFont{
    GlyphPicture{' ', "..... ..... ..... ..... ..... ..... ....."},
    GlyphPicture{'0', ".###. #...# #..## #.#.# ##..# #...# .###."},
    GlyphPicture{'1', "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###."},
    GlyphPicture{'2', ".###. #...# ....# ...#. ..#.. .#... #####"},
    GlyphPicture{'3', "##### ...#. ..#.. ...#. ....# #...# .###."},
    GlyphPicture{'4', "...#. ..##. .#.#. #..#. ##### ...#. ...#."},
    GlyphPicture{'5', "##### #.... ####. ....# ....# #...# .###."},
    GlyphPicture{'6', "..##. .#... #.... ####. #...# #...# .###."},
    GlyphPicture{'7', "##### ....# ...#. ..#.. .#... .#... .#..."},
    GlyphPicture{'8', ".###. #...# #...# .###. #...# #...# .###."},
    GlyphPicture{'9', ".###. #...# #...# .#### ....# ...#. .##.."},
    GlyphPicture{'A', ".###. #...# #...# ##### #...# #...# #...#"},
    GlyphPicture{'B', "####. #...# #...# ####. #...# #...# ####."},
    GlyphPicture{'C', ".###. #...# #.... #.... #.... #...# .###."},
    GlyphPicture{'D', "###.. #..#. #...# #...# #...# #..#. ###.."},
    GlyphPicture{'E', "##### #.... #.... ####. #.... #.... #####"},
    GlyphPicture{'F', "##### #.... #.... ####. #.... #.... #...."},
    GlyphPicture{'G', ".###. #...# #.... #.### #...# #...# .####"},
    GlyphPicture{'H', "#...# #...# #...# ##### #...# #...# #...#"},
    GlyphPicture{'I', ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###."},
    GlyphPicture{'J', "..### ...#. ...#. ...#. ...#. #..#. .##.."},
    GlyphPicture{'K', "#...# #..#. #.#.. ##... #.#.. #..#. #...#"},
    GlyphPicture{'L', "#.... #.... #.... #.... #.... #.... #####"},
    GlyphPicture{'M', "#...# ##.## #.#.# #.#.# #...# #...# #...#"},
    GlyphPicture{'N', "#...# #...# ##..# #.#.# #..## #...# #...#"},
    GlyphPicture{'O', ".###. #...# #...# #...# #...# #...# .###."},
    GlyphPicture{'P', "####. #...# #...# ####. #.... #.... #...."},
    GlyphPicture{'Q', ".###. #...# #...# #...# #.#.# #..#. .##.#"},
    GlyphPicture{'R', "####. #...# #...# ####. #.#.. #..#. #...#"},
    GlyphPicture{'S', ".#### #.... #.... .###. ....# ....# ####."},
    GlyphPicture{'T', "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#.."},
    GlyphPicture{'U', "#...# #...# #...# #...# #...# #...# .###."},
    GlyphPicture{'V', "#...# #...# #...# #...# #...# .#.#. ..#.."},
    GlyphPicture{'W', "#...# #...# #...# #.#.# #.#.# #.#.# .#.#."},
    GlyphPicture{'X', "#...# #...# .#.#. ..#.. .#.#. #...# #...#"},
    GlyphPicture{'Y', "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#.."},
    GlyphPicture{'Z', "##### ....# ...#. ..#.. .#... #.... #####"},
    GlyphPicture{'.', "..... ..... ..... ..... ..... .##.. .##.."},
    GlyphPicture{',', "..... ..... ..... ..... .##.. ..#.. .#..."},
    GlyphPicture{':', "..... .##.. .##.. ..... .##.. .##.. ....."},
    GlyphPicture{'/', "..... ....# ...#. ..#.. .#... #.... ....."},
    GlyphPicture{'-', "..... ..... ..... ##### ..... ..... ....."},
    GlyphPicture{'+', "..... ..#.. ..#.. ##### ..#.. ..#.. ....."},
    GlyphPicture{'=', "..... ..... ##### ..... ##### ..... ....."},
    GlyphPicture{'%', "##... ##..# ...#. ..#.. .#... #..## ...##"},
    GlyphPicture{'(', "...#. ..#.. .#... .#... .#... ..#.. ...#."},
    GlyphPicture{')', ".#... ..#.. ...#. ...#. ...#. ..#.. .#..."},
    GlyphPicture{'?', ".###. #...# ....# ...#. ..#.. ..... ..#.."},
};

constexpr bool wellFormed() {
  for (const GlyphPicture& glyph : kFont) {
    if (glyph.rows.size() != kGlyphHeight * (kGlyphWidth + 1) - 1) return false;
    for (std::size_t i = 0; i < glyph.rows.size(); ++i) {
      const char c = glyph.rows[i];
      if ((i + 1) % (kGlyphWidth + 1) == 0 ? c != ' ' : c != '#' && c != '.') return false;
    }
  }
  return true;
}
static_assert(wellFormed(), "every glyph is 7 rows of 5 '#' or '.' separated by spaces");

const GlyphPicture& pictureOf(char character) {
  if (character >= 'a' && character <= 'z') character = char(character - 'a' + 'A');
  for (const GlyphPicture& glyph : kFont)
    if (glyph.character == character) return glyph;
  return kFont.back();  // '?'
}

constexpr std::uint32_t kAdvance = kGlyphWidth + 1;  // font pixels from one character to the next
constexpr std::uint32_t kLineHeight = kGlyphHeight + 2;
constexpr std::uint32_t kMargin = 2;

// `rect` cut to the image; zero-sized when outside it.
vk::Rect2D clip(std::int64_t x, std::int64_t y, std::int64_t width, std::int64_t height, vk::Extent2D extent) {
  const std::int64_t x1 = std::min<std::int64_t>(x + width, extent.width);
  const std::int64_t y1 = std::min<std::int64_t>(y + height, extent.height);
  x = std::min<std::int64_t>(x, extent.width);
  y = std::min<std::int64_t>(y, extent.height);
  return {
      .offset = {std::int32_t(x), std::int32_t(y)},
      .extent = {std::uint32_t(std::max<std::int64_t>(x1 - x, 0)), std::uint32_t(std::max<std::int64_t>(y1 - y, 0))}};
}

bool empty(const vk::Rect2D& rect) {
  return rect.extent.width == 0 || rect.extent.height == 0;
}

vk::ClearAttachment clearColor(const glm::vec3& color) {
  return {.aspectMask = vk::ImageAspectFlagBits::eColor,
          .colorAttachment = 0,
          .clearValue = {.color = {.float32 = std::array{color.r, color.g, color.b, 1.0f}}}};
}

}  // namespace

bool glyphPixel(char character, std::uint32_t column, std::uint32_t row) {
  if (column >= kGlyphWidth || row >= kGlyphHeight) return false;
  return pictureOf(character).rows[row * (kGlyphWidth + 1) + column] == '#';
}

TextLayout layoutText(std::span<const std::string> lines, const TextOverlaySettings& settings, vk::Extent2D extent) {
  TextLayout layout;
  const std::int64_t scale = std::max<std::uint32_t>(settings.scale, 1);
  std::size_t longest = 0;
  for (const std::string& line : lines) longest = std::max(longest, line.size());
  if (longest == 0) return layout;
  const std::int64_t left = std::int64_t(settings.origin.x) + kMargin * scale;
  const std::int64_t top = std::int64_t(settings.origin.y) + kMargin * scale;
  layout.panel =
      clip(settings.origin.x, settings.origin.y, (std::int64_t(longest) * kAdvance - 1 + 2 * kMargin) * scale,
           (std::int64_t(lines.size()) * kLineHeight - 2 + 2 * kMargin) * scale, extent);
  for (std::size_t l = 0; l < lines.size(); ++l)
    for (std::size_t c = 0; c < lines[l].size(); ++c)
      for (std::uint32_t row = 0; row < kGlyphHeight; ++row)
        for (std::uint32_t column = 0; column < kGlyphWidth;) {
          if (!glyphPixel(lines[l][c], column, row)) {
            ++column;
            continue;
          }
          std::uint32_t end = column;
          while (end < kGlyphWidth && glyphPixel(lines[l][c], end, row)) ++end;
          const vk::Rect2D run =
              clip(left + (std::int64_t(c) * kAdvance + column) * scale,
                   top + (std::int64_t(l) * kLineHeight + row) * scale, (end - column) * scale, scale, extent);
          if (!empty(run)) layout.text.push_back(run);
          column = end;
        }
  return layout;
}

void recordTextOverlay(const vk::raii::CommandBuffer& commands, const Image& image, const TextLayout& layout,
                       const TextOverlaySettings& settings) {
  if (empty(layout.panel)) return;
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  transition(commands, image, Layout::eTransferSrcOptimal, Layout::eColorAttachmentOptimal, Stage::eTransfer,
             Access::eTransferRead, Stage::eColorAttachmentOutput,
             Access::eColorAttachmentRead | Access::eColorAttachmentWrite);
  // Load: the overlay covers a corner; the rest of the frame stays.
  const vk::RenderingAttachmentInfo color{.imageView = *image.view(),
                                          .imageLayout = Layout::eColorAttachmentOptimal,
                                          .loadOp = vk::AttachmentLoadOp::eLoad,
                                          .storeOp = vk::AttachmentStoreOp::eStore};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = image.extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color});
  commands.clearAttachments(clearColor(settings.panelColor),
                            vk::ClearRect{.rect = layout.panel, .baseArrayLayer = 0, .layerCount = 1});
  if (!layout.text.empty()) {
    std::vector<vk::ClearRect> rects;
    rects.reserve(layout.text.size());
    for (const vk::Rect2D& rect : layout.text) rects.push_back({.rect = rect, .baseArrayLayer = 0, .layerCount = 1});
    commands.clearAttachments(clearColor(settings.textColor), rects);
  }
  commands.endRendering();
  transition(commands, image, Layout::eColorAttachmentOptimal, Layout::eTransferSrcOptimal,
             Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eTransfer, Access::eTransferRead);
}

}  // namespace mane::render
