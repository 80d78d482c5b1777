// Scene files: the shipped scenes load and make sense; bad files fail with the file name,
// the JSON field path and what was expected.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/scene.hpp"
#include "scenes/scene_meshes.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using testing::ScratchDir;

const std::filesystem::path kScenes = std::filesystem::path(MANE_SOURCE_DIR) / "scenes";

/// The smallest valid scene; tests splice one mistake into it.
constexpr const char* kMinimal = R"({
  "name": "minimal",
  "camera": { "position": [0, 0, 1], "target": [0, 0, 0] }
})";

/// Parses `text` as file "bad.json" and returns the error message ("" on success).
std::string errorOf(const std::string& text) {
  auto scene = parseScene(text, "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

TEST(Scene, MinimalSceneGetsTheDocumentedDefaults) {
  auto scene = parseScene(kMinimal, "minimal.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->output.width, 1280);
  EXPECT_EQ(scene->output.height, 720);
  EXPECT_EQ(scene->camera.up, glm::vec3(0, 1, 0));
  EXPECT_TRUE(scene->lights.empty());
  EXPECT_EQ(scene->headMotion.kind, HeadMotionKind::none);
  EXPECT_FLOAT_EQ(scene->simulation.stepSeconds, 1.0f / 120.0f);
}

TEST(Scene, NaluLoadsWithTheLeePerrySmithHeadAndItsMaps) {
  auto scene = loadScene(kScenes / "nalu.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->output.width, 1280);
  EXPECT_EQ(scene->output.height, 720);
  ASSERT_EQ(scene->lights.size(), 2u);  // key and back light
  EXPECT_NEAR(glm::length(scene->lights[0].direction), 1.0f, 1e-6f);
  const MeshInstance* head = scene->findMesh("head");
  ASSERT_NE(head, nullptr);
  EXPECT_EQ(head->source, "head/LeePerrySmith/LeePerrySmith.glb");
  const Material* skin = scene->findMaterial(head->material);
  ASSERT_NE(skin, nullptr);
  EXPECT_EQ(skin->albedoTexture, "head/LeePerrySmith/Map-COL.jpg");
  EXPECT_EQ(skin->normalMap, "head/LeePerrySmith/Infinite-Level_02_Tangent_SmoothUV.jpg");
  EXPECT_EQ(skin->specularMap, "head/LeePerrySmith/Map-SPEC.jpg");
  ASSERT_EQ(scene->grooms.size(), 1u);
  EXPECT_TRUE(scene->grooms[0].isProcedural());
  EXPECT_EQ(scene->grooms[0].attachedMesh, "head");
  // Every asset the scene names is in the manifest.
  const AssetResolver resolver = testing::sharedResolver();
  for (const std::string& name : {head->source, skin->albedoTexture, skin->normalMap, skin->specularMap}) {
    EXPECT_NE(resolver.find(name), nullptr) << name;
  }
}

TEST(Scene, NaluCameraFramesTheWholeHead) {
  auto scene = loadScene(kScenes / "nalu.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const MeshInstance& head = *scene->findMesh("head");
  auto loaded = loadSceneMesh(head, testing::sharedResolver());
  ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
  if (loaded->procedural) MANE_SKIP_FOR_MISSING_ASSET(loaded->note);
  const Camera& c = scene->camera;
  const glm::mat4 viewProjection =
      glm::perspective(glm::radians(c.verticalFovDegrees), float(scene->output.width) / float(scene->output.height),
                       c.nearPlane, c.farPlane) *
      glm::lookAt(c.position, c.target, c.up);
  const glm::mat4 model = head.transform.matrix();
  glm::vec2 lo(1e9f);
  glm::vec2 hi(-1e9f);
  for (const glm::vec3& p : loaded->mesh.positions) {
    const glm::vec4 clip = viewProjection * model * glm::vec4(p, 1.0f);
    ASSERT_GT(clip.w, c.nearPlane);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
  }
  // Entirely in frame, and large: at least half the frame's height (NDC spans 2).
  EXPECT_GE(lo.x, -1.0f);
  EXPECT_LE(hi.x, 1.0f);
  EXPECT_GE(lo.y, -1.0f);
  EXPECT_LE(hi.y, 1.0f);
  EXPECT_GT(hi.y - lo.y, 1.0f);
  // Real-head size after the scene's scale: 15..30 cm across (ears included).
  const Bounds box = loaded->mesh.bounds();
  EXPECT_GT(box.size().x * head.transform.scale, 0.15f);
  EXPECT_LT(box.size().x * head.transform.scale, 0.30f);
}

TEST(Scene, EveryShippedSceneLoads) {
  std::size_t count = 0;
  for (const auto& item : std::filesystem::directory_iterator(kScenes)) {
    if (item.path().extension() != ".json" || item.path().filename() == "assets.json") continue;
    ++count;
    auto scene = loadScene(item.path());
    EXPECT_TRUE(scene.has_value()) << scene.error().message;
  }
  EXPECT_GE(count, 2u);
}

TEST(Scene, BadJsonGivesFileAndPosition) {
  const std::string message = errorOf("{ \"name\": \"x\", \n \"camera\": { ] }");
  EXPECT_NE(message.find("dir/bad.json: invalid JSON"), std::string::npos) << message;
  EXPECT_NE(message.find("line 2"), std::string::npos) << message;
}

TEST(Scene, MissingRequiredFieldIsNamed) {
  EXPECT_EQ(errorOf(R"({"name": "x"})"), "dir/bad.json: camera: required field is missing");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1]}})"),
            "dir/bad.json: camera.target: required field is missing");
}

