#pragma once
// 8-bit RGBA images (textures, fur photos) read from PNG or JPEG.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "common/error.hpp"

namespace mane::scenes {

/// Pixels in rows from the top of the image, 4 bytes (R, G, B, A) each; images without
/// alpha get A = 255, greyscale images repeat the grey in R, G and B. Values are the file's
/// encoded values (sRGB for colour maps, linear for data maps: the caller knows which).
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes
};

/// Decodes a PNG or JPEG (anything stb_image reads) to RGBA8. Errors name the file and give
/// stb_image's reason (for example "bad png sig" or "unknown image type"). Images larger than
/// 16384 pixels on a side or 8192 x 8192 pixels in all are refused before decoding.
[[nodiscard]] Result<Image> loadImage(const std::filesystem::path& file);

}  // namespace mane::scenes
