#pragma once
// The Marschner hair lookup tables on the GPU: a compute shader (shaders/marschner_lut.comp)
// bakes the longitudinal table M and the azimuthal table N of render/luts/marschner.hpp for one
// groom's HairShadingParams, then a chain of linear blits builds their mip maps, as the Nalu
// demo mip-maps its tables (GPU Gems 2 ch. 23) so strands whose tangent turns within a pixel read
// a filtered lobe. A hair pass samples them with hairScattering() from shaders/hair_shading.glsl.
//
// Layout. Texel centre i of n sits at parameter x = i/(n − 1) (both ends of a range on texel
// centres).
//   M: kLongitudinalSize², RGBA16F. x = (θi/π + ½, θr/π + ½); rgb = (M_R, M_TT, M_TRT), a = 0.
//   N: kAzimuthalWidth × kAzimuthalHeight, 2 layers, RGBA32F. x = (φ/π, cos θr);
//      layer 0 = (N_TT.rgb, N_R), layer 1 = (N_TRT.rgb, 0).
// A shader recovers all three lobes with one fetch of M and one of each N layer.
//
// Why not Nalu's exact parameterisation, M over (sin θi, sin θr) and N over (cos φ, cos θd):
//  - M over angles: near the poles a lobe of width β spans only ~β²/2 in sin θ (a texel of 1024
//    over [−1, 1] is 0.002, β_TT² = 0.004), so bilinear filtering in sin θ misses the lobe
//    shape; uniform in θ every lobe of the default groom covers ≥ 20 texels per β.
//  - N over φ: TRT's caustic sits near φ = 0 when η' approaches 2; in cos φ a peak of width β_N
//    at φ = 0 decays over only β_N²/2; uniform φ keeps it ~14 texels wide (β_N = 10°, 256).
//  - N over cos θr rather than cos θd: the attenuation is evaluated at the eye's angle (pbrt's
//    formulation, see marschner.hpp), which is what bounds the white-furnace albedo by 1. N has
//    twice as many rows as columns because TRT's caustic moves quickly with η'(θr) where η'
//    crosses 2 (cos θr ≈ 0.68 for η = 1.55).
//  - M in half floats (relative step 2^-11, values up to 1/β² ≤ 65504 for β ≥ 0.5°); N in
//    floats, since dark hair's TT/TRT values (down to ~1e-17) are below half's range.
// The test (tests/render/marschner_test.cpp) asks bilinear lookups at mip 0 to reproduce the CPU
// model within 1 % wherever a channel exceeds 1 % of its largest value; with the default lobe
// widths M stays within ~0.25 % and N within ~0.45 %. Lobes narrower than ~1° (M) or azimuthal
// widths under ~3° are undersampled.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/frame.hpp"
#include "render/luts/marschner.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// The two tables of a MarschnerLut.
enum class MarschnerTable : std::uint8_t { kLongitudinal, kAzimuthal };

class MarschnerLut {
public:
  static constexpr std::uint32_t kLongitudinalSize = 1024;  ///< texels per side of M
  static constexpr std::uint32_t kAzimuthalWidth = 256;     ///< texels of N along φ
  static constexpr std::uint32_t kAzimuthalHeight = 512;    ///< texels of N along cos θr
  static constexpr std::uint32_t kAzimuthalLayers = 2;
  static constexpr vk::Format kLongitudinalFormat = vk::Format::eR16G16B16A16Sfloat;
  static constexpr vk::Format kAzimuthalFormat = vk::Format::eR32G32B32A32Sfloat;
  /// Narrowest longitudinal width β_p the half-float M table holds (0.5°, radians).
  static constexpr float kMinimumLobeWidth = 0.008727f;

  /// Bakes both tables and their mip chains for `params` and waits for the GPU. Errors: invalid
  /// params (validate(), or a lobe narrower than kMinimumLobeWidth), a device whose formats lack
  /// storage, blit or linear filtering, or a Vulkan failure.
  static Result<MarschnerLut> create(const Device& device, const HairShadingParams& params);

  MarschnerLut(MarschnerLut&&) noexcept = default;
  MarschnerLut& operator=(MarschnerLut&&) noexcept = default;

  /// M, all mips, SHADER_READ_ONLY layout: a sampler2D.
  const vk::raii::ImageView& longitudinalView() const { return longitudinal_.view; }
  /// N, all mips and both layers, SHADER_READ_ONLY layout: a sampler2DArray.
  const vk::raii::ImageView& azimuthalView() const { return azimuthal_.view; }
  /// Trilinear, clamped to the edges: what hairScattering() expects.
  const vk::raii::Sampler& sampler() const { return sampler_; }
  const HairShadingParams& params() const { return params_; }
  /// Mip levels of `table` (a full chain down to 1×1).
  std::uint32_t mipLevels(MarschnerTable table) const;
  /// Texels of mip 0 of `table`.
  vk::Extent2D extent(MarschnerTable table) const;
  /// GPU time of the bake's steps ("longitudinal", "azimuthal", "mips"); empty without timestamps.
  const std::vector<PassTiming>& bakeTimings() const { return timings_; }

  /// The texels of mip `level` of `table` read back to the host (for tests and tools): texel
  /// (i, j) of layer l at (l·height + j)·width + i; half floats widened.
  Result<std::vector<glm::vec4>> readTexels(MarschnerTable table, std::uint32_t level) const;

private:
  struct Table {
    vk::raii::Image image{nullptr};
    Allocation allocation;
    vk::raii::ImageView view{nullptr};
    vk::Extent2D extent{};
    std::uint32_t layers = 1;
    std::uint32_t levels = 1;
    vk::Format format = vk::Format::eUndefined;
  };

  MarschnerLut() = default;
  static Table makeTable(const Device& device, vk::Extent2D extent, std::uint32_t layers, vk::Format format);
  void bake();

  const Device* device_ = nullptr;
  HairShadingParams params_;
  Table longitudinal_;
  Table azimuthal_;
  vk::raii::Sampler sampler_{nullptr};
  std::vector<PassTiming> timings_;
};

}  // namespace mane::render
