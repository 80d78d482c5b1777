// Fur in scene files: a material of kind "fur" and its `fur` block (defaults, every field,
// errors that name the field path), and the rule that fur grows on meshes, not on cloth.

#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "render/frame.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {
namespace {

std::string sceneWithMaterial(const std::string& fields) {
  return R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
             "materials": [{"name": "pelt")" +
         fields + "}]}";
}

std::string errorOf(const std::string& materialFields) {
  auto scene = parseScene(sceneWithMaterial(materialFields), "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

Material materialOf(const std::string& materialFields) {
  auto scene = parseScene(sceneWithMaterial(materialFields), "x.json");
  EXPECT_TRUE(scene.has_value()) << scene.error().message;
  return scene ? scene->materials[0] : Material{};
}

TEST(SceneFur, TakesTheRenderersDefaultsAndEveryField) {
  const render::FurParameters defaults;
  const Material plain = materialOf(R"(, "kind": "fur", "albedo_texture": "fur/grass_CC0.png")");
  EXPECT_EQ(plain.kind, MaterialKind::fur);
  EXPECT_EQ(plain.fur.layers, defaults.layers);
  EXPECT_EQ(plain.fur.thickness, defaults.thickness);
  EXPECT_EQ(plain.furUvScale, 1.0f);
  const Material full = materialOf(R"(, "kind": "fur", "albedo_texture": "fur/grass_CC0.png",
      "fur": {"layers": 32, "pixels_per_layer": 2.5, "thickness": 0.01, "uv_scale": 20, "fins": false, "lay_degrees": 45,
              "specular_exponent": 80, "specular_strength": 0.2, "comb": [0, -0.5, 0],
              "dynamics": {"guides": 500, "shape_stiffness": 0.7, "damping": 0.1, "iterations": 6},
              "lay_direction": [1, 0, 0]})");
  EXPECT_EQ(full.fur.layers, 32u);
  EXPECT_EQ(plain.fur.pixelsPerLayer, defaults.pixelsPerLayer);
  EXPECT_FLOAT_EQ(full.fur.pixelsPerLayer, 2.5f);
  EXPECT_FLOAT_EQ(full.fur.thickness, 0.01f);
  EXPECT_FLOAT_EQ(full.furUvScale, 20.0f);
  EXPECT_FALSE(full.fur.fins);
  EXPECT_NEAR(full.fur.layAngle, std::numbers::pi / 4.0, 1e-6);
  EXPECT_FLOAT_EQ(full.fur.specularExponent, 80.0f);
  EXPECT_FLOAT_EQ(full.fur.specularStrength, 0.2f);
  EXPECT_EQ(full.fur.comb, glm::vec3(0.0f, -0.5f, 0.0f));
  EXPECT_EQ(plain.fur.layDirection, glm::vec3(0.0f)) << "the photo by uvs unless a field is given";
  EXPECT_EQ(full.fur.layDirection, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_FLOAT_EQ(full.fur.layRepeatsPerMetre, 20.0f) << "uv_scale, per metre along the surface";
  EXPECT_FALSE(plain.furMotion.has_value()) << "fur stands still unless it asks for dynamics";
  ASSERT_TRUE(full.furMotion.has_value());
  EXPECT_EQ(full.furMotion->guides, 500);
  EXPECT_FLOAT_EQ(full.furMotion->shapeStiffness, 0.7f);
  EXPECT_FLOAT_EQ(full.furMotion->damping, 0.1f);
  EXPECT_EQ(full.furMotion->iterations, 6);
}

TEST(SceneFur, ErrorsNameTheFieldPath) {
  const std::string at = "dir/bad.json: materials[0]";
  const std::string fur = R"(, "kind": "fur", "albedo_texture": "fur/grass_CC0.png", "fur": )";
  EXPECT_EQ(errorOf(R"(, "kind": "fur")"),
            at + ".albedo_texture: a fur material needs the photo its shells are made from");
  EXPECT_EQ(errorOf(R"(, "fur": {"layers": 4})"), at + ".fur: applies to materials of kind \"fur\" only");
  EXPECT_EQ(errorOf(R"(, "kind": "felt")"), at + ".kind: expected \"lambert\", \"skin\" or \"fur\", got \"felt\"");
  EXPECT_EQ(errorOf(fur + R"({"layers": 0})"), at + ".fur.layers: expected 1..64 shells");
  EXPECT_EQ(errorOf(fur + R"({"layers": 65})"), at + ".fur.layers: expected 1..64 shells");
  EXPECT_EQ(errorOf(fur + R"({"pixels_per_layer": -1})"),
            at + ".fur.pixels_per_layer: expected pixels of fur height per shell in [0, 100] (0: always every shell)");
  EXPECT_EQ(errorOf(fur + R"({"thickness": 0})"), at + ".fur.thickness: expected a fur height in (0, 0.1] metres");
  EXPECT_EQ(errorOf(fur + R"({"uv_scale": -1})"),
            at + ".fur.uv_scale: expected photo repeats per uv unit in (0, 10000]");
  EXPECT_EQ(errorOf(fur + R"({"lay_degrees": 95})"), at + ".fur.lay_degrees: expected an angle in [0, 90] degrees");
  EXPECT_EQ(errorOf(fur + R"({"comb": [0, -3, 0]})"), at + ".fur.comb: expected a lean of at most 2 fur heights");
  EXPECT_EQ(errorOf(fur + R"({"dynamics": {"guides": 0}})"),
            at + ".fur.dynamics.guides: expected 1..100000 guide strands");
  EXPECT_EQ(errorOf(fur + R"({"shells": 15})").rfind(at + ".fur.shells: unknown field", 0), 0u);
}

TEST(SceneFur, ClothCannotWearFur) {
  auto scene = parseScene(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
      "materials": [{"name": "pelt", "kind": "fur", "albedo_texture": "fur/grass_CC0.png"}],
      "meshes": [{"name": "head", "source": "procedural:sphere"}],
      "cloths": [{"name": "cape", "source": "procedural:grid", "attached_mesh": "head", "material": "pelt"}]})",
                          "dir/bad.json");
  ASSERT_FALSE(scene.has_value());
  EXPECT_EQ(scene.error().message,
            "dir/bad.json: cloths[0].material: fur grows on meshes, not on cloth (its shells need a mesh that does "
            "not deform)");
}

}  // namespace
}  // namespace mane::scenes
