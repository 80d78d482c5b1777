// Cloth from a triangle mesh: constraint construction, colouring, free fall of the centre of
// mass, pins following the body, low stretch when hanging, bending stiffness, shape holds, determinism across thread
// counts, and bad input.

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "physics/cloth.hpp"
#include "tests/support/cloth_grid.hpp"

namespace mane::physics {
namespace {

// An n × n vertex grid of side `size` metres in the XY plane (a hanging sheet), two triangles
// per cell. Vertex (i, j) is at index j·n + i, row j = 0 at the top.
using Grid = mane::testing::ClothGrid;
using mane::testing::makeClothGrid;

using Pins = std::vector<std::uint32_t>;

TEST(Cloth, BuildsOneConstraintPerEdgeAndOneBendPerInteriorEdge) {
  // A 4×4 grid: 3·4 horizontal + 3·4 vertical + 9 diagonal edges = 33; interior edges (shared by
  // two triangles) = 33 − 12 boundary edges = 21.
  const Grid grid = makeClothGrid(4, 1.0f);
  auto cloth = Cloth::create(grid.positions, grid.triangles, {}, {});
  ASSERT_TRUE(cloth.has_value()) << cloth.error().message;
  EXPECT_EQ(cloth->edgeCount(), 33u);
  EXPECT_EQ(cloth->bendingCount(), 21u);
}

TEST(Cloth, NoTwoConstraintsOfAColourShareAParticle) {
  const Grid grid = makeClothGrid(12, 1.0f);
  auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 11}, {});
  ASSERT_TRUE(cloth.has_value());
  const auto starts = cloth->colourStarts();
  ASSERT_GE(starts.size(), 2u);
  EXPECT_EQ(starts.back(), cloth->constraints().size());
  for (std::size_t c = 0; c + 1 < starts.size(); ++c) {
    std::set<std::uint32_t> seen;
    for (std::size_t i = starts[c]; i < starts[c + 1]; ++i) {
      const auto& constraint = cloth->constraints()[i].constraint;
      EXPECT_TRUE(seen.insert(constraint.a).second) << "colour " << c;
      EXPECT_TRUE(seen.insert(constraint.b).second) << "colour " << c;
    }
  }
  EXPECT_LE(starts.size() - 1, 16u) << "a grid's constraint graph needs few colours";
}

// Internal constraints move equal masses by equal and opposite amounts, so the centre of mass
// of free cloth falls exactly as a particle: c(t) = c0 + ½·g·t² (no damping).
TEST(Cloth, FreeClothsCentreOfMassFallsLikeAParticle) {
  const Grid grid = makeClothGrid(8, 0.5f);
  ClothSettings settings;
  settings.solver.damping = 0.0f;
  settings.solver.fixedStep = 1.0 / 120.0;
  auto cloth = Cloth::create(grid.positions, grid.triangles, {}, settings);
  ASSERT_TRUE(cloth.has_value());
  auto centre = [&] {
    glm::dvec3 sum(0.0);
    for (const auto& p : cloth->particles().positions) sum += glm::dvec3(p);
    return sum / double(cloth->particles().size());
  };
  const glm::dvec3 start = centre();
  for (int i = 0; i < 60; ++i) ASSERT_TRUE(cloth->advance(1.0 / 120.0).has_value());
  // Started at rest (previous = current), position Verlet with constant g gives exactly
  // x_n = x_0 + g·h²·n(n+1)/2 (the discrete parabola; → ½·g·t² as h → 0). Internal constraints
  // cannot move the centre of mass, so it follows this up to float rounding: about 2,000
  // projections per particle, each off by an ulp (1e-7 m), stay well under 1e-4 m, while a
  // biased constraint (unequal shares) would shift it by centimetres.
  const double h = 1.0 / 120.0, n = 60.0;
  EXPECT_NEAR(start.y - centre().y, 9.81 * h * h * n * (n + 1.0) / 2.0, 1e-4);
}

