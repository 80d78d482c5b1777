// The weighted sums of limit evaluation (subdiv/detail/patch_sums.hpp) against the plain
// point-by-point loop they replace: bit for bit, for every patch size up to Gregory's 20 points,
// in the variant this CPU runs (AVX2 where it has it) and in the baseline one. Limit positions,
// normals and curvature must not depend on the CPU a simulation or a render runs on.

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "subdiv/detail/patch_sums.hpp"

namespace mane::subdiv::detail {
namespace {

TEST(PatchSums, EqualThePointByPointLoopBitForBitOnEveryCpuPath) {
  std::mt19937 random(20261201);
  std::uniform_real_distribution<double> weight(-2.0, 2.0), coordinate(-50.0, 50.0), exponent(-20.0, 20.0);
  std::vector<glm::dvec3> points(1000);
  for (glm::dvec3& p : points) p = glm::dvec3(coordinate(random), coordinate(random), coordinate(random));
  std::uniform_int_distribution<int> index(0, int(points.size()) - 1);
  int differences = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int count = 1 + trial % kMaxPatchPoints;
    PatchWeights weights;
    std::vector<int> controlPoints(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
      controlPoints[std::size_t(i)] = index(random);
      // Magnitudes far apart, so that a different order of additions would round differently.
      for (int d = 0; d < 6; ++d) weights[d][i] = weight(random) * std::exp2(exponent(random));
    }
    glm::dvec3 expected[6] = {};
    for (int i = 0; i < count; ++i)
      for (int d = 0; d < 6; ++d) expected[d] += weights[d][i] * points[std::size_t(controlPoints[std::size_t(i)])];
    glm::dvec3 dispatched[6], baseline[6];
    patchSums(weights, controlPoints, points, dispatched);
    patchSumsBaseline(weights, controlPoints, points, baseline);
    for (int d = 0; d < 6; ++d) {
      differences += std::memcmp(&expected[d], &dispatched[d], sizeof(glm::dvec3)) != 0 ? 1 : 0;
      differences += std::memcmp(&expected[d], &baseline[d], sizeof(glm::dvec3)) != 0 ? 1 : 0;
    }
  }
  EXPECT_EQ(differences, 0);
}

}  // namespace
}  // namespace mane::subdiv::detail
