#pragma once
// A few lines of text over the finished output image: `mane view`'s frame time and the states of
// its toggles. A 5×7 bitmap font kept as constants; every lit run of a glyph row
// becomes one rectangle, filled with vkCmdClearAttachments inside a rendering pass that keeps the
// image's contents, over an opaque panel filled the same way. No shader, texture or descriptor.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/resources.hpp"

namespace mane::render {

/// Width and height of a glyph of the overlay's font, in font pixels.
inline constexpr std::uint32_t kGlyphWidth = 5;
inline constexpr std::uint32_t kGlyphHeight = 7;

/// Whether font pixel (`column`, `row`) of `character`'s glyph is lit; column 0 is the left, row
/// 0 the top. Lower-case letters draw as capitals; characters without a glyph as '?'.
bool glyphPixel(char character, std::uint32_t column, std::uint32_t row);

struct TextOverlaySettings {
  std::uint32_t scale = 2;     ///< image pixels per font pixel, ≥ 1
  glm::uvec2 origin{8, 8};     ///< the panel's top-left corner, image pixels
  glm::vec3 textColor{1.0f};   ///< linear RGB (the sRGB output image encodes it)
  glm::vec3 panelColor{0.0f};  ///< linear RGB, opaque
};

/// Where the overlay writes, in image pixels, clipped to `extent`: an opaque panel behind the
/// text (a margin of two font pixels around it), then one rectangle per lit run of a glyph row.
/// Characters advance 6 font pixels, lines 9.
struct TextLayout {
  vk::Rect2D panel{};
  std::vector<vk::Rect2D> text;
};
TextLayout layoutText(std::span<const std::string> lines, const TextOverlaySettings& settings, vk::Extent2D extent);

/// Records `layout` over `image` (single-sample, colour-attachment usage, in TRANSFER_SRC layout
/// as Renderer::record leaves its output, and left so for the swapchain's copy or a read-back).
void recordTextOverlay(const vk::raii::CommandBuffer& commands, const Image& image, const TextLayout& layout,
                       const TextOverlaySettings& settings);

}  // namespace mane::render
