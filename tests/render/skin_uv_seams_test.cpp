// UV seams and their skirts (render/passes/skin_uv_seams.hpp), against layouts whose answer is
// known exactly: a tube cut open along one line, and a flat sheet cut in two charts, one of them
// turned, scaled and mirrored in uv. Where a chart's uvs are a similarity of the surface (both
// cases here), unfolding the far chart across a seam must land each of its vertices exactly where
// the near chart's own parametrisation, continued past the seam, would put it.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "render/passes/skin_uv_seams.hpp"

namespace mane::render {
namespace {

struct TestMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;
};

// A tube of `columns` × `rows` quads around the y axis, unrolled to uv u = column / columns,
// v = row / rows: the column u = 1 repeats the vertices of u = 0 with other uvs, the seam.
TestMesh tube(int columns, int rows) {
  TestMesh mesh;
  const float circumference = 1.0f;
  const float radius = circumference / (2.0f * std::numbers::pi_v<float>);
  for (int row = 0; row <= rows; ++row)
    for (int column = 0; column <= columns; ++column) {
      const float angle = 2.0f * std::numbers::pi_v<float> * float(column % columns) / float(columns);
      mesh.positions.push_back({radius * std::cos(angle), float(row) / float(rows), radius * std::sin(angle)});
      mesh.uvs.push_back({float(column) / float(columns), float(row) / float(rows)});
    }
  const auto at = [&](int column, int row) { return std::uint32_t(row * (columns + 1) + column); };
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column)
      mesh.indices.insert(mesh.indices.end(), {at(column, row), at(column + 1, row), at(column + 1, row + 1),
                                               at(column, row), at(column + 1, row + 1), at(column, row + 1)});
  return mesh;
}

std::vector<SkinDrawVertex> skirts(const TestMesh& mesh, float reach) {
  std::vector<SkinDrawVertex> draw = textureSpaceDrawList(mesh.positions, mesh.uvs, mesh.indices, reach);
  EXPECT_GE(draw.size(), mesh.indices.size());
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    EXPECT_EQ(draw[i].source, mesh.indices[i]);
    EXPECT_EQ(draw[i].depth, 0.0f);
    EXPECT_EQ(draw[i].uv, mesh.uvs[mesh.indices[i]]);
  }
  draw.erase(draw.begin(), draw.begin() + std::ptrdiff_t(mesh.indices.size()));
  return draw;
}

TEST(UvSeams, ATubeCutOpenHasOneSeamEdgePerRow) {
  const TestMesh mesh = tube(16, 5);
  const std::vector<UvSeamEdge> seams = findUvSeams(mesh.positions, mesh.uvs, mesh.indices);
  ASSERT_EQ(seams.size(), 5u);
  for (const UvSeamEdge& seam : seams)
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(mesh.positions[seam.ends[0][k]], mesh.positions[seam.ends[1][k]]);
      EXPECT_NE(mesh.uvs[seam.ends[0][k]], mesh.uvs[seam.ends[1][k]]);
      // One side at u = 0, the other at u = 1.
      EXPECT_EQ(std::abs(mesh.uvs[seam.ends[0][k]].x - mesh.uvs[seam.ends[1][k]].x), 1.0f);
    }
}

