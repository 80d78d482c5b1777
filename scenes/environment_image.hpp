#pragma once
// Environment panoramas read from Radiance RGBE (.hdr) or OpenEXR (.exr) files: linear RGB
// radiance, equirectangular.

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
  std::size_t clampedTexels = 0;  ///< texels with a channel above kMaxPanoramaRadiance, clamped to it
  std::size_t zeroedTexels = 0;   ///< texels with a channel negative or not a number (OpenEXR), set to 0
};

/// Decodes a panorama, told apart by its first bytes: a Radiance `.hdr` (stb_image's reader: RLE
/// or flat RGBE scanlines, "-Y h +X w" orientation) or an OpenEXR file (render/exr.hpp: R, G, B
/// or Y channels of any pixel type). Errors name the file and the problem: neither format, a
/// header declaring more than 16384 pixels on a side or 8192 × 8192 in all, a file cut short or
/// damaged, a panorama that is not twice as wide as it is high (within a pixel). Channels above
/// kMaxPanoramaRadiance are clamped to it, negative or NaN ones set to 0, and the texels counted.
[[nodiscard]] Result<Panorama> loadEnvironmentImage(const std::filesystem::path& file);

}  // namespace mane::scenes
