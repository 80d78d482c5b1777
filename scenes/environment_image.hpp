#pragma once
// Environment panoramas read from Radiance RGBE files (.hdr): linear RGB radiance, equirectangular.

#include <filesystem>

#include "common/error.hpp"
#include "render/environment/environment_map.hpp"

namespace mane::scenes {

/// Decodes a Radiance `.hdr` panorama (stb_image's reader: RLE or flat RGBE scanlines, "-Y h +X w"
/// orientation). Errors name the file and the problem: not a Radiance file, a header declaring
/// more than 16384 pixels on a side or 8192 × 8192 in all, a file cut short, a panorama that is
/// not twice as wide as it is high (within a pixel).
[[nodiscard]] Result<render::EquirectImage> loadEnvironmentImage(const std::filesystem::path& file);

}  // namespace mane::scenes
