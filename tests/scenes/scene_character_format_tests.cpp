// The scene file's character entries (scenes/README.md, "Characters"), joint-borne colliders
// and pinned cloth: what a valid entry becomes, and each mistake named by its JSON path.

#include <gtest/gtest.h>

#include <string>

#include "scenes/scene.hpp"
#include "scenes/scene_character.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

/// A scene with one character entry `character` (its inner fields) and optional extra top-level
/// fields `more`.
std::string sceneWith(const std::string& character, const std::string& more = "") {
  return R"({"name": "c", "camera": {"position": [0, 1, 3], "target": [0, 1, 0]},
             "materials": [{"name": "m"}],
             "characters": [{"name": "robot", "source": "robot.glb")" +
         (character.empty() ? "" : ", " + character) + "}]" + (more.empty() ? "" : ", " + more) + "}";
}

std::string errorOf(const std::string& text) {
  auto scene = parseScene(text, "dir/c.json");
  return scene ? std::string() : scene.error().message;
}

TEST(SceneCharacterFormat, AFullEntryKeepsEveryField) {
  auto scene = parseScene(sceneWith(R"("transform": {"scale": 0.5}, "material": "m", "materials": {"Main": "m"},
      "skinning": "dual_quaternion",
      "clips": [{"clip": "Walking"}, {"clip": "Dance", "start": 4, "speed": 2, "loop": false, "cross_fade": 0.5}],
      "morphs": [{"target": "Sad", "weight": 0.25}, {"target": "Angry", "keys": [{"time": 1, "weight": 0}, {"time": 2, "weight": 1}]}],
      "subdivision": {"meshes": ["Hand.L"], "max_pixel_error": 2})",
                                    R"("grooms": [{"name": "g", "source": "procedural", "attached_mesh": "robot/Head",
                                      "colliders": {"spheres": [{"joint": "Head", "centre": [0, 0.1, 0], "radius": 0.2}],
                                                    "capsules": [{"joint": "Neck", "to_joint": "Head", "radius": 0.1}]}}],
                                      "cloths": [{"name": "cape", "source": "procedural:grid", "attached_mesh": "robot/Torso",
                                      "pinned": {"vertices": [0, 3], "regions": [{"min": [-1, -0.1, -1], "max": [1, 0, 1]}]}}])"),
                          "c.json");
  ASSERT_TRUE(scene) << scene.error().message;
  const CharacterInstance& robot = scene->characters.at(0);
  EXPECT_EQ(robot.transform.scale, 0.5f);
  EXPECT_EQ(robot.skinning, physics::SkinningMethod::DualQuaternion);
  ASSERT_EQ(robot.clips.size(), 2u);
  EXPECT_EQ(robot.clips[0].startSeconds, 0.0f);
  EXPECT_TRUE(robot.clips[0].loop);
  EXPECT_EQ(robot.clips[1].speed, 2.0f);
  EXPECT_FALSE(robot.clips[1].loop);
  EXPECT_EQ(robot.clips[1].crossFadeSeconds, 0.5f);
  ASSERT_EQ(robot.morphs.size(), 2u);
  EXPECT_EQ(robot.morphs[0].weightAt(7.0f), 0.25f);
  EXPECT_EQ(robot.morphs[1].weightAt(0.0f), 0.0f);  // held before the first key
  EXPECT_EQ(robot.morphs[1].weightAt(1.5f), 0.5f);
  EXPECT_EQ(robot.morphs[1].weightAt(9.0f), 1.0f);  // and after the last
  EXPECT_EQ(robot.subdividedMeshes, std::vector<std::string>{"Hand.L"});
  ASSERT_TRUE(robot.subdivision);
  EXPECT_EQ(robot.subdivision->maxPixelError, 2.0f);
  const Colliders& colliders = scene->grooms.at(0).colliders;
  ASSERT_EQ(colliders.jointSpheres.size(), 1u);
  EXPECT_EQ(colliders.jointSpheres[0].joint, "Head");
  ASSERT_EQ(colliders.jointCapsules.size(), 1u);
  EXPECT_EQ(colliders.jointCapsules[0].toJoint, "Head");
  EXPECT_TRUE(colliders.spheres.empty() && colliders.capsules.empty());
  const Cloth& cape = scene->cloths.at(0);
  EXPECT_FALSE(cape.pinTopEdge);
  EXPECT_EQ(cape.pinVertices, (std::vector<std::uint32_t>{0, 3}));
  ASSERT_EQ(cape.pinRegions.size(), 1u);
}

