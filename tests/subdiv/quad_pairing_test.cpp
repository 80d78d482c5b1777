// Pairing a triangle cage's triangles into quads (subdiv/quad_pairing.hpp): a triangulated
// grid must come back as its squares, and pairs the rules exclude (across a uv seam, a
// crease, a fold, or into a sliver) must stay triangles.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include <glm/geometric.hpp>

#include "scenes/assets.hpp"
#include "scenes/gltf_loader.hpp"
#include "scenes/subdivided_mesh.hpp"
#include "subdiv/limit.hpp"
#include "subdiv/quad_pairing.hpp"
#include "test_cages.hpp"

namespace mane::subdiv {
namespace {

/// The flat (cells × cells) grid with every square cut into two triangles, the diagonals of
/// neighbouring squares alternating, and per-corner UVs equal to the (x, y) position.
Cage triangulatedGrid(int cells) {
  const Cage quads = testing::heightGrid(cells, [](int, int) { return 0.0f; });
  Cage cage;
  cage.positions = quads.positions;
  for (const glm::vec3& p : cage.positions) cage.uvs.emplace_back(p.x, p.y);
  for (std::size_t f = 0; f < quads.faceSizes.size(); ++f) {
    const std::uint32_t* q = &quads.faceVertices[4 * f];
    const bool otherDiagonal = f % 2 == 1;
    const std::array<std::uint32_t, 6> triangles =
        otherDiagonal ? std::array{q[0], q[1], q[3], q[1], q[2], q[3]} : std::array{q[0], q[1], q[2], q[0], q[2], q[3]};
    for (int t = 0; t < 2; ++t) cage.faceSizes.push_back(3);
    cage.faceVertices.insert(cage.faceVertices.end(), triangles.begin(), triangles.end());
    cage.faceUvIndices.insert(cage.faceUvIndices.end(), triangles.begin(), triangles.end());
  }
  return cage;
}

std::set<std::uint32_t> faceVertexSet(const Cage& cage, std::size_t offset, std::uint32_t size) {
  return {cage.faceVertices.begin() + std::ptrdiff_t(offset),
          cage.faceVertices.begin() + std::ptrdiff_t(offset + size)};
}

TEST(QuadPairing, TriangulatedGridBecomesItsSquaresAgain) {
  constexpr int kCells = 6;
  const Cage grid = testing::heightGrid(kCells, [](int, int) { return 0.0f; });
  const QuadPairing paired = pairTrianglesIntoQuads(triangulatedGrid(kCells));
  ASSERT_FALSE(findCageProblem(paired.cage).has_value()) << findCageProblem(paired.cage)->message;
  EXPECT_EQ(paired.quads, std::size_t(kCells * kCells));
  EXPECT_EQ(paired.triangles, 0u);
  std::set<std::set<std::uint32_t>> squares;
  for (std::size_t f = 0; f < grid.faceSizes.size(); ++f) squares.insert(faceVertexSet(grid, 4 * f, 4));
  for (std::size_t f = 0; f < paired.cage.faceSizes.size(); ++f) {
    ASSERT_EQ(paired.cage.faceSizes[f], 4u);
    EXPECT_EQ(squares.erase(faceVertexSet(paired.cage, 4 * f, 4)), 1u) << "quad " << f << " is not a grid square";
    // Counter-clockwise seen from +z, as the triangles were: a convex quad's corners all turn left.
    const std::uint32_t* q = &paired.cage.faceVertices[4 * f];
    for (int k = 0; k < 4; ++k) {
      const glm::vec3 a = paired.cage.positions[q[k]], b = paired.cage.positions[q[(k + 1) % 4]],
                      c = paired.cage.positions[q[(k + 2) % 4]];
      EXPECT_GT(glm::cross(b - a, c - b).z, 0.0f) << "quad " << f << " corner " << k;
    }
    // The UVs follow their vertices (here equal to x, y).
    for (int k = 0; k < 4; ++k) {
      const glm::vec2 uv = paired.cage.uvs[paired.cage.faceUvIndices[4 * f + std::size_t(k)]];
      EXPECT_EQ(uv, glm::vec2(paired.cage.positions[q[k]]));
    }
  }
  EXPECT_TRUE(squares.empty());
}

/// The two triangles of a grid of one square, (0, 1, 3) and (0, 3, 2) sharing the diagonal 0–3
/// (vertices 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1)).
Cage oneSquare() {
  Cage cage = triangulatedGrid(1);
  EXPECT_EQ(cage.faceVertices, (std::vector<std::uint32_t>{0, 1, 3, 0, 3, 2}));
  return cage;
}

TEST(QuadPairing, OneSquarePairsAndKeepsEverythingElse) {
  Cage cage = oneSquare();
  cage.corners.push_back({1, 2.0f});
  cage.boundary = BoundaryInterpolation::kEdgeOnly;
  const QuadPairing paired = pairTrianglesIntoQuads(cage);
  EXPECT_EQ(paired.quads, 1u);
  EXPECT_EQ(paired.cage.positions, cage.positions);
  EXPECT_EQ(paired.cage.uvs, cage.uvs);
  ASSERT_EQ(paired.cage.corners.size(), 1u);
  EXPECT_EQ(paired.cage.corners[0].vertex, 1u);
  EXPECT_EQ(paired.cage.boundary, BoundaryInterpolation::kEdgeOnly);
}

TEST(QuadPairing, UvSeamCreaseFoldAndSliverStayTriangles) {
  {  // A uv seam along the diagonal: the second triangle has its own uvs for vertices 0 and 3.
    Cage cage = oneSquare();
    cage.uvs.push_back({5.0f, 5.0f});
    cage.faceUvIndices[3] = 4;
    EXPECT_EQ(pairTrianglesIntoQuads(cage).quads, 0u);
    cage.uvs[4] = cage.uvs[0];  // the same uv under another index is no seam
    EXPECT_EQ(pairTrianglesIntoQuads(cage).quads, 1u);
  }
  {  // A creased diagonal.
    Cage cage = oneSquare();
    cage.creases.push_back({3, 0, 1.0f});
    const QuadPairing paired = pairTrianglesIntoQuads(cage);
    EXPECT_EQ(paired.quads, 0u);
    EXPECT_EQ(paired.triangles, 2u);
    EXPECT_EQ(paired.cage.creases.size(), 1u);
  }
  {  // Folded by 90° along the diagonal: vertex 2 above the diagonal's midpoint stands its
     // triangle upright (normal along (1, −1, 0)), the other lies flat (normal +z).
    Cage cage = oneSquare();
    cage.positions[2] = {0.5f, 0.5f, 1.0f};
    EXPECT_EQ(pairTrianglesIntoQuads(cage).quads, 0u);
    EXPECT_EQ(pairTrianglesIntoQuads(cage, {.maxCornerCosine = 1.0f, .minNormalCosine = -1.0f}).quads, 1u);
  }
  {  // A dart: vertex 2 pulled to just off the diagonal makes a corner near 180°.
    Cage cage = oneSquare();
    cage.positions[2] = {0.4f, 0.5f, 0.0f};
    EXPECT_EQ(pairTrianglesIntoQuads(cage).quads, 0u);
  }
}

TEST(QuadPairing, SimplifiedHeadScanBecomesQuadDominant) {
  auto resolver = scenes::AssetResolver::createDefault();
  ASSERT_TRUE(resolver.has_value()) << resolver.error().message;
  auto found = resolver->lookup("head/LeePerrySmith/LeePerrySmith.glb");
  ASSERT_TRUE(found.has_value()) << found.error().message;
  if (!found->path) GTEST_SKIP() << found->missingReason;
  auto mesh = scenes::loadGltf(*found->path);
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  auto coarse = scenes::coarseCageFromTriangles(*mesh, {.triangles = 3000, .maxRelativeError = 0.05f});
  ASSERT_TRUE(coarse.has_value()) << coarse.error().message;
  const Cage& cage = coarse->cage;
  ASSERT_FALSE(findCageProblem(cage).has_value()) << findCageProblem(cage)->message;
  // Every simplified triangle is in exactly one face.
  EXPECT_EQ(2 * coarse->quads + coarse->triangles, 3000u);
  EXPECT_EQ(coarse->quads + coarse->triangles, cage.faceSizes.size());
  // Quad-dominant: most of the surface is in quads.
  EXPECT_GT(2 * coarse->quads, coarse->triangles);
  // Quads halve the ptex faces a triangle cage has (3 per triangle) where they pair.
  auto surface = LimitSurface::create(cage, {.maxIsolationLevel = 1});
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  EXPECT_EQ(surface->ptexFaceCount(), coarse->quads + 3 * coarse->triangles);
}

}  // namespace
}  // namespace mane::subdiv
