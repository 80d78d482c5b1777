#pragma once
// physics' dense-groom layout in render's mirror types, field by field: render never includes
// physics (DESIGN.md), so whoever has both (the world, tests, benches) converts here. Both sides
// static_assert the same 8- and 64-byte elements.

#include <cstdint>
#include <vector>

#include "physics/interpolation.hpp"
#include "render/hair_data.hpp"

namespace mane::scenes {

struct RenderGroomLayout {
  std::uint32_t guideCount = 0;
  std::uint32_t guideVertexCount = 0;
  std::uint32_t vertexCount = 0;
  std::vector<render::GuideFrameRef> guideFrames;
  std::vector<render::DenseStrand> strands;

  /// A view of this layout; valid while it lives and is not changed.
  render::DenseStrandLayout view() const {
    return {.guideCount = guideCount,
            .guideVertexCount = guideVertexCount,
            .vertexCount = vertexCount,
            .guideFrames = guideFrames,
            .strands = strands};
  }
};

inline RenderGroomLayout renderLayoutOf(const physics::DenseGroomLayout& layout) {
  RenderGroomLayout result{
      .guideCount = layout.guideCount, .guideVertexCount = layout.guideVertexCount, .vertexCount = layout.vertexCount};
  for (const physics::GuideFrameRef& ref : layout.guideFrames)
    result.guideFrames.push_back({ref.partnerA, ref.partnerB});
  for (const physics::DenseStrand& s : layout.strands)
    result.strands.push_back({.guides = {s.guides[0], s.guides[1], s.guides[2]},
                              .guideCount = s.guideCount,
                              .weights = {s.weights[0], s.weights[1], s.weights[2]},
                              .vertexScale = s.vertexScale,
                              .rootOffset = s.rootOffset,
                              .clump = s.clump,
                              .tipJitter = s.tipJitter,
                              .lengthScale = s.lengthScale});
  return result;
}

}  // namespace mane::scenes