TEST(UvSeams, ATubesSkirtsContinueItsLayoutAcrossTheCut) {
  // Columns 1/16 wide; a reach of 2.5 columns past the cut. Each side's skirt is the other side's
  // columns, shifted by one whole turn: u − 1 past u = 0, u + 1 past u = 1.
  const int columns = 16, rows = 5;
  const TestMesh mesh = tube(columns, rows);
  const float reach = 2.5f / columns;
  const std::vector<SkinDrawVertex> skirt = skirts(mesh, reach);
  ASSERT_FALSE(skirt.empty());
  ASSERT_EQ(skirt.size() % 3, 0u);
  int before = 0, after = 0;
  for (const SkinDrawVertex& vertex : skirt) {
    const glm::vec2 own = mesh.uvs[vertex.source];
    const float shifted = vertex.uv.x < 0.5f ? own.x - 1.0f : own.x + 1.0f;
    EXPECT_NEAR(vertex.uv.x, shifted, 1e-6f) << "vertex " << vertex.source;
    EXPECT_NEAR(vertex.uv.y, own.y, 1e-6f) << "vertex " << vertex.source;
    (vertex.uv.x < 0.5f ? before : after) += 1;
    // Depth: the distance to its seam edge over the reach, above the mesh's own 0; that edge is
    // on the cut, so the depth is at least the distance past the cut.
    const float past = vertex.uv.x < 0.5f ? -vertex.uv.x : vertex.uv.x - 1.0f;
    EXPECT_GT(vertex.depth, 0.0f);
    EXPECT_LE(vertex.depth, 1.0f);
    EXPECT_GE(vertex.depth, std::min(1.0f, 1.0f / 256.0f + (1.0f - 1.0f / 256.0f) * past / reach) - 1e-5f);
  }
  EXPECT_EQ(before, after);
  // Nothing beyond the reach but whole triangles that start within it: at most 3 columns out.
  for (const SkinDrawVertex& vertex : skirt) EXPECT_LE(std::min(-vertex.uv.x, vertex.uv.x - 1.0f), 3.0f / columns);
  // Nearest first.
  for (std::size_t t = 3; t < skirt.size(); t += 3) {
    const auto nearest = [&](std::size_t first) {
      return std::min({skirt[first].depth, skirt[first + 1].depth, skirt[first + 2].depth});
    };
    EXPECT_LE(nearest(t - 3), nearest(t));
  }
}

// A flat 8 × 4 sheet of unit squares in the xz plane, cut at x = 4 into two charts, each laid
// out in uv by its own map of the position (x, z).
struct TwoChartSheet {
  static constexpr int kWidth = 8, kDepth = 4, kCut = 4;
  TestMesh mesh;
  std::vector<int> side;  // per vertex: 0 the left chart, 1 the right one
};

template <typename LeftMap, typename RightMap>
TwoChartSheet twoChartSheet(const LeftMap& leftMap, const RightMap& rightMap) {
  TwoChartSheet sheet;
  TestMesh& mesh = sheet.mesh;
  for (int chart = 0; chart < 2; ++chart) {
    const int first = chart == 0 ? 0 : TwoChartSheet::kCut,
              last = chart == 0 ? TwoChartSheet::kCut : TwoChartSheet::kWidth;
    const std::uint32_t base = std::uint32_t(mesh.positions.size());
    for (int z = 0; z <= TwoChartSheet::kDepth; ++z)
      for (int x = first; x <= last; ++x) {
        mesh.positions.push_back({float(x), 0.0f, float(z)});
        const glm::dvec2 p(x, z);
        mesh.uvs.push_back(glm::vec2(chart == 0 ? leftMap(p) : rightMap(p)));
        sheet.side.push_back(chart);
      }
    const int stride = last - first + 1;
    const auto at = [&](int x, int z) { return base + std::uint32_t(z * stride + (x - first)); };
    for (int z = 0; z < TwoChartSheet::kDepth; ++z)
      for (int x = first; x < last; ++x)
        mesh.indices.insert(mesh.indices.end(),
                            {at(x, z), at(x, z + 1), at(x + 1, z + 1), at(x, z), at(x + 1, z + 1), at(x + 1, z)});
  }
  return sheet;
}

