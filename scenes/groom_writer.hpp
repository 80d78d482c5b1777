#pragma once
// Guide strands → Cem Yuksel's HAIR format (`.hair`), the format loadCyHair (groom_loader.hpp)
// reads: for handing a simulated groom to other tools (`mane sim --save`).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::scenes {

/// The HAIR bytes of strands laid out one after another in `points` (`pointsPerStrand[s]` points
/// each, root first, in the caller's units): the 128-byte header with the segments and points
/// arrays announced (flags 1 | 2), a default thickness of 0 (none), transparency 0 and a white
/// colour (no look of their own: scenes/groom_looks.hpp), `info` (at most 87 bytes kept,
/// zero-padded) in the header's text field; then uint16
/// segments per strand and float3 points, little-endian. Errors: no strands, a strand of fewer
/// than 2 or more than 65,536 points (the format's uint16 segment count), counts that do not add
/// up to `points.size()`.
[[nodiscard]] Result<std::vector<unsigned char>> encodeCyHair(std::span<const std::uint32_t> pointsPerStrand,
                                                              std::span<const glm::vec3> points,
                                                              std::string_view info = {});

/// encodeCyHair written to `file` (its folder created); errors name the file.
[[nodiscard]] Result<void> writeCyHair(const std::filesystem::path& file,
                                       std::span<const std::uint32_t> pointsPerStrand,
                                       std::span<const glm::vec3> points, std::string_view info = {});

}  // namespace mane::scenes