TEST(Cloth, PinnedVerticesFollowTheBody) {
  const Grid grid = makeClothGrid(6, 0.4f);
  auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 5}, {});
  ASSERT_TRUE(cloth.has_value());
  const glm::mat4 moved = glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, 0.1f, -0.2f}), 0.7f, {0, 1, 0});
  ASSERT_TRUE(cloth->setBodyTransform(moved).has_value());
  ASSERT_TRUE(cloth->advance(1.0 / 30.0).has_value());
  for (std::uint32_t v : {0u, 5u}) {
    const glm::vec3 expected(moved * glm::vec4(grid.positions[v], 1.0f));
    EXPECT_LT(glm::distance(cloth->particles().positions[v], expected), 1e-6f) << "vertex " << v;
  }
}

// A sheet hanging from its top corners settles. Gauss–Seidel relaxation converges, so the
// worst edge stretch must fall with every doubling of the iterations (measured here: 7.8 %,
// 3.9 %, 1.8 %, 0.8 %, 0.3 % for 5…80) and be under 1 % by 40.
TEST(Cloth, HangingSheetStretchFallsWithIterations) {
  const Grid grid = makeClothGrid(10, 0.5f);
  float previous = 1.0f;
  for (int iterations : {5, 10, 20, 40, 80}) {
    ClothSettings settings;
    settings.solver.constraintIterations = iterations;
    settings.solver.damping = 0.05f;
    settings.solver.tethers = false;  // the relaxation alone
    auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 9}, settings);
    ASSERT_TRUE(cloth.has_value());
    for (int i = 0; i < 240; ++i) ASSERT_TRUE(cloth->advance(1.0 / 60.0).has_value());
    const float stretch = maxRelativeStretch(cloth->particles(), cloth->edges());
    EXPECT_LT(stretch, previous) << iterations << " iterations";
    if (iterations >= 40) {
      EXPECT_LT(stretch, 0.01f) << iterations << " iterations";
    }
    previous = stretch;
    // It hangs: the bottom row is well below the top row.
    EXPECT_LT(cloth->particles().positions[95].y, cloth->particles().positions[5].y - 0.3f);
  }
}

// A strip pinned along one short side is a cantilever: stiffer bending droops less.
// Long-range attachments: with only 3 sweeps a shaken sheet would stretch by tens of percent;
// with tethers no free vertex ends a step farther from its pin than its rest path along the
// edges (Kim et al. 2012's guarantee; + 1e-5 m for rounding).
TEST(Cloth, TethersBoundEveryVertexByItsPathToAPin) {
  const Grid grid = makeClothGrid(12, 0.5f);
  ClothSettings settings;
  settings.solver.constraintIterations = 3;
  auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 11}, settings);
  ASSERT_TRUE(cloth.has_value());
  EXPECT_EQ(cloth->tethers().size(), 144u - 2u);
  for (int frame = 0; frame < 90; ++frame) {
    const float swing = 0.3f * float(frame % 20 < 10 ? 1 : -1);
    ASSERT_TRUE(cloth->setBodyTransform(glm::translate(glm::mat4(1.0f), {swing, 0.0f, 0.0f})).has_value());
    ASSERT_TRUE(cloth->advance(1.0 / 60.0).has_value());
    for (const Tether& tether : cloth->tethers())
      ASSERT_LE(
          glm::distance(cloth->particles().positions[tether.particle], cloth->particles().positions[tether.anchor]),
          tether.maxDistance + 1e-5f)
          << "frame " << frame << " vertex " << tether.particle;
  }
  // The bottom corner's bound is its path to the nearer top corner: 11 edges down, 0.5 m.
  const auto corner =
      std::find_if(cloth->tethers().begin(), cloth->tethers().end(), [](const Tether& t) { return t.particle == 132; });
  ASSERT_NE(corner, cloth->tethers().end());
  EXPECT_NEAR(corner->maxDistance, 0.5f, 1e-5f);
}