TEST(Scene, WrongTypeNamesTheFieldPathAndTheExpectation) {
  const std::string message = errorOf(R"({"name": "x",
    "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
    "lights": [{"kind": "directional", "direction": [0, -1, 0]},
               {"kind": "directional", "direction": "down"}]})");
  EXPECT_EQ(message, "dir/bad.json: lights[1].direction: expected an array of 3 numbers, got a string");
  EXPECT_EQ(errorOf(R"({"name": "x", "output": {"width": 12.5},
                        "camera": {"position": [0, 0, 1], "target": [0, 0, 0]}})"),
            "dir/bad.json: output.width: expected an integer, got a fraction");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0], "target": [0, 0, 0]}})"),
            "dir/bad.json: camera.position: expected an array of 3 numbers, got 2 elements");
}

TEST(Scene, UnknownFieldIsATypo) {
  const std::string message = errorOf(R"({"name": "x",
    "camera": {"position": [0, 0, 1], "target": [0, 0, 0], "fov": 30}})");
  EXPECT_NE(message.find("dir/bad.json: camera.fov: unknown field"), std::string::npos) << message;
  EXPECT_NE(message.find("fov_degrees"), std::string::npos) << message;  // lists the known ones
  EXPECT_NE(errorOf(R"({"name": "x", "camra": {}, "camera": {"position": [0,0,1], "target": [0,0,0]}})")
                .find("camra: unknown field"),
            std::string::npos);
}

TEST(Scene, ValuesOutOfRangeAreRejected) {
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0],
                        "fov_degrees": 190}})"),
            "dir/bad.json: camera.fov_degrees: expected a vertical field of view in (0, 180) "
            "degrees");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "lights": [{"kind": "directional", "direction": [0, 0, 0]}]})"),
            "dir/bad.json: lights[0].direction: expected a non-zero direction");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "lights": [{"kind": "spot", "direction": [0, -1, 0]}]})"),
            "dir/bad.json: lights[0].kind: expected \"directional\" (the only light kind so "
            "far), got \"spot\"");
  // A count that would exhaust memory in the groom generator is refused where it is written.
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "meshes": [{"name": "head", "source": "procedural:sphere"}],
                        "grooms": [{"name": "g", "source": "procedural", "attached_mesh": "head",
                                    "strands": 2000000000}]})"),
            "dir/bad.json: grooms[0].strands: expected a strand count in 0..1000000");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "simulation": {"settle_seconds": -1}})"),
            "dir/bad.json: simulation.settle_seconds: expected 0..10 seconds");
}

TEST(Scene, ReferencesMustResolve) {
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "meshes": [{"name": "m", "source": "procedural:sphere", "material": "skin"}]})"),
            "dir/bad.json: meshes[0].material: no material named \"skin\" in materials");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "grooms": [{"name": "h", "source": "procedural", "attached_mesh": "head"}]})"),
            "dir/bad.json: grooms[0].attached_mesh: no mesh named \"head\" in meshes");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "meshes": [{"name": "m", "source": "procedural:cube"}]})"),
            "dir/bad.json: meshes[0].source: unknown procedural mesh \"procedural:cube\" "
            "(known: procedural:sphere)");
}

TEST(Scene, InvertZIsForGroomFilesOnly) {
  auto scene = parseScene(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                              "meshes": [{"name": "head", "source": "procedural:sphere"}],
                              "grooms": [{"name": "a", "source": "hair/tressfx_ponytail/tail.tfx",
                                          "attached_mesh": "head", "invert_z": true},
                                         {"name": "b", "source": "hair/tressfx_ponytail/tail.tfx",
                                          "attached_mesh": "head"}]})",
                          "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_TRUE(scene->grooms[0].invertZ);
  EXPECT_FALSE(scene->grooms[1].invertZ);
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "meshes": [{"name": "head", "source": "procedural:sphere"}],
                        "grooms": [{"name": "g", "source": "procedural", "attached_mesh": "head",
                                    "invert_z": true}]})"),
            "dir/bad.json: grooms[0].invert_z: applies to groom files only, not to \"procedural\"");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "meshes": [{"name": "head", "source": "procedural:sphere"}],
                        "grooms": [{"name": "g", "source": "a.tfx", "attached_mesh": "head",
                                    "invert_z": 1}]})"),
            "dir/bad.json: grooms[0].invert_z: expected true or false, got a number");
}

