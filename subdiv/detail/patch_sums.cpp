#include "subdiv/detail/patch_sums.hpp"

namespace mane::subdiv::detail {
namespace {

// The sums as lanes [coordinate][basis function] (6 and 7 are padding): the lanes of one
// coordinate sit side by side, so the compiler computes several of them at once, each still
// added point by point.
[[gnu::always_inline]] inline void accumulate(const PatchWeights& weights, std::span<const int> controlPoints,
                                              std::span<const glm::dvec3> points, glm::dvec3 (&sums)[6]) {
  alignas(64) double perPoint[kMaxPatchPoints][8];
  const std::size_t count = controlPoints.size();
  for (std::size_t i = 0; i < count; ++i) {
    for (int d = 0; d < 6; ++d) perPoint[i][d] = weights[d][i];
    perPoint[i][6] = perPoint[i][7] = 0.0;
  }
  alignas(64) double lanes[3][8] = {};
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3& point = points[static_cast<std::size_t>(controlPoints[i])];
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 8; ++d) lanes[c][d] += perPoint[i][d] * point[c];
  }
  for (int d = 0; d < 6; ++d) sums[d] = glm::dvec3(lanes[0][d], lanes[1][d], lanes[2][d]);
}

#if defined(__x86_64__)
// AVX2 adds and multiplies round as the baseline's SSE2 does, and -ffp-contract=off keeps them
// from fusing into multiply-adds.
[[gnu::target("avx2")]] void accumulateAvx2(const PatchWeights& weights, std::span<const int> controlPoints,
                                            std::span<const glm::dvec3> points, glm::dvec3 (&sums)[6]) {
  accumulate(weights, controlPoints, points, sums);
}
#endif

}  // namespace

void patchSums(const PatchWeights& weights, std::span<const int> controlPoints, std::span<const glm::dvec3> points,
               glm::dvec3 (&sums)[6]) {
#if defined(__x86_64__)
  static const bool hasAvx2 = __builtin_cpu_supports("avx2");
  if (hasAvx2) return accumulateAvx2(weights, controlPoints, points, sums);
#endif
  accumulate(weights, controlPoints, points, sums);
}

void patchSumsBaseline(const PatchWeights& weights, std::span<const int> controlPoints,
                       std::span<const glm::dvec3> points, glm::dvec3 (&sums)[6]) {
  accumulate(weights, controlPoints, points, sums);
}

}  // namespace mane::subdiv::detail
