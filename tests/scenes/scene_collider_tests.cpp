// The `colliders` block of grooms and cloths (scenes/README.md, "Colliders"): what a valid block
// becomes in the Scene, and the field path every mistake is reported at.

#include <gtest/gtest.h>

#include <string>

#include "scenes/scene.hpp"

namespace mane::scenes {
namespace {

/// A scene with a head mesh, one groom and one cloth attached to it; `groomColliders` and
/// `clothColliders` are spliced in as the JSON of their `colliders` fields (empty: absent).
std::string sceneWith(const std::string& groomColliders, const std::string& clothColliders = "") {
  return R"({"name": "c", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
    "meshes": [{"name": "head", "source": "procedural:sphere", "transform": {"scale": 0.1}},
               {"name": "body", "source": "procedural:sphere"}],
    "grooms": [{"name": "hair", "source": "procedural", "attached_mesh": "head")" +
         (groomColliders.empty() ? "" : ", \"colliders\": " + groomColliders) + R"(}],
    "cloths": [{"name": "cape", "source": "procedural:grid", "attached_mesh": "head")" +
         (clothColliders.empty() ? "" : ", \"colliders\": " + clothColliders) + "}]}";
}

std::string errorOf(const std::string& text) {
  auto scene = parseScene(text, "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

TEST(SceneColliders, AValidBlockArrivesInTheSceneAsWritten) {
  auto scene = parseScene(sceneWith(R"({
      "spheres": [{"centre": [0.0, 0.06, 0.01], "radius": 0.04}, {"centre": [1, 2, 3], "radius": 0.5}],
      "capsules": [{"a": [-0.002, 0.0, -0.008], "b": [-0.002, -0.05, -0.008], "radius": 0.026}],
      "sdf": {"mesh": "head", "resolution": 32},
      "friction": 0.2,
      "thickness": 0.001})",
                                    R"({"capsules": [{"a": [0, -0.1, 0], "b": [0, -0.1, 0], "radius": 0.12}],
                                        "sdf": {"mesh": "body"}})"),
                          "c.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const Colliders& hair = scene->grooms[0].colliders;
  ASSERT_EQ(hair.spheres.size(), 2u);
  EXPECT_EQ(hair.spheres[0].centre, glm::vec3(0.0f, 0.06f, 0.01f));
  EXPECT_EQ(hair.spheres[0].radius, 0.04f);
  EXPECT_EQ(hair.spheres[1].centre, glm::vec3(1, 2, 3));
  EXPECT_EQ(hair.spheres[1].radius, 0.5f);
  ASSERT_EQ(hair.capsules.size(), 1u);
  EXPECT_EQ(hair.capsules[0].a, glm::vec3(-0.002f, 0.0f, -0.008f));
  EXPECT_EQ(hair.capsules[0].b, glm::vec3(-0.002f, -0.05f, -0.008f));
  EXPECT_EQ(hair.capsules[0].radius, 0.026f);
  ASSERT_TRUE(hair.sdf.has_value());
  EXPECT_EQ(hair.sdf->mesh, "head");
  EXPECT_EQ(hair.sdf->resolution, 32);
  EXPECT_EQ(hair.friction, 0.2f);
  EXPECT_EQ(hair.thickness, 0.001f);
  EXPECT_FALSE(hair.empty());

  // The cloth's block: a capsule with a = b (a sphere) is allowed; the documented defaults apply.
  const Colliders& cape = scene->cloths[0].colliders;
  EXPECT_TRUE(cape.spheres.empty());
  ASSERT_EQ(cape.capsules.size(), 1u);
  EXPECT_EQ(cape.capsules[0].a, cape.capsules[0].b);
  ASSERT_TRUE(cape.sdf.has_value());
  EXPECT_EQ(cape.sdf->mesh, "body");
  EXPECT_EQ(cape.sdf->resolution, 48);
  EXPECT_EQ(cape.friction, 0.0f);
  EXPECT_EQ(cape.thickness, 0.0f);
}

TEST(SceneColliders, NoBlockMeansNoColliders) {
  auto scene = parseScene(sceneWith("", "{}"), "c.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_TRUE(scene->grooms[0].colliders.empty());
  EXPECT_TRUE(scene->cloths[0].colliders.empty());
  EXPECT_FALSE(scene->grooms[0].colliders.sdf.has_value());
}

TEST(SceneColliders, BadShapesAreReportedAtTheirFieldPath) {
  EXPECT_EQ(errorOf(sceneWith(R"({"spheres": [{"centre": [0, 0, 0], "radius": 0.1},
                                              {"centre": [0, 0, 0], "radius": -0.1}]})")),
            "dir/bad.json: grooms[0].colliders.spheres[1].radius: expected a radius > 0 metres");
  EXPECT_EQ(errorOf(sceneWith(R"({"spheres": [{"centre": [0, 0, 0], "radius": 0}]})")),
            "dir/bad.json: grooms[0].colliders.spheres[0].radius: expected a radius > 0 metres");
  EXPECT_EQ(errorOf(sceneWith("", R"({"capsules": [{"a": [0, 0, 0], "b": [0, 1, 0], "radius": -2}]})")),
            "dir/bad.json: cloths[0].colliders.capsules[0].radius: expected a radius > 0 metres");
  EXPECT_EQ(errorOf(sceneWith(R"({"capsules": [{"a": [0, 0, 0], "radius": 0.1}]})")),
            "dir/bad.json: grooms[0].colliders.capsules[0].b: required field is missing");
  EXPECT_EQ(errorOf(sceneWith(R"({"spheres": [{"centre": [0, 0], "radius": 0.1}]})")),
            "dir/bad.json: grooms[0].colliders.spheres[0].centre: expected an array of 3 numbers, got 2 elements");
  EXPECT_EQ(errorOf(sceneWith(R"({"spheres": {"centre": [0, 0, 0], "radius": 0.1}})")),
            "dir/bad.json: grooms[0].colliders.spheres: expected an array, got an object");
}

TEST(SceneColliders, NonFiniteNumbersAreRejectedWhereTheyAreWritten) {
  // JSON has no NaN or infinity; a number beyond float range would become one.
  EXPECT_EQ(errorOf(sceneWith(R"({"capsules": [{"a": [0, 1e39, 0], "b": [0, 0, 0], "radius": 0.1}]})")),
            "dir/bad.json: grooms[0].colliders.capsules[0].a[1]: expected a finite number within float range "
            "(|x| < 3.4e38)");
  EXPECT_EQ(errorOf(sceneWith(R"({"spheres": [{"centre": [0, 0, 0], "radius": -1e39}]})")),
            "dir/bad.json: grooms[0].colliders.spheres[0].radius: expected a finite number within float range "
            "(|x| < 3.4e38)");
  EXPECT_EQ(errorOf(sceneWith("", R"({"friction": 1e40})")),
            "dir/bad.json: cloths[0].colliders.friction: expected a finite number within float range "
            "(|x| < 3.4e38)");
}

TEST(SceneColliders, TheFieldMustNameAMeshAtAUsableResolution) {
  EXPECT_EQ(errorOf(sceneWith(R"({"sdf": {"mesh": "torso"}})")),
            "dir/bad.json: grooms[0].colliders.sdf.mesh: no mesh named \"torso\" in meshes, nor a character part \"<character>/<mesh>\" of characters");
  EXPECT_EQ(errorOf(sceneWith("", R"({"sdf": {"mesh": "torso", "resolution": 32}})")),
            "dir/bad.json: cloths[0].colliders.sdf.mesh: no mesh named \"torso\" in meshes, nor a character part \"<character>/<mesh>\" of characters");
  EXPECT_EQ(errorOf(sceneWith(R"({"sdf": {"resolution": 32}})")),
            "dir/bad.json: grooms[0].colliders.sdf.mesh: required field is missing");
  EXPECT_EQ(errorOf(sceneWith(R"({"sdf": {"mesh": "head", "resolution": 7}})")),
            "dir/bad.json: grooms[0].colliders.sdf.resolution: expected a resolution in 8..128 grid nodes");
  EXPECT_EQ(errorOf(sceneWith(R"({"sdf": {"mesh": "head", "resolution": 129}})")),
            "dir/bad.json: grooms[0].colliders.sdf.resolution: expected a resolution in 8..128 grid nodes");
  EXPECT_EQ(errorOf(sceneWith(R"({"sdf": {"mesh": "head", "resolution": 47.5}})")),
            "dir/bad.json: grooms[0].colliders.sdf.resolution: expected an integer, got a fraction");
  EXPECT_EQ(errorOf(sceneWith(R"({"sdf": "head"})")),
            "dir/bad.json: grooms[0].colliders.sdf: expected an object, got a string");
}

TEST(SceneColliders, FrictionAndThicknessMustBeInRange) {
  EXPECT_EQ(errorOf(sceneWith(R"({"friction": -0.1})")),
            "dir/bad.json: grooms[0].colliders.friction: expected a friction coefficient >= 0");
  EXPECT_EQ(errorOf(sceneWith("", R"({"thickness": -0.001})")),
            "dir/bad.json: cloths[0].colliders.thickness: expected a thickness in [0, 1] metres");
  EXPECT_EQ(errorOf(sceneWith(R"({"thickness": 2})")),
            "dir/bad.json: grooms[0].colliders.thickness: expected a thickness in [0, 1] metres");
}

TEST(SceneColliders, UnknownFieldsAreTypos) {
  const std::string message = errorOf(sceneWith(R"({"spheres": [{"center": [0, 0, 0], "radius": 0.1}]})"));
  EXPECT_NE(message.find("dir/bad.json: grooms[0].colliders.spheres[0].center: unknown field"), std::string::npos)
      << message;
  EXPECT_NE(message.find("centre"), std::string::npos) << message;  // lists the known ones
  EXPECT_NE(
      errorOf(sceneWith(R"({"sdf": {"mesh": "head", "res": 32}})")).find("grooms[0].colliders.sdf.res: unknown field"),
      std::string::npos);
  EXPECT_NE(errorOf(sceneWith("", R"({"boxes": []})")).find("cloths[0].colliders.boxes: unknown field"),
            std::string::npos);
}

}  // namespace
}  // namespace mane::scenes
