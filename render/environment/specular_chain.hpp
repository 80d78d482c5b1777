#pragma once
// The environment's radiance pre-filtered for glossy reflection, baked on the GPU in a compute
// pass (shaders/environment_prefilter.comp): a cube map whose mip level ℓ holds the radiance
// pre-filtered for GGX roughness ℓ/7 (render/environment/specular_reference.hpp has the integral
// and its brute-force CPU reference). Each texel of levels 1 to 7 averages directions
// importance-sampled from the GGX lobe (a Hammersley set), each looked up in the source's mip
// chain at the level whose texels match the sample's share of the lobe (Křivánek and Colbert's
// filtered importance sampling, GPU Gems 3, ch. 20, without their one-level bias: the box-filtered
// mips of a cube's faces leak across the horizon enough already); level 0, the mirror, is the
// source resampled.

#include <algorithm>
#include <cstdint>

#include "common/error.hpp"
#include "render/environment/environment_map.hpp"
#include "render/resources.hpp"

namespace mane::render {

class SpecularChain {
public:
  static constexpr std::uint32_t kLevels = 8;

  /// Directions sampled per texel at level ℓ ≥ 1: 64 × 2^(ℓ−1), at most 1024. Rougher levels have
  /// fewer texels and wider lobes: more samples there keep each one's footprint (and so the mip
  /// it reads) small, for little cost.
  [[nodiscard]] static std::uint32_t samplesOf(std::uint32_t level) {
    return level == 0 ? 1u : std::min(64u << (level - 1), 1024u);
  }

  /// Bakes the chain from `source` (a sampled cube with its mip chain, in SHADER_READ_ONLY layout)
  /// at `baseSize` texels a side for level 0 (a power of two ≥ 128, so that level 7 keeps a texel).
  [[nodiscard]] static Result<SpecularChain> bake(const Device& device, const Image& source,
                                                  const vk::raii::Sampler& sampler, std::uint32_t baseSize);

  /// The roughness level ℓ is pre-filtered for.
  [[nodiscard]] static float roughnessOf(std::uint32_t level) { return float(level) / float(kLevels - 1); }

  /// The cube, all levels, in SHADER_READ_ONLY layout.
  [[nodiscard]] const Image& image() const { return image_; }

  /// A host copy of level `level` (for tests and tools).
  [[nodiscard]] CubeMap readLevel(const Device& device, std::uint32_t level) const;

private:
  Image image_;
};

/// Uploads `cube` as a sampled fp16 cube map with its mip chain (each level a linear 2 × 2 box of
/// the one above), in SHADER_READ_ONLY layout. Radiance above fp16's largest value is clamped to it.
[[nodiscard]] Image uploadCubeWithMips(const Device& device, const CubeMap& cube);

}  // namespace mane::render
