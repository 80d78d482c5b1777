#include "render/luts/fur_shells.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mane::render {
namespace {

// Rec. ITU-R BT.709 relative luminance weights (linear RGB).
constexpr double kRedWeight = 0.2126;
constexpr double kGreenWeight = 0.7152;
constexpr double kBlueWeight = 0.0722;

float orderStatistic(std::vector<float>& values, double fraction) {
  const auto rank = static_cast<std::size_t>(std::floor(fraction * double(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(rank), values.end());
  return values[rank];
}

}  // namespace

float linearFromSrgb(std::uint8_t value) {
  const double encoded = value / 255.0;
  const double linear = encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
  return static_cast<float>(linear);
}

float photoLuminance(std::uint8_t red, std::uint8_t green, std::uint8_t blue) {
  return static_cast<float>(kRedWeight * linearFromSrgb(red) + kGreenWeight * linearFromSrgb(green) +
                            kBlueWeight * linearFromSrgb(blue));
}

std::vector<float> photoLuminances(const TextureData& photo) {
  const std::size_t pixels = std::size_t(photo.width) * photo.height;
  std::vector<float> luminances(std::min(pixels, photo.rgba.size() / 4));
  for (std::size_t i = 0; i < luminances.size(); ++i)
    luminances[i] = photoLuminance(photo.rgba[4 * i], photo.rgba[4 * i + 1], photo.rgba[4 * i + 2]);
  return luminances;
}

Result<LuminanceRange> robustLuminanceRange(std::span<const float> luminances,
                                            const LuminancePercentiles& percentiles) {
  if (luminances.empty()) return fail("fur photo luminance range: the photo has no pixels");
  if (!(percentiles.low >= 0.0 && percentiles.low < percentiles.high && percentiles.high <= 1.0))
    return fail("fur photo luminance range: percentiles must satisfy 0 ≤ low < high ≤ 1, got low " +
                std::to_string(percentiles.low) + " and high " + std::to_string(percentiles.high));
  std::vector<float> sorted(luminances.begin(), luminances.end());
  LuminanceRange range;
  range.minimum = std::max(orderStatistic(sorted, percentiles.low), kMinimumLuminance);
  range.maximum = orderStatistic(sorted, percentiles.high);
  if (!(range.maximum > range.minimum))
    return fail("fur photo luminance range: I_max (" + std::to_string(range.maximum) + ") is not above I_min (" +
                std::to_string(range.minimum) + "): a photo without contrast gives no depth");
  return range;
}

std::vector<std::uint32_t> luminanceHistogram(std::span<const float> luminances, std::uint32_t bins) {
  std::vector<std::uint32_t> counts(std::max(bins, 1u), 0);
  const double last = double(counts.size() - 1);
  for (const float luminance : luminances) {
    const double bin = std::clamp(std::floor(double(luminance) * double(counts.size())), 0.0, last);
    ++counts[static_cast<std::size_t>(bin)];
  }
  return counts;
}

Result<FurShellModel> FurShellModel::create(LuminanceRange range, std::uint32_t layers, float thickness) {
  if (layers == 0 || layers > kMaxFurLayers)
    return fail("fur shells: the layer count must be 1 … " + std::to_string(kMaxFurLayers) + ", got " +
                std::to_string(layers));
  if (!(std::isfinite(thickness) && thickness > 0.0f))
    return fail("fur shells: the thickness h_b must be a finite number of metres > 0, got " +
                std::to_string(thickness));
  if (!(std::isfinite(range.maximum) && range.minimum > 0.0f && range.maximum > range.minimum))
    return fail("fur shells: the luminance range needs 0 < I_min < I_max, got I_min " + std::to_string(range.minimum) +
                " and I_max " + std::to_string(range.maximum));
  return FurShellModel(range, layers, thickness);
}

Result<FurShellModel> FurShellModel::fromPhoto(const TextureData& photo, const FurShellSettings& settings) {
  const std::string name = "fur photo (" + std::to_string(photo.width) + "×" + std::to_string(photo.height) + ")";
  if (photo.rgba.size() < std::size_t(photo.width) * photo.height * 4)
    return fail(name + ": " + std::to_string(photo.rgba.size()) + " bytes of texels, fewer than width × height × 4");
  const std::vector<float> luminances = photoLuminances(photo);
  auto range = robustLuminanceRange(luminances, settings.percentiles);
  if (!range) return fail(name + ": " + range.error().message);
  auto model = create(*range, settings.layers, settings.thickness);
  if (!model) return fail(name + ": " + model.error().message);
  return model;
}

double FurShellModel::attenuation() const {
  return std::log(double(range_.maximum) / double(range_.minimum)) / double(thickness_);
}

double FurShellModel::threshold(std::uint32_t n) const {
  const double logRatio = std::log(double(range_.maximum) / double(range_.minimum));
  return double(range_.maximum) * std::exp(-logRatio * double(n) / double(layers_));
}

std::vector<float> FurShellModel::thresholds() const {
  std::vector<float> values(layers_ + 1);
  for (std::uint32_t n = 0; n <= layers_; ++n) values[n] = static_cast<float>(threshold(n));
  return values;
}

double FurShellModel::depthOf(double luminance) const {
  const double depth = std::log(double(range_.maximum) / std::max(luminance, 1e-30)) / attenuation();
  return std::clamp(depth, 0.0, double(thickness_));
}

std::uint32_t FurShellModel::layerOf(double luminance) const {
  // Compared against the same I(n) the GPU reads, so that a pixel exactly on an edge lands in
  // the same layer on both (I(n) ≤ I < I(n−1)).
  for (std::uint32_t n = 1; n < layers_; ++n)
    if (luminance >= threshold(n)) return n;
  return layers_;
}

double FurShellModel::layerDepth(std::uint32_t n) const {
  return double(thickness_) * double(n) / double(layers_);
}

std::vector<std::uint32_t> layerPixelCounts(const FurShellModel& model, std::span<const float> luminances) {
  std::vector<std::uint32_t> counts(model.layers(), 0);
  for (const float luminance : luminances) ++counts[model.layerOf(luminance) - 1];
  return counts;
}

}  // namespace mane::render