TEST(Cloth, StifferBendingDroopsLess) {
  auto tipDrop = [](float stiffness) {
    Grid grid;
    const int n = 12;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < 2; ++j) grid.positions.push_back({0.05f * float(i), 0.0f, 0.05f * float(j)});
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
      grid.triangles.insert(grid.triangles.end(), {a, b, c, b, d, c});
    }
    ClothSettings settings;
    settings.bendingStiffness = stiffness;
    settings.solver.constraintIterations = 16;
    settings.solver.damping = 0.1f;
    auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 1, 2, 3}, settings);
    EXPECT_TRUE(cloth.has_value());
    for (int i = 0; i < 180; ++i) EXPECT_TRUE(cloth->advance(1.0 / 60.0).has_value());
    return -cloth->particles().positions[2 * n - 1].y;
  };
  const float limp = tipDrop(0.0f), medium = tipDrop(0.3f), stiff = tipDrop(1.0f);
  EXPECT_GT(limp, medium);
  EXPECT_GT(medium, stiff);
}

// A free triangle whose vertices are all held towards the body with stiffness k settles where each
// step's fall under gravity, g·dt², less the share k pulled back, leaves it: k·(x − rest + g·dt²)
// = g·dt², so it hangs g·dt²·(1 − k)/k below its rest (its edges stay at rest length). The body
// then moves and the triangle follows it.
TEST(Cloth, ShapeHoldsSettleWhereTheirPullBalancesGravity) {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {0.1f, 0, 0}, {0, 0, 0.1f}};
  const std::vector<std::uint32_t> triangles = {0, 1, 2};
  ClothSettings settings;
  settings.solver.fixedStep = 1.0 / 60.0;
  settings.solver.damping = 0.05f;
  const float k = 0.2f;
  for (std::uint32_t v = 0; v < 3; ++v) settings.shapeHolds.push_back({v, k});
  const glm::mat4 body = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  auto cloth = Cloth::create(positions, triangles, {}, settings, body);
  ASSERT_TRUE(cloth.has_value()) << cloth.error().message;
  for (int i = 0; i < 600; ++i) ASSERT_TRUE(cloth->advance(1.0 / 60.0).has_value());
  const double dt = settings.solver.fixedStep, g = 9.81;
  const double sag = g * dt * dt * (1.0 - k) / k;
  for (std::uint32_t v = 0; v < 3; ++v) {
    const glm::vec3 p = cloth->particles().positions[v];
    EXPECT_NEAR(p.y, 1.0 - sag, 1e-5) << v;
    EXPECT_NEAR(p.x, positions[v].x, 1e-6) << v;
    EXPECT_NEAR(p.z, positions[v].z, 1e-6) << v;
  }
  ASSERT_TRUE(cloth->setBodyTransform(glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 1.0f, 0.0f))).has_value());
  for (int i = 0; i < 600; ++i) ASSERT_TRUE(cloth->advance(1.0 / 60.0).has_value());
  EXPECT_NEAR(cloth->particles().positions[1].x, 0.6f, 1e-5);
}

// A free sheet dropped onto a ball that moves with the body: after every step no particle is
// inside the ball (signed distance ≥ −1e-4 m, the frictionless last pass puts them on the
// surface), and the sheet ends up draped over it rather than falling through.
TEST(Cloth, DrapesOverABallColliderAndNeverEntersIt) {
  Grid grid = makeClothGrid(15, 0.8f);
  for (auto& p : grid.positions) p = glm::vec3(p.x - 0.4f, 0.3f, p.y + 0.4f);  // horizontal, above
  ClothSettings settings;
  settings.solver.constraintIterations = 8;
  auto cloth = Cloth::create(grid.positions, grid.triangles, {}, settings);
  ASSERT_TRUE(cloth.has_value());
  ColliderSet ball;
  ball.spheres.push_back({.centre = {0, 0, 0}, .radius = 0.2f});
  ball.friction = 0.6f;
  ASSERT_TRUE(cloth->setColliders(ball).has_value());
  const glm::vec3 offset(0.0f, -0.05f, 0.0f);  // the body (and its ball) moves down at the start
  ASSERT_TRUE(cloth->setBodyTransform(glm::translate(glm::mat4(1.0f), offset)).has_value());
  float deepest = 1.0f;
  for (int frame = 0; frame < 120; ++frame) {
    ASSERT_TRUE(cloth->advance(1.0 / 120.0).has_value());
    for (const glm::vec3& p : cloth->particles().positions)
      deepest = std::min(deepest, glm::distance(p, offset) - 0.2f);
  }
  EXPECT_GE(deepest, -1e-4f);
  // The middle of the sheet rests on top of the moved ball (friction holds it there).
  const glm::vec3 middle = cloth->particles().positions[7 * 15 + 7];
  EXPECT_NEAR(middle.y, offset.y + 0.2f, 0.01f);
  EXPECT_FALSE(Cloth::create(grid.positions, grid.triangles, {}, settings)
                   ->setColliders({.spheres = {{.centre = {0, 0, 0}, .radius = -1.0f}}})
                   .has_value());
}

