#pragma once
// A groom's per-strand looks (HairStrandLook, render/hair_data.hpp) on the GPU: one buffer that
// HairPass and HairLightingPass both read as RGBA32F texels (shaders/hair_strand_look.glsl), two
// per dense strand s:
//   texel 2s     = (widthScale, tipWidthScale, opacityScale, 0)
//   texel 2s + 1 = (colour.r, colour.g, colour.b, 0)
// A groom without looks gets factors of 1 for every strand: multiplying by 1 changes no bit, so
// its strands are drawn exactly as their settings alone would draw them.

#include <cstdint>
#include <span>

#include "common/error.hpp"
#include "render/hair_data.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// Checks the looks of a groom of `strandCount` dense strands: none, or one per strand with
/// every factor finite and in the range HairStrandLook documents. The message names the first
/// bad strand and starts in lower case, for the caller to put its subject before.
[[nodiscard]] Result<void> validateStrandLooks(std::span<const HairStrandLook> looks, std::size_t strandCount);

/// `looks` (valid for `strandCount` strands), or factors of 1 for all of them when empty, in a
/// device-local buffer with UNIFORM_TEXEL_BUFFER usage.
[[nodiscard]] Buffer uploadStrandLooks(const Device& device, std::span<const HairStrandLook> looks,
                                       std::uint32_t strandCount);

/// The groom's width and opacity as its hair shadows take them (one width and one opacity per
/// groom: render/passes/hair_shadow_pass.hpp): `settings`' own, scaled by the mean of the
/// strands' factors where there are looks.
struct ShadowedLook {
  float width = 0.0f;    ///< metres
  float opacity = 0.0f;  ///< in [0, 1]
};
[[nodiscard]] ShadowedLook shadowedLook(const HairGroomSettings& settings, std::span<const HairStrandLook> looks);

}  // namespace mane::render
