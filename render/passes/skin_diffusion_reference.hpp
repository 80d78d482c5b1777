#pragma once
// The CPU reference of texture-space diffusion's blurs (render/passes/skin_diffusion_pass.hpp): the
// same cascade, taps, weights, normalisation and resolve as shaders/skin_diffusion_blur.comp
// (render/passes/skin_diffusion_kernel.hpp), in double precision, for tests that compare the GPU
// with it. Slow (a 256² map takes well under a second): not for frames.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/luts/skin_profile.hpp"

namespace mane::render {

/// The inputs of the blurs, as texels, row-major (texel (i, j) at j·size + i, v = 0 on row 0).
struct SkinDiffusionMaps {
  std::uint32_t size = 0;
  /// size² texels: rgb the irradiance times the coverage, a the coverage (1 on the mesh, 0 off it).
  std::vector<glm::vec4> irradiance;
  /// size² texels: millimetres of surface per texel along u (x) and v (y); 0 off the mesh.
  std::vector<glm::vec2> stretch;
};

/// The diffused irradiance, size² texels: rgb = Σ_i w_i·blur_i(E·c) / Σ_i w_i·blur_i(c) per
/// channel (0 where that coverage is below kSkinMinCoverage), a = the least of the three
/// blurred coverages. Texels off the mesh blur with `uncoveredStretch` mm per texel.
/// Precondition: both maps hold size² texels.
std::vector<glm::vec4> diffuseSkinIrradianceReference(const SkinDiffusionMaps& maps, const SkinProfile& profile,
                                                      double uncoveredStretch);

}  // namespace mane::render
