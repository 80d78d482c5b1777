#include "render/passes/skin_diffusion_kernel.hpp"

#include <algorithm>
#include <cmath>

namespace mane::render {

std::array<SkinDiffusionStage, kSkinGaussianCount> skinDiffusionStages(const SkinProfile& profile) {
  std::array<SkinGaussian, kSkinGaussianCount> sorted = profile.gaussians;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const SkinGaussian& a, const SkinGaussian& b) { return a.variance < b.variance; });
  std::array<SkinDiffusionStage, kSkinGaussianCount> stages;
  double previous = 0.0;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const double sigma = std::sqrt(std::max(sorted[i].variance - previous, 0.0));
    // The input of this blur is the previous Gaussian, of width sqrt(previous) (none: the raw
    // irradiance); sparse taps must not be farther apart than that.
    const double sparseSpacing = kSkinBlurReach * sigma / kSkinBlurSparseHalfTaps;
    const bool dense = i == 0 || sparseSpacing > std::sqrt(previous);
    stages[i] = {.variance = sorted[i].variance,
                 .sigma = sigma,
                 .weight = sorted[i].weight,
                 .halfTaps = dense ? kSkinBlurDenseHalfTaps : kSkinBlurSparseHalfTaps};
    previous = sorted[i].variance;
  }
  return stages;
}

double skinBlurTapOffset(double sigmaTexels, int halfTaps, int k) {
  const double spacing = std::max(1.0, kSkinBlurReach * sigmaTexels / halfTaps);
  return std::floor(k * spacing + 0.5);
}

double skinUncoveredStretch(std::span<const glm::vec2> stretch) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const glm::vec2& texel : stretch)
    for (int axis = 0; axis < 2; ++axis)
      if (std::isfinite(texel[axis]) && texel[axis] > 0.0f) {
        sum += texel[axis];
        ++count;
      }
  return count > 0 ? sum / double(count) : 1.0;
}

}  // namespace mane::render
