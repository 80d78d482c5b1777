#pragma once
// Private to subdiv/: the weighted sums a limit evaluation spends most of its time in, the
// control points of one patch times each of its six basis functions (position, ∂u, ∂v, ∂uu,
// ∂uv, ∂vv). Each sum adds its products point by point in the patch's order, whichever variant
// runs, so the bits do not depend on the CPU.

#include <cstddef>
#include <span>

#include <glm/vec3.hpp>

namespace mane::subdiv::detail {

/// The most control points of a patch (Gregory basis patches have 20, B-spline patches 16).
inline constexpr int kMaxPatchPoints = 20;

/// Per basis function, its weight for each control point of the patch.
using PatchWeights = double[6][kMaxPatchPoints];

/// sums[d] = Σ_i weights[d][i] · points[controlPoints[i]], i = 0, 1, … in order.
/// controlPoints.size() ≤ kMaxPatchPoints.
void patchSums(const PatchWeights& weights, std::span<const int> controlPoints, std::span<const glm::dvec3> points,
               glm::dvec3 (&sums)[6]);

/// The same without SIMD beyond the baseline (for tests: patchSums uses AVX2 where it can).
void patchSumsBaseline(const PatchWeights& weights, std::span<const int> controlPoints,
                       std::span<const glm::dvec3> points, glm::dvec3 (&sums)[6]);

}  // namespace mane::subdiv::detail
