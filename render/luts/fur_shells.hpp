#pragma once
// Shell-texture thresholds from a single photograph of fur (Ukaji, Kosaka, Hattori, Kubo,
// Morishima, "Feature Extraction and Real-time Rendering of Fur from Realistic Image", one of the
// source documents, docs/design.md#sources; "[U]" below). The CPU reference of what
// FurPass (render/passes/fur_pass.hpp) draws: the GPU reads the thresholds this file computes.
//
// The model [U §3.1]. Fur is a scattering medium of thickness h_b over the skin. Light entering
// from above decays exponentially with the depth h below the fur's top surface, so a photo taken
// from above shows, at each pixel, a luminance that says how deep the fur there ends:
//   I = I_max · e^(−a·h)                                                         [U eq. 1]
//   a = ln(I_max / I_min) / h_b                                                  [U eq. 2]
// Bright pixels are hair tips near the top (h ≈ 0), dark ones are deep, near the skin (h ≈ h_b).
// I_min must be > 0 (the decay never reaches zero): it is floored at kMinimumLuminance.
//
// The layers [U §3.2]. With N layers, layer n (n = 0 … N) lies at depth h = h_b·n/N below the
// top [U eq. 3]; n = 0 is the fur's top surface, n = N the skin. Putting eq. 3 into eq. 1:
//   I(n) = I_max · e^(−ln(I_max/I_min)·n/N)                                      [U eq. 4]
// and the photo is split into N shell textures with the I(n) as bin edges: layer n (1 … N) holds
// the pixels with I(n) ≤ I < I(n−1). In depth terms a pixel of luminance I ends at
// h(I) = ln(I_max/I)/a, and layer n holds those with h(n−1) < h(I) ≤ h(n): each pixel lies in
// exactly one layer, the first one at or below where its fur ends. Pixels brighter than I_max
// (ignored outliers) go to layer 1, darker than I_min to layer N, so the layers partition the
// photo: layerOf(I) = clamp(ceil(N · ln(I_max/I) / ln(I_max/I_min)), 1, N).
// Why this reproduces the photo: seen from straight above, each pixel is drawn once, with its
// own colour, so the stack shows the photo; seen from an angle, bright pixels stand higher than
// dark ones and give parallax, which is the fur's relief.
//
// What goes to the GPU [U §3.3]: only the photo, once; the layer's two thresholds I(n) and
// I(n−1) per draw. FurShellModel::thresholds() gives I(0 … N) for that.
//
// Luminance. [U] greyscales the photo without saying how. We use relative luminance as
// Rec. ITU-R BT.709 defines it, Y = 0.2126 R + 0.7152 G + 0.0722 B, on linear RGB: the photo's
// 8-bit sRGB values are decoded with the IEC 61966-2-1 transfer function first. Linear values
// are what eq. 1 is about (light decaying in a medium), and the GPU gets the same numbers by
// sampling the photo through an sRGB texture format.
//
// Robust I_max and I_min. [U §3.2] asks for thresholds that ignore "small noise far from the
// histogram's mountain". We take percentiles of the luminances (exact order statistics, what a
// fine histogram approximates): I_min at the 1st and I_max at the 99th by default. A few
// specular glints or dead pixels (sensor noise, JPEG ringing at dark hair) are well under 1 % of
// a fur photo, so they fall outside, while 98 % of the pixels set the range. Pixels beyond the
// percentiles still land in the first or last layer.
//
// Units: h_b in metres; luminances are linear relative luminance in [0, 1].

#include <cstdint>
#include <span>
#include <vector>

#include "common/error.hpp"
#include "render/frame.hpp"

