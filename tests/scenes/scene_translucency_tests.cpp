// Translucency in scene files: a material's `translucency` block (defaults, each method, errors
// that name the field path), and the two shipped scenes of the voxelized-translucency paper's test
// objects, which load their procedural meshes, voxelize them and light them from behind.

#include <gtest/gtest.h>

#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "render/luts/solid_voxels.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_meshes.hpp"
#include "scenes/world.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(MANE_SOURCE_DIR) / "scenes";

/// A scene with one material; `fields` completes its object after the name.
std::string sceneWithMaterial(const std::string& fields) {
  return R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
             "materials": [{"name": "jade")" +
         fields + "}]}";
}

/// The error message of the scene with that material ("" when it parses).
std::string errorOf(const std::string& materialFields) {
  auto scene = parseScene(sceneWithMaterial(materialFields), "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

/// The material's translucency once parsed; fails the test when it does not parse.
render::TranslucencyParameters translucencyOf(const std::string& materialFields) {
  auto scene = parseScene(sceneWithMaterial(materialFields), "x.json");
  EXPECT_TRUE(scene.has_value()) << scene.error().message;
  return scene ? scene->materials[0].translucency : render::TranslucencyParameters{};
}

TEST(SceneTranslucency, IsOffByDefaultWithTheRenderersExtinctionAndResolution) {
  const render::TranslucencyParameters renderDefaults;
  const render::TranslucencyParameters none = translucencyOf("");
  EXPECT_EQ(none.method, render::TranslucencyMethod::kNone);
  const render::TranslucencyParameters voxels = translucencyOf(R"(, "translucency": {"method": "voxel_lut"})");
  EXPECT_EQ(voxels.method, render::TranslucencyMethod::kVoxelLut);
  EXPECT_EQ(voxels.extinction, renderDefaults.extinction);
  EXPECT_EQ(voxels.voxelResolution, 32);
  EXPECT_EQ(renderDefaults.voxelResolution, 32);
}

TEST(SceneTranslucency, TakesEachMethodAndItsFields) {
  const render::TranslucencyParameters depth =
      translucencyOf(R"(, "translucency": {"method": "depth_map", "extinction": [10, 0, 2.5]})");
  EXPECT_EQ(depth.method, render::TranslucencyMethod::kDepthMap);
  EXPECT_EQ(depth.extinction, glm::vec3(10.0f, 0.0f, 2.5f));
  const render::TranslucencyParameters voxels = translucencyOf(
      R"(, "translucency": {"method": "voxel_lut", "extinction": [30, 16, 26], "voxel_resolution": 48})");
  EXPECT_EQ(voxels.method, render::TranslucencyMethod::kVoxelLut);
  EXPECT_EQ(voxels.extinction, glm::vec3(30.0f, 16.0f, 26.0f));
  EXPECT_EQ(voxels.voxelResolution, 48);
  EXPECT_EQ(translucencyOf(R"(, "translucency": {"method": "none"})").method, render::TranslucencyMethod::kNone);
  // Skin takes a method and a resolution: it transmits its diffusion profile, not exp(−σd).
  const render::TranslucencyParameters skin =
      translucencyOf(R"(, "kind": "skin", "translucency": {"method": "voxel_lut", "voxel_resolution": 4})");
  EXPECT_EQ(skin.voxelResolution, render::SolidVoxels::kMinResolution);
}

TEST(SceneTranslucency, ErrorsNameTheFieldPath) {
  const std::string at = "dir/bad.json: materials[0].translucency";
  EXPECT_EQ(errorOf(R"(, "translucency": "voxel_lut")"), at + ": expected an object, got a string");
  EXPECT_EQ(errorOf(R"(, "translucency": {})"), at + ".method: required field is missing");
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "ray_march"})"),
            at + ".method: expected \"none\", \"depth_map\" or \"voxel_lut\", got \"ray_march\"");
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "depth_map", "extinction": [1, -2, 3]})"),
            at + ".extinction[1]: expected an extinction >= 0 per metre");
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "depth_map", "extinction": [1, 2]})"),
            at + ".extinction: expected an array of 3 numbers, got 2 elements");
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "depth_map", "extinction": [1, 2, 1e39]})"),
            at + ".extinction[2]: expected a finite number within float range (|x| < 3.4e38)");
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "none", "extinction": [1, 2, 3]})"),
            at + ".extinction: applies to methods \"depth_map\" and \"voxel_lut\" only");
  EXPECT_EQ(errorOf(R"(, "kind": "skin", "translucency": {"method": "depth_map", "extinction": [1, 2, 3]})"),
            at + ".extinction: applies to materials other than \"skin\" (skin transmits its diffusion profile)");
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "depth_map", "voxel_resolution": 32})"),
            at + ".voxel_resolution: applies to method \"voxel_lut\" only");
  for (const char* resolution : {"3", "129", "-1"}) {
    EXPECT_EQ(
        errorOf(R"(, "translucency": {"method": "voxel_lut", "voxel_resolution": )" + std::string(resolution) + "}"),
        at + ".voxel_resolution: expected a resolution in 4..128 cells per axis")
        << resolution;
  }
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "voxel_lut", "voxel_resolution": 32.5})"),
            at + ".voxel_resolution: expected an integer, got a fraction");
  EXPECT_EQ(errorOf(R"(, "translucency": {"method": "voxel_lut", "sigma": [1, 1, 1]})"),
            at + ".sigma: unknown field (expected one of: extinction, method, voxel_resolution)");
}

