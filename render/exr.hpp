#pragma once
// Linear HDR images to and from OpenEXR files (the OpenEXR library): frames written as fp16 RGB,
// panoramas read from any scanline or tiled file with R, G, B (or Y) channels.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "common/error.hpp"

namespace mane::render {

/// Files larger than this on a side, or than kMaxExrPixels in all, are refused before anything
/// is allocated for their pixels.
inline constexpr int kMaxExrSide = 16384;
inline constexpr long long kMaxExrPixels = 8192LL * 8192;

/// Linear RGBA texels of an OpenEXR file's data window, rows top to bottom.
struct ExrImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;
};

/// Decodes the first part of an OpenEXR file held in `bytes`; `name` names it in errors. Reads
/// R, G, B and A (1 where absent), or Y alone as grey; any pixel type (half, float, uint) becomes
/// float. Errors name the file and the problem: not an OpenEXR file, deep data, no colour
/// channels (the ones found are listed), sub-sampled colour channels, a data window past the
/// size limits, or the library's own complaint about a damaged file.
[[nodiscard]] Result<ExrImage> decodeExr(std::span<const unsigned char> bytes, const std::string& name);

/// Writes `rgbaHalf` (fp16 bit patterns, four a texel, rows top to bottom, linear) as an OpenEXR
/// file of half R, G, B channels, ZIP-compressed; alpha is dropped, a frame being opaque. The
/// parent folder is created when missing.
Result<void> writeExr(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                      std::span<const std::uint16_t> rgbaHalf);

}  // namespace mane::render