TEST(Cloth, ThreadCountDoesNotChangeTheResult) {
  // 128² = 16,384 vertices: enough for 4 workers (Cloth::advance takes one per 4,096).
  const Grid grid = makeClothGrid(128, 0.6f);
  std::uint64_t hashes[3];
  const unsigned threads[3] = {1, 2, 4};
  for (int run = 0; run < 3; ++run) {
    auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0, 127}, {});
    ASSERT_TRUE(cloth.has_value());
    for (int frame = 0; frame < 10; ++frame) {
      const glm::mat4 body = glm::rotate(glm::mat4(1.0f), 0.05f * float(frame), {0, 1, 0});
      ASSERT_TRUE(cloth->setBodyTransform(body).has_value());
      ASSERT_TRUE(cloth->advance(1.0 / 60.0, threads[run]).has_value());
    }
    hashes[run] = cloth->stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

TEST(Cloth, BadInputIsNamed) {
  const Grid grid = makeClothGrid(3, 1.0f);
  auto message = [&](std::vector<glm::vec3> positions, std::vector<std::uint32_t> triangles,
                     std::vector<std::uint32_t> pins) {
    auto cloth = Cloth::create(positions, triangles, pins, {});
    return cloth ? std::string("(created)") : cloth.error().message;
  };
  EXPECT_NE(message(grid.positions, {0, 1, 42}, {}).find("triangle 0 uses vertex 42"), std::string::npos);
  EXPECT_NE(message(grid.positions, {0, 1, 1}, {}).find("repeats a vertex"), std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2}, {}).find("zero area"), std::string::npos);
  auto nan = grid.positions;
  nan[4].x = std::nanf("");
  EXPECT_NE(message(nan, grid.triangles, {}).find("vertex 4 is NaN"), std::string::npos);
  EXPECT_NE(message(grid.positions, grid.triangles, {99}).find("pinned cloth vertex 99"), std::string::npos);
  EXPECT_NE(message({}, {}, {}).find("empty"), std::string::npos);

  auto withHolds = [&](std::vector<ClothShapeHold> holds) {
    ClothSettings settings;
    settings.shapeHolds = std::move(holds);
    auto cloth = Cloth::create(grid.positions, grid.triangles, Pins{0}, settings);
    return cloth ? std::string("(created)") : cloth.error().message;
  };
  EXPECT_EQ(withHolds({{9, 0.5f}}), "ClothSettings.shapeHolds[0] holds vertex 9 but the mesh has 9");
  EXPECT_EQ(withHolds({{0, 0.5f}}), "ClothSettings.shapeHolds[0]: vertex 0 is pinned");
  EXPECT_EQ(withHolds({{4, 0.5f}, {4, 0.5f}}), "ClothSettings.shapeHolds[1]: vertex 4 is held twice");
  EXPECT_EQ(withHolds({{4, 1.5f}}), "ClothSettings.shapeHolds[0].stiffness must be in (0, 1], got 1.500000");
  EXPECT_EQ(withHolds({{4, 1.0f}}), "(created)");
}

}  // namespace
}  // namespace mane::physics