// Found by tests/fuzz/fuzz_scene: nlohmann reports a number beyond double range as
// out_of_range, not parse_error, and that exception escaped parseScene.
TEST(Scene, NumberBeyondDoubleRangeIsInvalidJsonNotACrash) {
  const std::string message = errorOf(R"({"name": "x", "camera": {"position": [1e400, 0, 1],
                                          "target": [0, 0, 0]}})");
  EXPECT_NE(message.find("dir/bad.json: invalid JSON"), std::string::npos) << message;
  EXPECT_NE(message.find("1e400"), std::string::npos) << message;
}

TEST(Scene, NumberBeyondFloatRangeIsRejectedNotMadeInfinite) {
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 1e39, 1], "target": [0, 0, 0]}})"),
            "dir/bad.json: camera.position[1]: expected a finite number within float range "
            "(|x| < 3.4e38)");
}

TEST(Scene, NonExistentFile) {
  auto scene = loadScene("/nonexistent/mane/scene.json");
  ASSERT_FALSE(scene.has_value());
  EXPECT_NE(scene.error().message.find("/nonexistent/mane/scene.json: cannot open"), std::string::npos);
}

TEST(Transform, AppliesScaleThenRotationXyzThenTranslation) {
  Transform t;
  t.translation = {1, 2, 3};
  t.rotationDegrees = {0, 90, 0};  // +X turns to −Z about +Y (right-handed)
  t.scale = 2;
  const glm::vec3 p = glm::vec3(t.matrix() * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(glm::distance(p, glm::vec3(1, 2, 1)), 0.0f, 1e-5f);
  Transform xy;
  xy.rotationDegrees = {90, 90, 0};  // X first: +Y → +Z; then Y: +Z → +X
  const glm::vec3 q = glm::vec3(xy.matrix() * glm::vec4(0, 1, 0, 1));
  EXPECT_NEAR(glm::distance(q, glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
}

TEST(HeadMotion, TurnPeaksAQuarterPeriodIn) {
  HeadMotion turn{HeadMotionKind::turn, "head", 20.0f, 0.25f, {}};
  EXPECT_NEAR(turn.poseAt(1.0f).rotationDegrees.y, 20.0f, 1e-4f);  // sin(2π·0.25·1) = 1
  EXPECT_NEAR(turn.poseAt(2.0f).rotationDegrees.y, 0.0f, 1e-4f);
  EXPECT_EQ(turn.poseAt(1.0f).rotationDegrees.x, 0.0f);
}

TEST(HeadMotion, KeyframesInterpolateLinearlyAndHoldAtTheEnds) {
  auto scene = parseScene(R"({"name": "k",
    "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
    "meshes": [{"name": "head", "source": "procedural:sphere"}],
    "animation": {"head": {"mesh": "head", "motion": "keyframes", "keyframes": [
      {"time": 1, "rotation_degrees": [0, 0, 0]},
      {"time": 3, "rotation_degrees": [0, 40, 0], "translation": [0, 0.2, 0]}]}}})",
                          "k.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const HeadMotion& motion = scene->headMotion;
  EXPECT_NEAR(motion.poseAt(2.0f).rotationDegrees.y, 20.0f, 1e-5f);
  EXPECT_NEAR(motion.poseAt(2.0f).translation.y, 0.1f, 1e-6f);
  EXPECT_EQ(motion.poseAt(0.0f).rotationDegrees.y, 0.0f);
  EXPECT_EQ(motion.poseAt(9.0f).rotationDegrees.y, 40.0f);
  // The animated matrix of the head includes the pose; other meshes are unaffected.
  const glm::vec3 moved = glm::vec3(animatedMatrix(*scene, scene->meshes[0], 9.0f) * glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(moved.y, 0.2f, 1e-6f);
  EXPECT_NE(errorOf(R"({"name": "k", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
      "meshes": [{"name": "head", "source": "procedural:sphere"}],
      "animation": {"head": {"mesh": "head", "motion": "keyframes", "keyframes": [
        {"time": 2}, {"time": 1}]}}})")
                .find("animation.head.keyframes[1].time: expected times in strictly increasing"),
            std::string::npos);
}

}  // namespace
}  // namespace mane::scenes
