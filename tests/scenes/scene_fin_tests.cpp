// "procedural:fin" cloths (scenes/README.md, "Cloths"): the block as it arrives in the Scene, the
// errors, the fin's geometry against the shape it was asked for, and its base and rays held.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "scenes/fin_cloth.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_cloth.hpp"
#include "tests/scenes/test_support.hpp"

namespace mane::scenes {
namespace {

using testing::sceneWithCloth;

TEST(SceneFin, TheShapeArrivesAsWrittenAndDefaultsAsDocumented) {
  auto scene = parseScene(sceneWithCloth(R"("source": "procedural:fin",
      "fin": {"rays": 5, "length": 0.1, "root": 0.02, "spread_degrees": 90, "taper": 0.8, "scallop": 0.3,
              "pleat": 0.1, "rows": 9, "ray_stiffness": 0.5})"),
                          "f.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const FinShape& fin = scene->cloths[0].fin;
  EXPECT_EQ(fin.rays, 5);
  EXPECT_EQ(fin.length, 0.1f);
  EXPECT_EQ(fin.root, 0.02f);
  EXPECT_EQ(fin.spreadDegrees, 90.0f);
  EXPECT_EQ(fin.taper, 0.8f);
  EXPECT_EQ(fin.scallop, 0.3f);
  EXPECT_EQ(fin.pleat, 0.1f);
  EXPECT_EQ(fin.rows, 9);
  EXPECT_EQ(fin.rayStiffness, 0.5f);

  auto plain = parseScene(sceneWithCloth(R"("source": "procedural:fin")"), "f.json");
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  const FinShape defaults;
  EXPECT_EQ(plain->cloths[0].fin.rays, defaults.rays);
  EXPECT_EQ(plain->cloths[0].fin.length, defaults.length);
  EXPECT_TRUE(plain->cloths[0].pinTopEdge) << "a fin is held at its base unless the scene says otherwise";
}

TEST(SceneFin, MistakesAreReportedAtTheirField) {
  const auto expectError = [](const std::string& cloth, const std::string& expected) {
    auto scene = parseScene(sceneWithCloth(cloth), "dir/bad.json");
    const std::string message = scene ? std::string() : scene.error().message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  expectError(R"("source": "procedural:grid", "fin": {})", R"(cloths[0].fin: applies to "procedural:fin" cloths only)");
  expectError(R"("source": "procedural:fin", "fin": {"rays": 2})", "cloths[0].fin.rays: expected 3..32 rays");
  expectError(R"("source": "procedural:fin", "fin": {"length": 0})",
              "cloths[0].fin.length: expected a length in [0.001, 1]");
  expectError(R"("source": "procedural:fin", "fin": {"root": 2})",
              "cloths[0].fin.root: expected a length in [0.001, 1]");
  expectError(R"("source": "procedural:fin", "fin": {"spread_degrees": 170})",
              "cloths[0].fin.spread_degrees: expected an angle in (0, 150]");
  expectError(R"("source": "procedural:fin", "fin": {"taper": 0})", "cloths[0].fin.taper: expected a share in (0, 1]");
  expectError(R"("source": "procedural:fin", "fin": {"scallop": 0.6})",
              "cloths[0].fin.scallop: expected a share in [0, 0.5]");
  expectError(R"("source": "procedural:fin", "fin": {"pleat": -0.1})",
              "cloths[0].fin.pleat: expected a share in [0, 0.5]");
  expectError(R"("source": "procedural:fin", "fin": {"rows": 3})", "cloths[0].fin.rows: expected 4..128 vertices");
  expectError(R"("source": "procedural:fin", "fin": {"ray_stiffness": 0})",
              "cloths[0].fin.ray_stiffness: expected a stiffness in (0, 1]");
  expectError(R"("source": "procedural:fin", "fin": {"spines": 3})", "cloths[0].fin.spines");
}

// Against the shape's definition: ray k of n leaves its root point (root·(k/(n−1) − ½), 0) at
// spread·(k/(n−1) − ½) from −y and ends at length·(1 − (1 − taper)·k/(n−1)), standing ±pleat times
// the gap to its neighbour out of the plane; midway between two rays the edge lies 1 − scallop of
// their length from its root; every triangle turns counter-clockwise seen from +z.
TEST(SceneFin, RaysAndEdgeLieWhereTheShapeSays) {
  FinShape shape;
  shape.rays = 5;
  shape.length = 0.1f;
  shape.root = 0.04f;
  shape.spreadDegrees = 80.0f;
  shape.taper = 0.5f;
  shape.scallop = 0.2f;
  shape.pleat = 0.25f;
  shape.rows = 6;
  const FinCloth fin = makeFin(shape);
  const int columns = (shape.rays - 1) * kFinColumnsPerGap + 1;
  ASSERT_EQ(fin.columns, columns);
  ASSERT_EQ(fin.mesh.positions.size(), std::size_t(columns * shape.rows));
  const auto vertex = [&](int row, int column) { return glm::dvec3(fin.mesh.positions[row * columns + column]); };
  const auto rootOf = [&](double across) { return glm::dvec2(double(shape.root) * (across - 0.5), 0.0); };
  const double spread = glm::radians(double(shape.spreadDegrees));
  for (int ray = 0; ray < shape.rays; ++ray) {
    const double across = double(ray) / double(shape.rays - 1);
    const double length = double(shape.length) * (1.0 - (1.0 - double(shape.taper)) * across);
    const double angle = spread * (across - 0.5);
    const glm::dvec3 tip = vertex(shape.rows - 1, ray * kFinColumnsPerGap);
    const glm::dvec2 expected = rootOf(across) + length * glm::dvec2(std::sin(angle), -std::cos(angle));
    EXPECT_NEAR(tip.x, expected.x, 1e-7) << ray;
    EXPECT_NEAR(tip.y, expected.y, 1e-7) << ray;
    const int neighbour = ray + 1 < shape.rays ? ray + 1 : ray - 1;
    const glm::dvec3 other = vertex(shape.rows - 1, neighbour * kFinColumnsPerGap);
    const double gap = glm::distance(glm::dvec2(tip), glm::dvec2(other));
    EXPECT_NEAR(tip.z, (ray % 2 == 0 ? 1.0 : -1.0) * double(shape.pleat) * gap, 1e-7) << ray;
  }
  for (int gap = 0; gap + 1 < shape.rays; ++gap) {
    const int column = gap * kFinColumnsPerGap + kFinColumnsPerGap / 2;
    const double across = double(column) / double(columns - 1);
    const double length = double(shape.length) * (1.0 - (1.0 - double(shape.taper)) * across);
    const glm::dvec3 edge = vertex(shape.rows - 1, column);
    EXPECT_NEAR(glm::distance(glm::dvec2(edge), rootOf(across)), length * (1.0 - double(shape.scallop)), 1e-7) << gap;
    EXPECT_EQ(edge.z, 0.0) << "the membrane between the rays lies in the plane";
  }
  for (std::size_t t = 0; t < fin.mesh.indices.size(); t += 3) {
    const glm::dvec3 a = glm::dvec3(fin.mesh.positions[fin.mesh.indices[t]]);
    const glm::dvec3 b = glm::dvec3(fin.mesh.positions[fin.mesh.indices[t + 1]]);
    const glm::dvec3 c = glm::dvec3(fin.mesh.positions[fin.mesh.indices[t + 2]]);
    EXPECT_GT((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x), 0.0) << "triangle " << t / 3;
  }
}

// The base (the root and the row after it) is pinned; every other ray vertex is held, at
// ray_stiffness just past the base falling linearly to half of it at the tip; the membrane is free.
TEST(SceneFin, TheBaseIsPinnedAndTheRaysHeld) {
  auto scene = parseScene(
      sceneWithCloth(R"("source": "procedural:fin", "fin": {"rays": 4, "rows": 8, "ray_stiffness": 0.4})"), "f.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const Cloth& entry = scene->cloths[0];
  auto mesh = loadClothMesh(entry, testing::sharedResolver(), {});
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  auto cloth = SceneCloth::create(entry, *mesh, scene->simulation, glm::mat4(1.0f));
  ASSERT_TRUE(cloth.has_value()) << cloth.error().message;
  const int columns = 3 * kFinColumnsPerGap + 1;
  ASSERT_EQ(cloth->cloth().pinnedVertices().size(), std::size_t(2 * columns));
  for (std::uint32_t v : cloth->cloth().pinnedVertices()) EXPECT_LT(v, std::uint32_t(2 * columns));

  const FinCloth fin = makeFin(entry.fin);
  ASSERT_EQ(fin.holds.size(), std::size_t(4 * (8 - 2)));
  for (const physics::ClothShapeHold& hold : fin.holds) {
    const int row = int(hold.vertex) / columns, column = int(hold.vertex) % columns;
    EXPECT_GE(row, 2);
    EXPECT_EQ(column % kFinColumnsPerGap, 0) << "only the rays are held";
    EXPECT_NEAR(hold.stiffness, 0.4f * (1.0f - 0.5f * float(row - 1) / 6.0f), 1e-7f) << hold.vertex;
  }
}

}  // namespace
}  // namespace mane::scenes