namespace mane::render {

/// Darkest I_min used: eq. 2 needs I_min > 0. 1e-3 is a linear luminance darker than sRGB code
/// value 1 on every channel (≈ 3e-4 each) rounded up — below any exposure a fur photo uses.
inline constexpr float kMinimumLuminance = 1e-3f;

/// sRGB code value (0 … 255) → linear value in [0, 1] (IEC 61966-2-1).
[[nodiscard]] float linearFromSrgb(std::uint8_t value);

/// Relative luminance (Rec. 709 weights on linearised sRGB) of one 8-bit sRGB colour.
[[nodiscard]] float photoLuminance(std::uint8_t red, std::uint8_t green, std::uint8_t blue);

/// The luminance of every pixel of `photo`, rows top to bottom. Alpha is ignored.
[[nodiscard]] std::vector<float> photoLuminances(const TextureData& photo);

/// Which order statistics bound the photo's luminance range.
struct LuminancePercentiles {
  double low = 0.01;   ///< fraction of pixels allowed below I_min
  double high = 0.99;  ///< fraction of pixels allowed at or below I_max
};

struct LuminanceRange {
  float minimum = 0.0f;  ///< I_min, ≥ kMinimumLuminance
  float maximum = 0.0f;  ///< I_max
};

/// I_min and I_max as the `percentiles` of `luminances` (the value at rank ⌊p·(count − 1)⌋ of
/// the sorted values), I_min floored at kMinimumLuminance. Errors: no luminances, percentiles
/// outside 0 ≤ low < high ≤ 1, or I_max ≤ I_min (a photo with no contrast has no depth).
[[nodiscard]] Result<LuminanceRange> robustLuminanceRange(std::span<const float> luminances,
                                                          const LuminancePercentiles& percentiles = {});

/// Pixel counts of `luminances` over `bins` equal bins on [0, 1] (values outside go to the end bins).
[[nodiscard]] std::vector<std::uint32_t> luminanceHistogram(std::span<const float> luminances, std::uint32_t bins);

struct FurShellSettings {
  std::uint32_t layers = 15;  ///< N, 1 … kMaxFurLayers ([U] uses 8 on a square and 15 on meshes)
  float thickness = 0.01f;    ///< h_b, metres
  LuminancePercentiles percentiles;
};

/// The most layers FurPass draws: its uniform block holds I(0 … 64) whatever N is.
inline constexpr std::uint32_t kMaxFurLayers = 64;

/// Eqs. 1–4 of [U] for one photo: the luminance ↔ depth map and the layer thresholds.
class FurShellModel {
public:
  /// The model of a photo whose luminances span `range`. Errors: no layers or more than
  /// kMaxFurLayers, a thickness that is not a finite number > 0, or a range with I_max ≤ I_min.
  [[nodiscard]] static Result<FurShellModel> create(LuminanceRange range, std::uint32_t layers, float thickness);

  /// Luminances → robustLuminanceRange → create. Errors name the photo's size and the cause.
  [[nodiscard]] static Result<FurShellModel> fromPhoto(const TextureData& photo, const FurShellSettings& settings = {});

  [[nodiscard]] LuminanceRange range() const { return range_; }
  [[nodiscard]] std::uint32_t layers() const { return layers_; }
  /// h_b, metres.
  [[nodiscard]] float thickness() const { return thickness_; }
  /// a = ln(I_max/I_min)/h_b, 1/metre (eq. 2).
  [[nodiscard]] double attenuation() const;
  /// I(n) for n = 0 … N (eq. 4): I(0) = I_max, I(N) = I_min.
  [[nodiscard]] double threshold(std::uint32_t n) const;
  /// I(0 … N), N + 1 values, decreasing.
  [[nodiscard]] std::vector<float> thresholds() const;
  /// Depth below the fur's top where fur of luminance I ends, h(I) = ln(I_max/I)/a, metres,
  /// clamped to [0, h_b] (eq. 1 solved for h).
  [[nodiscard]] double depthOf(double luminance) const;
  /// The layer 1 … N that holds a pixel of luminance I: I(n) ≤ I < I(n−1), clamped (file comment).
  [[nodiscard]] std::uint32_t layerOf(double luminance) const;
  /// Depth of layer n below the top, h_b·n/N (eq. 3), metres.
  [[nodiscard]] double layerDepth(std::uint32_t n) const;
  /// Height of layer n above the skin, h_b − layerDepth(n): where FurPass draws its shell.
  [[nodiscard]] double layerHeight(std::uint32_t n) const { return thickness_ - layerDepth(n); }

private:
  FurShellModel(LuminanceRange range, std::uint32_t layers, float thickness)
      : range_(range), layers_(layers), thickness_(thickness) {}

  LuminanceRange range_;
  std::uint32_t layers_;
  float thickness_;
};

/// Pixels per layer: entry n − 1 counts the luminances with layerOf = n (N entries).
[[nodiscard]] std::vector<std::uint32_t> layerPixelCounts(const FurShellModel& model,
                                                          std::span<const float> luminances);

}  // namespace mane::render
