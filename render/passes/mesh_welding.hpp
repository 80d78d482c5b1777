#pragma once
// Vertices that files split (at uv seams, hard edges) but that are one point of the surface.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace mane::render {

/// Per vertex, the first vertex at the same position (bit for bit, −0 and +0 alike): vertices
/// split at a uv seam keep their positions exactly, so equal positions are one point.
[[nodiscard]] std::vector<std::uint32_t> weldByPosition(std::span<const glm::vec3> positions);

}  // namespace mane::render