/// The first mesh of a shipped scene, its geometry and its material.
struct ShippedObject {
  Scene scene;
  LoadedMesh mesh;
};

ShippedObject loadShipped(const std::string& file) {
  auto scene = loadScene(kScenes / file);
  EXPECT_TRUE(scene.has_value()) << scene.error().message;
  if (!scene || scene->meshes.empty()) return {};
  auto mesh = loadSceneMesh(scene->meshes[0], testing::sharedResolver(), kScenes);
  EXPECT_TRUE(mesh.has_value()) << mesh.error().message;
  return {std::move(*scene), mesh ? std::move(*mesh) : LoadedMesh{}};
}

/// The object fills between `minHeight` and all of the frame (NDC spans 2), in front of the camera.
void expectFramed(const Scene& scene, const Mesh& mesh, float minHeight) {
  const Camera& c = scene.camera;
  const glm::mat4 viewProjection =
      glm::perspective(glm::radians(c.verticalFovDegrees), float(scene.output.width) / float(scene.output.height),
                       c.nearPlane, c.farPlane) *
      glm::lookAt(c.position, c.target, c.up);
  const glm::mat4 model = scene.meshes[0].transform.matrix();
  glm::vec2 lo(1e9f);
  glm::vec2 hi(-1e9f);
  for (const glm::vec3& p : mesh.positions) {
    const glm::vec4 clip = viewProjection * model * glm::vec4(p, 1.0f);
    ASSERT_GT(clip.w, c.nearPlane);
    lo = glm::min(lo, glm::vec2(clip) / clip.w);
    hi = glm::max(hi, glm::vec2(clip) / clip.w);
  }
  EXPECT_GE(lo.x, -1.0f);
  EXPECT_LE(hi.x, 1.0f);
  EXPECT_GE(lo.y, -1.0f);
  EXPECT_LE(hi.y, 1.0f);
  EXPECT_GT(hi.y - lo.y, minHeight);
}

/// What both test scenes promise: a built-in closed mesh that voxelizes at the material's
/// resolution, 10 cm across, in frame, and a first light that shines through it toward the camera.
void expectBacklitTranslucentObject(const std::string& file, const std::string& source) {
  SCOPED_TRACE(file);
  const ShippedObject object = loadShipped(file);
  ASSERT_EQ(object.scene.meshes.size(), 1u);
  EXPECT_EQ(object.scene.meshes[0].source, source);
  EXPECT_EQ(object.scene.output.width, 640);
  EXPECT_EQ(object.scene.output.height, 480);
  EXPECT_FLOAT_EQ(object.scene.meshes[0].transform.scale, 0.1f);
  EXPECT_TRUE(object.mesh.procedural);
  EXPECT_EQ(object.mesh.note, "");
  const Material* material = object.scene.findMaterial(object.scene.meshes[0].material);
  ASSERT_NE(material, nullptr);
  const render::TranslucencyParameters& translucency = material->translucency;
  EXPECT_EQ(translucency.method, render::TranslucencyMethod::kVoxelLut);
  auto voxels =
      render::voxelizeSolid(object.mesh.mesh.positions, object.mesh.mesh.indices, translucency.voxelResolution);
  EXPECT_TRUE(voxels.has_value()) << voxels.error().message;
  // Light through 2 to 6 cm of it keeps between e^−3 and e^−0.3 in every channel: visibly graded.
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(translucency.extinction[c] * 0.06f, 0.3f);
    EXPECT_LT(translucency.extinction[c] * 0.02f, 3.0f);
  }
  expectFramed(object.scene, object.mesh.mesh, 0.8f);
  // The first light (the one translucency uses) travels from behind the object toward the
  // camera; the second is a weaker fill.
  ASSERT_EQ(object.scene.lights.size(), 2u);
  const glm::vec3 towardCamera = glm::normalize(object.scene.camera.position - object.scene.camera.target);
  EXPECT_GT(glm::dot(object.scene.lights[0].direction, towardCamera), 0.7f);
  EXPECT_LT(object.scene.lights[1].intensity, 0.25f * object.scene.lights[0].intensity);
}

TEST(SceneTranslucency, TranslucentCubeSceneBacklightsTheCubeWithAHollow) {
  expectBacklitTranslucentObject("translucent_cube.json", "procedural:cube_with_hollow");
}

TEST(SceneTranslucency, TorusSceneBacklightsTheTorus) {
  expectBacklitTranslucentObject("torus.json", "procedural:torus");
}

TEST(SceneTranslucency, WorldHandsEachMaterialsTranslucencyToTheRenderer) {
  auto scene = loadScene(kScenes / "translucent_cube.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const render::TranslucencyParameters expected = scene->materials[0].translucency;
  auto world = World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::StaticScene frame = world->staticScene();
  ASSERT_EQ(frame.materials.size(), 2u);  // jade, then the default material
  EXPECT_EQ(frame.materials[0].translucency.method, expected.method);
  EXPECT_EQ(frame.materials[0].translucency.extinction, expected.extinction);
  EXPECT_EQ(frame.materials[0].translucency.voxelResolution, expected.voxelResolution);
  EXPECT_EQ(frame.materials[1].translucency.method, render::TranslucencyMethod::kNone);
}

}  // namespace
}  // namespace mane::scenes
