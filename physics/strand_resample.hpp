#pragma once
// Resampling guide strands to a fixed particle count: a groom authored with any number of
// points per strand (TressFX files carry 4 to 64, procedural ones whatever was asked) becomes
// strands of N particles equally spaced along the original curve, which is what the solver's
// cost and stability are tuned for (one segment length per strand).
//
// The input polyline is the curve: new points lie on its segments at equal arc-length steps
// (linear interpolation, as the TressFX Maya exporter does when it adds vertices to a strand), the root
// and the tip are copied bit for bit. Arc lengths are accumulated in double so that the spacing
// of the result is equal to float rounding even for strands of thousands of points.

#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

/// Returns `count` points equally spaced by arc length along the polyline `points` (root
/// first): point k lies at arc length k·L/(count − 1), where L is the polyline's length, so the
/// first is `points.front()` and the last `points.back()`, both exactly. Positions in any unit
/// (metres in the engine); coincident consecutive input points (zero-length segments) are
/// allowed and simply contribute no length.
/// Fails, naming the problem, when `count` < 2, `points` has fewer than 2 points, a point is NaN
/// or infinite, or the total length is zero (all points coincide) or overflows.
[[nodiscard]] Result<std::vector<glm::vec3>> resampleStrand(std::span<const glm::vec3> points, std::size_t count);

/// `resampleStrand` on every strand of a groom, in order. Errors name the strand (0-based, as
/// `HairSystem` does) and the problem; an empty groom is an error too.
[[nodiscard]] Result<std::vector<std::vector<glm::vec3>>> resampleGroom(std::span<const std::vector<glm::vec3>> strands,
                                                                        std::size_t count);

}  // namespace mane::physics
