// Thread counts do not change results (docs/design.md#determinism): the deforming-cage update
// and the tessellation split their work over fixed ranges and merge in range order, so 1, 2
// and 4 workers must give the same bytes. The oracle is the single-threaded result.

#include <cstring>
#include <functional>
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

// An update recomputes only the points that read a moved cage vertex, directly or through
// another point (the search kept while the same vertices move); the surface stays, bit for bit,
// the one built from the moved cage: when part of the cage moves, the same part moves again,
// single vertices one to three rings from a pole move (the pole's end-cap points read refined
// points around it), and nothing moves.
TEST(ParallelSubdivision, UpdatesMovingPartOfTheCageGiveTheRebuiltSurfaceBitForBit) {
  const Cage cage = denseSphere();
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  const auto samplesOf = [](const LimitSurface& limit) {
    std::vector<glm::dvec3> samples;
    for (std::uint32_t face = 0; face < limit.ptexFaceCount(); face += 5)
      // Near every corner too, where the patches of end caps (local points) lie.
      for (const glm::dvec2 uv : {glm::dvec2(0.4, 0.8), glm::dvec2(0.01, 0.01), glm::dvec2(0.99, 0.01),
                                  glm::dvec2(0.01, 0.99), glm::dvec2(0.99, 0.99)}) {
        const LimitSample sample = limit.evaluate(face, uv.x, uv.y);
        samples.emplace_back(sample.position);
        samples.emplace_back(sample.normal);
        samples.emplace_back(sample.curvature.mean, sample.curvature.gaussian, 0.0);
      }
    return samples;
  };
  // uvSphere numbers the south pole 0, then 128 vertices per latitude circle from the south.
  const auto onCircle = [](std::size_t circle, std::size_t s) { return 1 + (circle - 1) * 128 + s; };
  std::vector<glm::vec3> positions = cage.positions;
  // The same vertices each time (the rest cage's upper part), each by a different amount, so that
  // the second move reuses the stale stencils the first found.
  std::vector<std::size_t> upperPart;
  for (std::size_t v = 0; v < cage.positions.size(); ++v)
    if (cage.positions[v].z > 0.4f) upperPart.push_back(v);
  const auto moveUpperPart = [&](glm::vec3 by) {
    for (std::size_t v : upperPart) positions[v] += by * (2.0f + positions[v].x);
  };
  const struct {
    const char* what;
    std::function<void()> move;
  } steps[] = {{"the upper part moves",
                [&] {
                  moveUpperPart({0.01f, 0.0f, 0.02f});
                }},
               {"the upper part moves again",
                [&] {
                  moveUpperPart({0.02f, -0.03f, 0.01f});
                }},
               {"a vertex next to the pole moves", [&] { positions[onCircle(1, 0)].x += 0.01f; }},
               {"a vertex two rings out moves", [&] { positions[onCircle(2, 5)].y += 0.01f; }},
               {"a vertex three rings out moves", [&] { positions[onCircle(3, 9)].z += 0.01f; }},
               {"nothing moves", [] {}}};
  for (const auto& step : steps) {
    step.move();
    ASSERT_TRUE(surface->updatePositions(positions, 2).has_value()) << step.what;
    Cage moved = cage;
    moved.positions = positions;
    auto rebuilt = LimitSurface::create(moved);
    ASSERT_TRUE(rebuilt.has_value()) << rebuilt.error().message;
    EXPECT_TRUE(sameBytes(samplesOf(*surface), samplesOf(*rebuilt))) << step.what;
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
