// Thread counts do not change results (DESIGN.md, "Determinism"): the deforming-cage update
// and the tessellation split their work over fixed ranges and merge in range order, so 1, 2
// and 4 workers must give the same bytes. The oracle is the single-threaded result.

#include <cstring>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "subdiv/tessellator.hpp"
#include "tests/subdiv/test_cages.hpp"

namespace mane::subdiv {
namespace {

template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Enough faces and points (8,064 quads, 256 pole triangles, ~10⁵ stencils) that every stage
// really splits among 4 workers.
Cage denseSphere() {
  return testing::uvSphere(128, 64, 1.0f);
}

ScreenView closeView() {
  const glm::vec2 viewport{1280.0f, 720.0f};
  const glm::mat4 projection = glm::perspective(glm::radians(40.0f), viewport.x / viewport.y, 0.01f, 100.0f);
  const glm::vec3 eye = glm::normalize(glm::vec3(0.3f, 0.5f, 1.0f)) * 2.5f;
  return {projection * glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0)), viewport};
}

/// The cage squashed and twisted: a deformation no stencil reproduces by accident.
std::vector<glm::vec3> deformed(const Cage& cage) {
  std::vector<glm::vec3> positions = cage.positions;
  for (glm::vec3& p : positions) {
    const float angle = 0.4f * p.z;
    p = glm::vec3(p.x * std::cos(angle) - p.y * std::sin(angle), p.x * std::sin(angle) + p.y * std::cos(angle),
                  0.8f * p.z);
  }
  return positions;
}

TEST(ParallelSubdivision, DeformingCageUpdateIsBitIdenticalForAnyThreadCount) {
  const Cage cage = denseSphere();
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  std::vector<glm::dvec3> reference;
  for (unsigned threads : {1u, 2u, 4u}) {
    // Back to the rest cage first, so that no point keeps a value from the last update.
    ASSERT_TRUE(surface->updatePositions(cage.positions).has_value());
    ASSERT_TRUE(surface->updatePositions(deformed(cage), threads).has_value());
    std::vector<glm::dvec3> samples;
    for (std::uint32_t face = 0; face < surface->ptexFaceCount(); face += 7)
      for (double u : {0.0, 0.3, 1.0}) samples.push_back(surface->evaluatePosition(face, u, 1.0 - u * 0.5));
    if (threads == 1)
      reference = samples;
    else
      EXPECT_TRUE(sameBytes(samples, reference)) << threads << " threads";
  }
}

TEST(ParallelSubdivision, TessellationIsBitIdenticalForAnyThreadCount) {
  const Cage cage = denseSphere();
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  ASSERT_TRUE(surface->updatePositions(deformed(cage), 2).has_value());
  auto tessellator = AdaptiveTessellator::create(*surface, {.keepPtexCoordinates = true});
  ASSERT_TRUE(tessellator.has_value()) << tessellator.error().message;
  TessellatedMesh reference;
  tessellator->tessellate(closeView(), reference, 1);
  const TessellationStatistics referenceStatistics = tessellator->statistics();
  ASSERT_GT(reference.triangleCount(), 20'000u);  // the camera is close enough to split cells
  for (unsigned threads : {2u, 4u}) {
    TessellatedMesh mesh;
    tessellator->tessellate(closeView(), mesh, threads);
    EXPECT_TRUE(sameBytes(mesh.indices, reference.indices)) << threads << " threads";
    EXPECT_TRUE(sameBytes(mesh.positions, reference.positions)) << threads << " threads";
    EXPECT_TRUE(sameBytes(mesh.normals, reference.normals)) << threads << " threads";
    EXPECT_TRUE(sameBytes(mesh.meanCurvature, reference.meanCurvature)) << threads << " threads";
    EXPECT_TRUE(sameBytes(mesh.weldedVertex, reference.weldedVertex)) << threads << " threads";
    EXPECT_TRUE(sameBytes(mesh.trianglePtexFaces, reference.trianglePtexFaces)) << threads << " threads";
    EXPECT_TRUE(sameBytes(mesh.cornerPtexCoordinates, reference.cornerPtexCoordinates)) << threads << " threads";
    EXPECT_EQ(tessellator->statistics().cells, referenceStatistics.cells);
    EXPECT_EQ(tessellator->statistics().positionEvaluations, referenceStatistics.positionEvaluations);
  }
}

}  // namespace
}  // namespace mane::subdiv
