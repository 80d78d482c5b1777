#pragma once
// Hair roots on a subdivision surface: a procedural groom whose mesh is drawn
// as its Catmull-Clark limit surface grows from that surface, evaluated exactly by OpenSubdiv at
// sampled (ptex face, u, v), rather than from the triangles of one view's tessellation, which
// change as the camera moves while the hair must stay put.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "scenes/scene.hpp"
#include "subdiv/limit.hpp"

namespace mane::scenes {

/// A point of the limit surface where a strand grows.
struct LimitRoot {
  std::uint32_t ptexFace = 0;
  glm::dvec2 uv{0.0};        ///< the ptex face's parameters, in [0, 1]²
  glm::vec3 position{0.0f};  ///< LimitSurface::evaluate(ptexFace, uv): model units
  glm::vec3 normal{0.0f};    ///< its unit limit normal (∂u × ∂v), outward
};

/// `count` roots spread uniformly by area over the part of `surface` that `region` selects,
/// tested at each root itself: limit normal y ≥ `minUp`, z ≤ `maxForward`, and height within
/// the top `topFraction` of the surface's height (as for a triangle mesh's scalp, but per point
/// instead of per triangle). Sampling is exact in area up to the grid it starts from: every ptex
/// face is cut into g × g cells (g from 1 to 8, about 65,000 cells in all); a cell is picked with
/// probability proportional to a bound of its area, a point in it uniformly in (u, v), and the
/// point is kept with probability |∂u × ∂v| / that bound and when it lies in the region
/// (rejection sampling), and with a denser hairline also with probability
/// `ScalpRegion::densityAt` / `hairlineDensity`. Cells none of whose corners are in the region are never picked, so a
/// region's rim may lose slivers narrower than a cell. Reproducible: the same surface, region,
/// count and `seed` give the same roots, bit for bit. Errors: no point of the surface in the
/// region, or a region too thin to hit.
[[nodiscard]] Result<std::vector<LimitRoot>> sampleScalpOnLimitSurface(const subdiv::LimitSurface& surface,
                                                                       const ScalpRegion& region, std::size_t count,
                                                                       std::uint64_t seed);

}  // namespace mane::scenes
