#include "render/hair_order.hpp"

#include <algorithm>
#include <numeric>

#include <glm/geometric.hpp>

namespace mane::render {

StrandDrawOrder::StrandDrawOrder(const DenseStrandLayout& layout) {
  const std::uint32_t guides = std::max<std::uint32_t>(layout.guideCount, 1);
  const auto primary = [&](const DenseStrand& strand) { return strand.guides[0] < guides ? strand.guides[0] : 0u; };
  // Counting sort by primary guide: counts, prefix sums, then placement in layout order.
  firstStrand_.assign(guides + 1, 0);
  for (const DenseStrand& strand : layout.strands) ++firstStrand_[primary(strand) + 1];
  std::partial_sum(firstStrand_.begin(), firstStrand_.end(), firstStrand_.begin());
  strands_.resize(layout.strands.size());
  std::vector<std::uint32_t> next(firstStrand_.begin(), firstStrand_.end() - 1);
  for (std::uint32_t s = 0; s < layout.strands.size(); ++s) strands_[next[primary(layout.strands[s])]++] = s;
  guides_.resize(guides);
  distances_.resize(guides);
  order_.resize(strands_.size());
}

std::span<const std::uint32_t> StrandDrawOrder::backToFront(std::span<const glm::vec3> guideMiddles, glm::vec4 eye) {
  const std::size_t guides = std::min(guideMiddles.size(), distances_.size());
  for (std::size_t g = 0; g < distances_.size(); ++g) {
    const glm::vec3 middle = g < guides ? guideMiddles[g] : glm::vec3(0.0f);
    // Perspective: distance from the eye. Orthographic: depth along the view, −(p · ωe).
    distances_[g] = eye.w != 0.0f ? glm::length(middle - glm::vec3(eye)) : -glm::dot(middle, glm::vec3(eye));
  }
  std::iota(guides_.begin(), guides_.end(), 0u);
  std::stable_sort(guides_.begin(), guides_.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return distances_[a] > distances_[b]; });
  std::size_t k = 0;
  for (const std::uint32_t g : guides_)
    for (std::uint32_t i = firstStrand_[g]; i < firstStrand_[g + 1]; ++i) order_[k++] = strands_[i];
  return order_;
}

}  // namespace mane::render