TEST(UvSeams, AMirroredTurnedChartUnfoldsOntoItsNeighboursLayout) {
  // The left chart's uv is the position scaled by 1/16; the right chart's is turned by 70°,
  // scaled by 1/40, mirrored and moved. Unfolded across the cut, the right chart must land where
  // the left chart's map (x, z) / 16 puts it, and the left chart where the right chart's map
  // puts it.
  const double turn = 70.0 * std::numbers::pi / 180.0;
  const auto leftMap = [](glm::dvec2 p) { return p / 16.0; };
  const auto rightMap = [&](glm::dvec2 p) {
    const glm::dvec2 mirrored(p.x, -p.y);
    return glm::dvec2(0.6, 0.7) + glm::dvec2(std::cos(turn) * mirrored.x - std::sin(turn) * mirrored.y,
                                             std::sin(turn) * mirrored.x + std::cos(turn) * mirrored.y) /
                                      40.0;
  };
  const TwoChartSheet sheet = twoChartSheet(leftMap, rightMap);
  const TestMesh& mesh = sheet.mesh;
  const std::vector<int>& side = sheet.side;
  ASSERT_EQ(findUvSeams(mesh.positions, mesh.uvs, mesh.indices).size(), std::size_t(TwoChartSheet::kDepth));

  const std::vector<SkinDrawVertex> skirt = skirts(mesh, 1.0f);
  ASSERT_FALSE(skirt.empty());
  int onLeft = 0, onRight = 0;
  for (const SkinDrawVertex& drawn : skirt) {
    const glm::dvec2 p(mesh.positions[drawn.source].x, mesh.positions[drawn.source].z);
    // A right-chart vertex drawn in the left chart's layout, or the other way round.
    const glm::dvec2 expected = side[drawn.source] == 1 ? leftMap(p) : rightMap(p);
    EXPECT_NEAR(drawn.uv.x, expected.x, 1e-6) << "vertex " << drawn.source;
    EXPECT_NEAR(drawn.uv.y, expected.y, 1e-6) << "vertex " << drawn.source;
    (side[drawn.source] == 1 ? onLeft : onRight) += 1;
  }
  EXPECT_GT(onLeft, 0);
  EXPECT_GT(onRight, 0);
}

TEST(UvSeams, ANeighbourSquashedInUvGivesAMirroredSkirt) {
  // The right chart maps to one point (a surface no texture covers): it has nothing to show, so
  // the left chart's skirt is its own skin mirrored across the cut, u → 2·cut/16 − u, and the
  // right chart draws no skirt.
  const auto leftMap = [](glm::dvec2 p) { return p / 16.0; };
  const auto rightMap = [](glm::dvec2) { return glm::dvec2(0.9, 0.9); };
  const TwoChartSheet sheet = twoChartSheet(leftMap, rightMap);
  const std::vector<SkinDrawVertex> skirt = skirts(sheet.mesh, 0.1f);
  ASSERT_FALSE(skirt.empty());
  const double cut = TwoChartSheet::kCut / 16.0;
  for (const SkinDrawVertex& drawn : skirt) {
    ASSERT_EQ(sheet.side[drawn.source], 0) << "vertex " << drawn.source;
    const glm::vec2 own = sheet.mesh.uvs[drawn.source];
    EXPECT_NEAR(drawn.uv.x, 2.0 * cut - own.x, 1e-6) << "vertex " << drawn.source;
    EXPECT_NEAR(drawn.uv.y, own.y, 1e-6) << "vertex " << drawn.source;
  }
}

TEST(UvSeams, AMeshWithoutSeamsOrWithoutReachDrawsOnlyItself) {
  TestMesh sheet;
  sheet.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  sheet.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  sheet.indices = {0, 1, 2, 0, 2, 3};
  EXPECT_TRUE(findUvSeams(sheet.positions, sheet.uvs, sheet.indices).empty());
  EXPECT_TRUE(skirts(sheet, 0.1f).empty());
  const TestMesh cutTube = tube(8, 2);
  EXPECT_EQ(textureSpaceDrawList(cutTube.positions, cutTube.uvs, cutTube.indices, 0.0f).size(), cutTube.indices.size());
}

}  // namespace
}  // namespace mane::render
