#pragma once
// Environment panoramas read from Radiance RGBE files (.hdr): linear RGB radiance, equirectangular.

#include <cstddef>
#include <filesystem>

#include "common/error.hpp"
#include "render/environment/environment_map.hpp"

namespace mane::scenes {

/// Radiance beyond this (RGBE reaches 1.7e38) is clamped to it: sums of a few such texels would
/// overflow single precision, and no sky or lamp comes near it in the lights' units.
inline constexpr float kMaxPanoramaRadiance = 1e9f;

struct Panorama {
  render::EquirectImage image;
  std::size_t clampedTexels = 0;  ///< texels whose radiance was above kMaxPanoramaRadiance
};

/// Decodes a Radiance `.hdr` panorama (stb_image's reader: RLE or flat RGBE scanlines, "-Y h +X w"
/// orientation). Errors name the file and the problem: not a Radiance file, a header declaring
/// more than 16384 pixels on a side or 8192 × 8192 in all, a file cut short, a panorama that is
/// not twice as wide as it is high (within a pixel). Texels above kMaxPanoramaRadiance are
/// clamped to it and counted.
[[nodiscard]] Result<Panorama> loadEnvironmentImage(const std::filesystem::path& file);

}  // namespace mane::scenes
