#include "render/passes/skin_diffusion_reference.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "render/passes/skin_diffusion_kernel.hpp"

namespace mane::render {
namespace {

using Texels = std::vector<glm::dvec4>;

// One blur along `axis` (0: u, rows; 1: v, columns), as shaders/skin_diffusion_blur.comp does it.
Texels blurAxis(const Texels& source, const std::vector<glm::vec2>& stretch, int size, int axis,
                const SkinDiffusionStage& stage, double uncoveredStretch) {
  auto fetch = [&](glm::ivec2 texel) {
    // Outside the map: transparent black, no coverage.
    if (texel.x < 0 || texel.y < 0 || texel.x >= size || texel.y >= size) return glm::dvec4(0.0);
    return source[std::size_t(texel.y) * size + texel.x];
  };
  const int halfTaps = stage.halfTaps;
  Texels result(source.size());
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::ivec2 texel(x, y);
      double mmPerTexel = stretch[std::size_t(y) * size + x][axis];
      if (!(mmPerTexel > 0.0)) mmPerTexel = uncoveredStretch;
      const double sigma = std::max(stage.sigma / mmPerTexel, kSkinBlurMinSigma);
      // Trapezoid weights on the rounded nodes: G(x_k)·(x_(k+1) − x_(k−1))/2, x_(−1) = −x_1.
      const double first = skinBlurTapOffset(sigma, halfTaps, 1);
      glm::dvec4 sum = first * fetch(texel);
      double total = first;
      for (int k = 1; k <= halfTaps; ++k) {
        const double offset = skinBlurTapOffset(sigma, halfTaps, k);
        const double gap = skinBlurTapOffset(sigma, halfTaps, k + 1) - skinBlurTapOffset(sigma, halfTaps, k - 1);
        const double weight = std::exp(-offset * offset / (2.0 * sigma * sigma)) * 0.5 * gap;
        glm::ivec2 ahead = texel, behind = texel;
        ahead[axis] += int(offset);
        behind[axis] -= int(offset);
        sum += weight * (fetch(ahead) + fetch(behind));
        total += 2.0 * weight;
      }
      result[std::size_t(y) * size + x] = sum / total;
    }
  return result;
}

}  // namespace

std::vector<glm::vec4> diffuseSkinIrradianceReference(const SkinDiffusionMaps& maps, const SkinProfile& profile,
                                                      double uncoveredStretch) {
  const int size = static_cast<int>(maps.size);
  const std::size_t texels = std::size_t(size) * size;
  assert(maps.irradiance.size() == texels && maps.stretch.size() == texels);
  Texels current(maps.irradiance.begin(), maps.irradiance.end());
  std::vector<glm::dvec3> accumulated(texels, glm::dvec3(0.0)), coverage(texels, glm::dvec3(0.0));
  for (const SkinDiffusionStage& stage : skinDiffusionStages(profile)) {
    const Texels across = blurAxis(current, maps.stretch, size, 0, stage, uncoveredStretch);
    current = blurAxis(across, maps.stretch, size, 1, stage, uncoveredStretch);
    for (std::size_t i = 0; i < texels; ++i) {
      accumulated[i] += stage.weight * glm::dvec3(current[i]);
      coverage[i] += stage.weight * current[i].a;
    }
  }
  std::vector<glm::vec4> result(texels);
  for (std::size_t i = 0; i < texels; ++i) {
    glm::dvec3 diffused(0.0);
    for (int c = 0; c < 3; ++c)
      if (coverage[i][c] >= kSkinMinCoverage) diffused[c] = accumulated[i][c] / coverage[i][c];
    const double least = std::min({coverage[i].r, coverage[i].g, coverage[i].b});
    result[i] = glm::vec4(glm::dvec4(diffused, least));
  }
  return result;
}

}  // namespace mane::render