TEST(SceneCharacterFormat, MistakesAreNamedByTheirPath) {
  const auto starts = [](const std::string& text, const std::string& prefix) {
    const std::string message = errorOf(text);
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  };
  starts(sceneWith(R"("skinning": "quaternion")"), "dir/c.json: characters[0].skinning: expected \"linear_blend\"");
  starts(sceneWith(R"("clips": [{"clip": "A", "start": 2}, {"clip": "B", "start": 1}])"),
         "dir/c.json: characters[0].clips[1].start: expected start times in strictly increasing order");
  starts(sceneWith(R"("clips": [{"clip": "A", "speed": 0}])"), "dir/c.json: characters[0].clips[0].speed");
  starts(sceneWith(R"("morphs": [{"target": "Sad", "weight": 1, "keys": [{"time": 0, "weight": 1}]}])"),
         "dir/c.json: characters[0].morphs[0]: expected either \"weight\" or \"keys\"");
  starts(sceneWith(R"("materials": {"Main": "nothing"})"), "dir/c.json: characters[0].materials.Main: no material");
  starts(sceneWith(R"("subdivision": {"max_pixel_error": 1})"), "dir/c.json: characters[0].subdivision.meshes");
  starts(sceneWith("", R"("grooms": [{"name": "g", "source": "procedural", "attached_mesh": "ghost/Head"}])"),
         "dir/c.json: grooms[0].attached_mesh: no mesh named \"ghost/Head\"");
  starts(sceneWith("", R"("meshes": [{"name": "a/b", "source": "procedural:sphere"}])"),
         "dir/c.json: meshes[0].name: expected a name without '/'");
  // A joint needs a character to take it from: the body must be a character part.
  starts(sceneWith("", R"("meshes": [{"name": "ball", "source": "procedural:sphere"}],
                         "grooms": [{"name": "g", "source": "procedural", "attached_mesh": "ball",
                                     "colliders": {"spheres": [{"joint": "Head", "centre": [0, 0, 0], "radius": 1}]}}])"),
         "dir/c.json: grooms[0].colliders: shapes with a \"joint\" need a body that is a character part");
  starts(sceneWith("", R"("grooms": [{"name": "g", "source": "procedural", "attached_mesh": "robot/Head",
                           "colliders": {"capsules": [{"to_joint": "Head", "radius": 1}]}}])"),
         "dir/c.json: grooms[0].colliders.capsules[0].to_joint: needs \"joint\"");
  starts(sceneWith("", R"("grooms": [{"name": "g", "source": "procedural", "attached_mesh": "robot/Head",
                           "colliders": {"capsules": [{"joint": "Neck", "to_joint": "Head", "a": [0, 0, 0], "radius": 1}]}}])"),
         "dir/c.json: grooms[0].colliders.capsules[0].a: a capsule from \"joint\" to \"to_joint\"");
  starts(sceneWith("", R"("cloths": [{"name": "c", "source": "procedural:grid", "attached_mesh": "robot/Torso",
                           "pinned": {"regions": [{"min": [0, 0, 0], "max": [-1, 1, 1]}]}}])"),
         "dir/c.json: cloths[0].pinned.regions[0].max: expected a corner at or above \"min\"");
  starts(sceneWith("", R"("cloths": [{"name": "c", "source": "procedural:grid", "attached_mesh": "robot/Torso",
                           "pinned": "corners"}])"),
         "dir/c.json: cloths[0].pinned: expected \"top_edge\", \"none\" or an object");
}

TEST(SceneCharacterFormat, RigidPartKeepsRotationAndTranslationAndDropsScale) {
  const glm::mat4 placement = Transform{.translation = {1, 2, 3}, .rotationDegrees = {30, 40, 50}, .scale = 7}.matrix();
  const glm::mat4 rigid = rigidPart(placement);
  const glm::mat4 expected = Transform{.translation = {1, 2, 3}, .rotationDegrees = {30, 40, 50}}.matrix();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(rigid[c][r], expected[c][r], 1e-6f) << c << "," << r;
}

}  // namespace
}  // namespace mane::scenes
