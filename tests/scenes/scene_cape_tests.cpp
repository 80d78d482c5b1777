// "procedural:cape" cloths and cloth self collision (scenes/README.md, "Cloths"): the block as it
// arrives in the Scene, the errors, the cut's geometry, and a pattern that rests flat.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "scenes/scene.hpp"
#include "scenes/scene_cloth.hpp"
#include "tests/scenes/test_support.hpp"

namespace mane::scenes {
namespace {

using testing::sceneWithCloth;

std::string errorOf(const std::string& cloth) {
  auto scene = parseScene(sceneWithCloth(cloth), "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

TEST(SceneCape, TheCutArrivesAsWrittenAndDefaultsAsDocumented) {
  auto scene = parseScene(sceneWithCloth(R"("source": "procedural:cape",
      "cape": {"collar_radius": 0.05, "hem_radius": 0.2, "length": 0.3, "wrap_degrees": 180, "columns": 10,
               "rows": 7},
      "simulation": {"self_collision": 0.002})"),
                          "c.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const Cloth& cloth = scene->cloths[0];
  EXPECT_EQ(cloth.cape.collarRadius, 0.05f);
  EXPECT_EQ(cloth.cape.hemRadius, 0.2f);
  EXPECT_EQ(cloth.cape.length, 0.3f);
  EXPECT_EQ(cloth.cape.wrapDegrees, 180.0f);
  EXPECT_EQ(cloth.cape.columns, 10);
  EXPECT_EQ(cloth.cape.rows, 7);
  EXPECT_EQ(cloth.selfCollision, 0.002f);

  auto plain = parseScene(sceneWithCloth(R"("source": "procedural:cape")"), "c.json");
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  EXPECT_EQ(plain->cloths[0].cape.columns, CapeShape{}.columns);
  EXPECT_EQ(plain->cloths[0].selfCollision, 0.0f);
}

TEST(SceneCape, MistakesAreReportedAtTheirField) {
  const auto expectError = [](const std::string& cloth, const std::string& expected) {
    const std::string message = errorOf(cloth);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  expectError(
      R"("source": "procedural:cloak")",
      R"(cloths[0].source: expected a mesh asset, a file path, "procedural:grid", "procedural:cape" or "procedural:fin")");
  expectError(R"("source": "procedural:grid", "cape": {})",
              R"(cloths[0].cape: applies to "procedural:cape" cloths only)");
  expectError(R"("source": "procedural:cape", "cape": {"collar_radius": 0})",
              "cloths[0].cape.collar_radius: expected a radius in (0, 10]");
  expectError(R"("source": "procedural:cape", "cape": {"hem_radius": 0.01})",
              "cloths[0].cape.hem_radius: expected a radius from collar_radius to collar_radius + length");
  expectError(R"("source": "procedural:cape", "cape": {"length": 0.1, "hem_radius": 0.5})",
              "cloths[0].cape.hem_radius");
  expectError(R"("source": "procedural:cape", "cape": {"wrap_degrees": 400})",
              "cloths[0].cape.wrap_degrees: expected an angle in (0, 360]");
  expectError(R"("source": "procedural:cape", "cape": {"columns": 1})",
              "cloths[0].cape.columns: expected 2..512 vertices");
  expectError(R"("source": "procedural:cape", "cape": {"rows": 600})", "cloths[0].cape.rows: expected 2..512 vertices");
  expectError(R"("source": "procedural:cape", "cape": {"sleeves": 2})", "cloths[0].cape.sleeves");
  expectError(R"("source": "procedural:cape", "simulation": {"self_collision": -0.001})",
              "cloths[0].simulation.self_collision: expected a thickness in [0, 0.1] metres");
}

// The cut: rows × columns vertices; the top row on the collar's arc (radius, height 0, the wrap
// centred on −z), the bottom row on the hem's at the depth a cone's side of that slant has.
TEST(SceneCape, TheMeshIsACone_sSideFromCollarToHem) {
  Cloth cloth;
  cloth.name = "cape";
  cloth.source = "procedural:cape";
  cloth.cape = {
      .collarRadius = 0.05f, .hemRadius = 0.2f, .length = 0.25f, .wrapDegrees = 240.0f, .columns = 25, .rows = 11};
  auto mesh = loadClothMesh(cloth, testing::resolverWithoutAssets(), ".");
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  ASSERT_EQ(mesh->positions.size(), 25u * 11u);
  EXPECT_EQ(mesh->indices.size(), 24u * 10u * 6u);
  const float drop = std::sqrt(0.25f * 0.25f - 0.15f * 0.15f);  // 0.2 m
  for (int column = 0; column < 25; ++column) {
    const glm::vec3 top = mesh->positions[std::size_t(column)], hem = mesh->positions[std::size_t(10 * 25 + column)];
    EXPECT_NEAR(std::hypot(top.x, top.z), 0.05f, 1e-6f);
    EXPECT_EQ(top.y, 0.0f);
    EXPECT_NEAR(std::hypot(hem.x, hem.z), 0.2f, 1e-6f);
    EXPECT_NEAR(hem.y, -drop, 1e-6f);
    const float angle = std::atan2(top.x, -top.z) * 180.0f / std::numbers::pi_v<float>;
    EXPECT_NEAR(angle, -120.0f + 240.0f * float(column) / 24.0f, 1e-3f);
  }
}

// A cut cloth rests flat: across every interior edge the bending constraint's rest length is the
// distance between the two opposite corners once the two triangles are unfolded into one plane,
// which follows from the five edges' rest lengths alone. The cone it starts as is curved, so its
// own distances are shorter (checked too, else this would prove nothing), while its edges are the
// pattern's.
TEST(SceneCape, ItsBendingRestsOnTheFlatPattern) {
  Cloth cloth;
  cloth.name = "cape";
  cloth.source = "procedural:cape";
  cloth.attachedMesh = "body";
  cloth.bendingStiffness = 0.5f;
  cloth.cape = {
      .collarRadius = 0.05f, .hemRadius = 0.2f, .length = 0.25f, .wrapDegrees = 240.0f, .columns = 17, .rows = 9};
  auto mesh = loadClothMesh(cloth, testing::resolverWithoutAssets(), ".");
  ASSERT_TRUE(mesh.has_value());
  auto built = SceneCloth::create(cloth, *mesh, SimulationSettings{}, glm::mat4(1.0f));
  ASSERT_TRUE(built.has_value()) << built.error().message;
  std::map<std::pair<std::uint32_t, std::uint32_t>, float> rest;
  for (const physics::SoftDistanceConstraint& c : built->cloth().constraints())
    rest[{std::min(c.constraint.a, c.constraint.b), std::max(c.constraint.a, c.constraint.b)}] =
        c.constraint.restLength;
  const auto restOf = [&](std::uint32_t a, std::uint32_t b) { return rest.at({std::min(a, b), std::max(a, b)}); };

  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> opposite;
  for (std::size_t t = 0; t < mesh->indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh->indices[t + k], b = mesh->indices[t + (k + 1) % 3];
      opposite[{std::min(a, b), std::max(a, b)}].push_back(mesh->indices[t + (k + 2) % 3]);
    }
  int hinges = 0, curved = 0;
  for (const auto& [edge, corners] : opposite) {
    if (corners.size() != 2) continue;
    const auto [a, b] = edge;
    const std::uint32_t c = corners[0], d = corners[1];
    // Two pinned corners have no constraint between them: such a hinge (on the collar) is left out.
    const bool constrained =
        rest.contains({std::min(a, b), b}) && rest.contains({std::min(c, d), std::max(c, d)}) &&
        rest.contains({std::min(a, c), std::max(a, c)}) && rest.contains({std::min(b, c), std::max(b, c)}) &&
        rest.contains({std::min(a, d), std::max(a, d)}) && rest.contains({std::min(b, d), std::max(b, d)});
    if (!constrained) continue;
    // a at the origin, b on +x; c above the axis, d below it, from their distances to a and b.
    const double ab = restOf(a, b);
    const auto place = [&](std::uint32_t v, double sign) {
      const double av = restOf(a, v), bv = restOf(b, v);
      const double x = (av * av - bv * bv + ab * ab) / (2.0 * ab);
      return glm::dvec2(x, sign * std::sqrt(std::max(0.0, av * av - x * x)));
    };
    const double flat = glm::distance(place(c, 1.0), place(d, -1.0));
    EXPECT_NEAR(restOf(c, d), flat, 1e-4 * flat) << "hinge " << a << "-" << b;
    curved += glm::distance(mesh->positions[c], mesh->positions[d]) < flat * (1.0 - 1e-4);
    ++hinges;
  }
  EXPECT_GT(hinges, 200);
  // A cone's side is developable: along the mesh's edges the pattern is the cone, up to the
  // difference between the chords of the arcs (1 − cos² α times Δθ²/24, 0.3 % here).
  for (const physics::DistanceConstraint& edge : built->cloth().edges())
    EXPECT_NEAR(glm::distance(mesh->positions[edge.a], mesh->positions[edge.b]), edge.restLength,
                0.005f * edge.restLength);
  EXPECT_GT(curved, hinges / 4) << "the cone should be curved across its columns";
}

}  // namespace
}  // namespace mane::scenes
