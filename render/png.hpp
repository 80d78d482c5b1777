#pragma once
// 8-bit RGBA images to and from PNG files (stb).

#include <cstdint>
#include <filesystem>
#include <span>

#include "common/error.hpp"

namespace mane::render {

/// Writes tightly packed RGBA8 texels (rows top to bottom) as a PNG; the parent folder is
/// created when missing.
Result<void> writePng(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                      std::span<const std::uint8_t> rgba);

}  // namespace mane::render
