#pragma once
// The CPU reference for render/passes/opacity_shadow_map_pass.hpp: the opacity between a point and a
// directional light found by casting rays through the strands, with no map, no slices and no
// rasterization: an independent oracle for the map (docs/design.md#testing).
//
// The model, shared with the map (see its header): a strand is a chain of cylinders of radius r
// around its segments; a ray from the point towards the light that crosses a segment's cylinder
// collects α, the groom's opacity per crossing; the transmittance is exp(−κ·opacity)
// (Kim & Neumann 2001, eq. 1).
//
// Ray–cylinder test (analytic, per segment): the ray p + t·L (t > 0) and the segment's axis a + u·(b − a)
// come closest where their projections onto the plane ⊥ L are closest; the ray crosses the
// cylinder when that distance is at most r, the closest axis point lies at u ∈ [0, 1), and that
// point is on the light's side of p ((c − p)·L > 0). This is the exact crossing of the infinite
// cylinder, bounded by the axis parameter instead of the end caps: the half-open u makes a
// straight chain of segments count a ray once, where capped cylinders would count it twice near
// every joint (the caps differ from this only within r of a joint). Segments parallel to L
// (projected length below 1e-9·r) are crossed when the ray passes within r of them.
//
// A map texel stands for the rays through its footprint, so filteredOpacity() averages ray
// opacities over a neighbourhood with the kernel the map applies: rasterized lines one texel
// wide (a box), read back by bilinear filtering (a tent); box ∗ tent is the quadratic B-spline
// with texel-spaced knots (support ±1.5 texels), sampled on a grid of rays.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/error.hpp"

namespace mane::render {

/// A groom as the reference sees it (the map's OpacityShadowStrands and settings, on the CPU).
struct OpacityReferenceGroom {
  std::span<const glm::vec4> positions;  ///< strand-major, xyz metres (w ignored)
  std::uint32_t strandCount = 0;
  std::uint32_t verticesPerStrand = 0;  ///< ≥ 2
  float strandRadius = 0.0f;            ///< r, metres
  float strandOpacity = 1.0f;           ///< α per crossing
  float extinction = 1.0f;              ///< κ
};

class OpacityReference {
public:
  /// Indexes the segments in a grid over the plane ⊥ `towardLight` (one pass over the strands).
  /// Fails on no strands, fewer than 2 vertices per strand, too few positions, non-finite
  /// positions, a radius or opacity that is not positive, or a light direction that is not unit.
  [[nodiscard]] static Result<OpacityReference> create(const OpacityReferenceGroom& groom, glm::vec3 towardLight);

  /// α × the segment cylinders the ray from `point` towards the light crosses.
  [[nodiscard]] double rayOpacity(const glm::dvec3& point) const;
  /// rayOpacity averaged over rays around `point` (perpendicular to the light) with the
  /// quadratic B-spline weight of knot spacing `texelSize` (metres), `raysPerTexel`² rays per
  /// texel area over the kernel's ±1.5 texels.
  [[nodiscard]] double filteredOpacity(const glm::dvec3& point, double texelSize, int raysPerTexel) const;
  /// exp(−κ·opacity).
  [[nodiscard]] double transmittance(double opacity) const;

private:
  struct Segment {
    glm::dvec3 a;       ///< axis start, metres
    glm::dvec3 axis;    ///< b − a, metres
    glm::dvec2 start;   ///< a projected onto (e1, e2)
    glm::dvec2 across;  ///< (b − a) projected
    double lengthSquared;
  };

  OpacityReference() = default;
  glm::dvec2 project(const glm::dvec3& p) const;

  glm::dvec3 light_{0.0, 0.0, 1.0};
  glm::dvec3 e1_{1.0, 0.0, 0.0}, e2_{0.0, 1.0, 0.0};
  double radius_ = 0.0, opacity_ = 1.0, extinction_ = 1.0;
  std::vector<Segment> segments_;
  glm::dvec2 gridOrigin_{0.0};
  double cellSize_ = 1.0;
  int cellsX_ = 1, cellsY_ = 1;
  std::vector<std::uint32_t> cellStart_;  ///< CSR: segments of cell i are cellSegments_[cellStart_[i] .. [i+1])
  std::vector<std::uint32_t> cellSegments_;
};

}  // namespace mane::render
