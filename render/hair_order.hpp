#pragma once
// The order hair strands are drawn in, back to front, for "over" blending
// (render/passes/hair_pass.hpp, "Compositing"). Strands are sorted by their primary guide (the
// first in DenseStrand::guides): the guides by the distance of their middle vertex from the eye,
// farthest first, and each guide's strands in layout order after it. A guide stands for the
// strands that follow it (they lie within a few millimetres of it), and there are far fewer
// guides than strands (Nalu 762 for 4,095; the ponytail 4,933 for 50,000), so the sort is cheap
// enough for the CPU every frame. Deterministic: ties keep guide order.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/hair_data.hpp"

namespace mane::render {

class StrandDrawOrder {
public:
  /// Groups `layout`'s strands by primary guide. The layout is validated by its consumers
  /// (StrandInterpolationPass); a primary guide out of range is treated as guide 0.
  explicit StrandDrawOrder(const DenseStrandLayout& layout);

  /// Strand indices back to front for the guide middles `guideMiddles` (one per guide, world
  /// metres) seen from `eye` (w = 1: a position; w = 0: the unit direction towards an eye at
  /// infinity, as hairEye gives). The span stays valid until the next call.
  [[nodiscard]] std::span<const std::uint32_t> backToFront(std::span<const glm::vec3> guideMiddles, glm::vec4 eye);

private:
  std::vector<std::uint32_t> firstStrand_;  ///< per guide, into strands_; one more at the end
  std::vector<std::uint32_t> strands_;      ///< strand indices grouped by primary guide
  std::vector<std::uint32_t> guides_;       ///< scratch: guides in drawing order
  std::vector<float> distances_;            ///< scratch: per guide
  std::vector<std::uint32_t> order_;
};

}  // namespace mane::render
