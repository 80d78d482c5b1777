// Scene files: the shipped scenes load and make sense; bad files fail with the file name,
// the JSON field path and what was expected.

#include <gtest/gtest.h>

#include <numbers>

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
  EXPECT_FALSE(skin->doubleSided) << "the head is closed where the camera sees it: its back faces are culled";
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
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "materials": [{"name": "m", "double_sided": "no"}]})"),
            "dir/bad.json: materials[0].double_sided: expected true or false, got a string");
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

TEST(Scene, SkinMaterialsTakeTheirParametersAndNameBadOnes) {
  const std::string prefix = R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                                 "materials": [{"name": "face", )";
  auto scene = parseScene(
      prefix + R"("kind": "skin", "skin": {"range": "penner", "roughness": 0.4, "specular_intensity": 0.3}}]})",
      "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const Material& material = scene->materials[0];
  EXPECT_EQ(material.kind, MaterialKind::skin);
  EXPECT_EQ(material.skin.range, render::SkinIntegrationRange::kPenner);
  EXPECT_FLOAT_EQ(material.skin.roughness, 0.4f);
  EXPECT_FLOAT_EQ(material.skin.specularIntensity, 0.3f);
  auto defaults = parseScene(prefix + R"("kind": "skin"}]})", "x.json");
  ASSERT_TRUE(defaults.has_value());
  EXPECT_EQ(defaults->materials[0].skin.range, render::SkinIntegrationRange::kCurvature);
  EXPECT_EQ(defaults->materials[0].skin.diffusion, render::SkinDiffusion::kPreintegrated);
  auto textureSpace = parseScene(
      prefix + R"("kind": "skin", "skin": {"diffusion": "texture_space", "irradiance_size": 2048}}]})", "x.json");
  ASSERT_TRUE(textureSpace.has_value()) << textureSpace.error().message;
  EXPECT_EQ(textureSpace->materials[0].skin.diffusion, render::SkinDiffusion::kTextureSpace);
  EXPECT_EQ(textureSpace->materials[0].skin.irradianceSize, 2048u);
  EXPECT_EQ(errorOf(prefix + R"("kind": "skin", "skin": {"diffusion": "screen"}}]})"),
            "dir/bad.json: materials[0].skin.diffusion: expected \"preintegrated\" or \"texture_space\", got "
            "\"screen\"");
  EXPECT_EQ(errorOf(prefix + R"("kind": "skin", "skin": {"irradiance_size": 1001}}]})"),
            "dir/bad.json: materials[0].skin.irradiance_size: expected a multiple of 8 texels in 64..4096");

  EXPECT_EQ(errorOf(prefix + R"("kind": "marble"}]})"),
            "dir/bad.json: materials[0].kind: expected \"lambert\", \"skin\" or \"fur\", got \"marble\"");
  EXPECT_EQ(errorOf(prefix + R"("skin": {}}]})"),
            "dir/bad.json: materials[0].skin: applies to materials of kind \"skin\" only");
  EXPECT_EQ(errorOf(prefix + R"("kind": "skin", "skin": {"range": "wide"}}]})"),
            "dir/bad.json: materials[0].skin.range: expected \"curvature\" or \"penner\", got \"wide\"");
  EXPECT_EQ(errorOf(prefix + R"("kind": "skin", "skin": {"roughness": 0}}]})"),
            "dir/bad.json: materials[0].skin.roughness: expected a Beckmann roughness in (0, 1]");
  EXPECT_EQ(errorOf(prefix + R"("kind": "skin", "skin": {"specular_intensity": -1}}]})"),
            "dir/bad.json: materials[0].skin.specular_intensity: expected a specular intensity in [0, 10]");
}

TEST(Scene, ReferencesMustResolve) {
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "meshes": [{"name": "m", "source": "procedural:sphere", "material": "skin"}]})"),
            "dir/bad.json: meshes[0].material: no material named \"skin\" in materials");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "grooms": [{"name": "h", "source": "procedural", "attached_mesh": "head"}]})"),
            "dir/bad.json: grooms[0].attached_mesh: no mesh named \"head\" in meshes, nor a character part \"<character>/<mesh>\" of characters");
  EXPECT_EQ(errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                        "meshes": [{"name": "m", "source": "procedural:cube"}]})"),
            "dir/bad.json: meshes[0].source: unknown procedural mesh \"procedural:cube\" "
            "(known: procedural:sphere, procedural:cube_with_hollow, procedural:torus, procedural:plane, "
            "procedural:hull, procedural:spar)");
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

/// A scene with one groom on a sphere whose groom object ends with `groomFields` (", ..." or
/// ""), and `rootFields` (", ..." or "") at the top level.
std::string groomScene(const std::string& groomFields, const std::string& rootFields = "") {
  return R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
             "meshes": [{"name": "head", "source": "procedural:sphere"}],
             "grooms": [{"name": "g", "attached_mesh": "head")" +
         groomFields + "}]" + rootFields + "}";
}

TEST(Scene, GroomRenderDefaultsAreBlondeRibbons04MmWideAndOpacityShadowsAt512) {
  auto scene = parseScene(groomScene(R"(, "source": "procedural")"), "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  // What World drew before the render block existed: blonde, 0.4 mm, the rest as
  // render::HairGroomSettings' defaults, 4,095 strands (denseStrands 0).
  const GroomRendering& rendering = scene->grooms[0].rendering;
  EXPECT_EQ(rendering.look, render::HairLook::kBlonde);
  EXPECT_FLOAT_EQ(rendering.settings.width, 4e-4f);
  const render::HairGroomSettings defaults;
  EXPECT_EQ(rendering.settings.tipWidthScale, defaults.tipWidthScale);
  EXPECT_EQ(rendering.settings.opacity, defaults.opacity);
  EXPECT_EQ(rendering.settings.minimumPixelWidth, defaults.minimumPixelWidth);
  EXPECT_EQ(rendering.settings.shadowExtinction, defaults.shadowExtinction);
  EXPECT_EQ(rendering.denseStrands, 0);
  EXPECT_EQ(rendering.verticesPerStrand, 0);
  EXPECT_EQ(rendering.guideBlend, physics::GuideBlend::kSingle);
  EXPECT_EQ(rendering.curve, StrandCurve::kCatmullRom);
  EXPECT_FLOAT_EQ(rendering.clump, 0.3f);
  EXPECT_EQ(rendering.curlRadius, 0.0f) << "straight unless the scene curls it";
  EXPECT_EQ(rendering.frizz, 0.0f);
  // Nothing given: a groom file's own widths, opacities and colours may fill them in.
  EXPECT_FALSE(rendering.colour.has_value());
  EXPECT_FALSE(rendering.given.width || rendering.given.tipWidthScale || rendering.given.opacity);
  EXPECT_EQ(scene->hairShadows.mode, render::HairShadowMode::kOpacityShadowMap);
  EXPECT_EQ(scene->hairShadows.resolution, 512u);
}

TEST(Scene, GroomRenderBlockSetsEveryField) {
  auto scene = parseScene(groomScene(R"(, "source": "procedural",
      "render": {"look": "dark", "width": 1e-4, "tip_width_scale": 0.25, "opacity": 0.5,
                 "colour": [0.5, 0.25, 0], "min_pixel_width": 0.25, "shadow_extinction": 3.5, "lod_pixel_width": 2,
                 "strands": 1000000, "vertices_per_strand": 4096, "guide_blend": "barycentric",
                 "curve": "linear", "clump": 1, "curl": {"radius": 0.003, "period": 0.01, "variation": 0.5},
                 "frizz": 0.0002})"),
                          "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const GroomRendering& rendering = scene->grooms[0].rendering;
  EXPECT_EQ(rendering.look, render::HairLook::kDark);
  EXPECT_FLOAT_EQ(rendering.settings.width, 1e-4f);
  EXPECT_FLOAT_EQ(rendering.settings.tipWidthScale, 0.25f);
  EXPECT_FLOAT_EQ(rendering.settings.opacity, 0.5f);
  EXPECT_FLOAT_EQ(rendering.settings.minimumPixelWidth, 0.25f);
  EXPECT_FLOAT_EQ(rendering.settings.shadowExtinction, 3.5f);
  EXPECT_FLOAT_EQ(rendering.settings.lodPixelWidth, 2.0f);
  EXPECT_EQ(rendering.denseStrands, 1'000'000);
  EXPECT_EQ(rendering.verticesPerStrand, 4096);
  EXPECT_EQ(rendering.guideBlend, physics::GuideBlend::kBarycentric);
  EXPECT_EQ(rendering.curve, StrandCurve::kLinear);
  EXPECT_FLOAT_EQ(rendering.clump, 1.0f);
  EXPECT_FLOAT_EQ(rendering.curlRadius, 0.003f);
  EXPECT_FLOAT_EQ(rendering.curlPeriod, 0.01f);
  EXPECT_FLOAT_EQ(rendering.curlVariation, 0.5f);
  EXPECT_FLOAT_EQ(rendering.frizz, 0.0002f);
  EXPECT_EQ(rendering.colour, glm::vec3(0.5f, 0.25f, 0.0f));
  EXPECT_TRUE(rendering.given.width && rendering.given.tipWidthScale && rendering.given.opacity);
  // The closed ends of the ranges are accepted.
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural",
      "render": {"look": "blonde", "width": 0.01, "tip_width_scale": 0, "opacity": 0.001, "strands": 1})")),
            "");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural", "render": {"tip_width_scale": 1, "opacity": 1})")), "");
}

TEST(Scene, ProceduralGroomsTakeAScalpRegion) {
  auto scene = parseScene(groomScene(R"(, "source": "procedural",
                    "scalp": {"top_fraction": 0.3, "min_up": 0.1, "max_forward": 0.35, "hairline_density": 6})"),
                          "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_FLOAT_EQ(scene->grooms[0].scalp.topFraction, 0.3f);
  EXPECT_FLOAT_EQ(scene->grooms[0].scalp.minUp, 0.1f);
  EXPECT_FLOAT_EQ(scene->grooms[0].scalp.maxForward, 0.35f);
  EXPECT_FLOAT_EQ(scene->grooms[0].scalp.hairlineDensity, 6.0f);
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural", "scalp": {"hairline_density": 0.5})")),
            "dir/bad.json: grooms[0].scalp.hairline_density: expected a density in [1, 16] times the scalp's");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural", "scalp": {"top_fraction": 0})")),
            "dir/bad.json: grooms[0].scalp.top_fraction: expected a fraction of the mesh's height in (0, 1]");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural", "scalp": {"max_forward": 2})")),
            "dir/bad.json: grooms[0].scalp.max_forward: expected a normal component in [-1, 1]");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "a.tfx", "scalp": {})")),
            "dir/bad.json: grooms[0].scalp: applies to \"procedural\" grooms only");
}

TEST(Scene, ProceduralGroomsMayBeCombed) {
  auto scene = parseScene(groomScene(R"(, "source": "procedural")"), "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->grooms[0].comb, glm::vec3(0.0f));
  scene = parseScene(groomScene(R"(, "source": "procedural", "comb": [0, 0.2, -1.5])"), "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->grooms[0].comb, glm::vec3(0.0f, 0.2f, -1.5f));
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "a.tfx", "comb": [0, 0, -1])")),
            "dir/bad.json: grooms[0].comb: applies to \"procedural\" grooms only");
  EXPECT_NE(errorOf(groomScene(R"(, "source": "procedural", "comb": [0, -1])")).find("grooms[0].comb"),
            std::string::npos);
}

TEST(Scene, ProceduralGroomsMayHaveAPartingAndBeLaidOverTheirBody) {
  auto scene = parseScene(groomScene(R"(, "source": "procedural")"), "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->grooms[0].parting.comb, 0.0f);
  EXPECT_FALSE(scene->grooms[0].drape.has_value());
  scene = parseScene(groomScene(R"(, "source": "procedural", "parting": {"comb": 2, "x": 0.01, "back_z": -0.02},
                                "drape": {"droop": 80, "layer": 0.002, "combed_length": 0.03})"),
                     "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->grooms[0].parting.comb, 2.0f);
  EXPECT_EQ(scene->grooms[0].parting.x, 0.01f);
  EXPECT_EQ(scene->grooms[0].parting.backZ, -0.02f);
  ASSERT_TRUE(scene->grooms[0].drape.has_value());
  EXPECT_EQ(scene->grooms[0].drape->droop, 80.0f);
  EXPECT_EQ(scene->grooms[0].drape->layer, 0.002f);
  EXPECT_EQ(scene->grooms[0].drape->combedLength, 0.03f);
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "a.tfx", "parting": {"comb": 1})")),
            "dir/bad.json: grooms[0].parting: applies to \"procedural\" grooms only");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "a.tfx", "drape": {})")),
            "dir/bad.json: grooms[0].drape: applies to \"procedural\" grooms only");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural", "parting": {"comb": -1})")),
            "dir/bad.json: grooms[0].parting.comb: expected a comb in [0, 10]");
  EXPECT_NE(errorOf(groomScene(R"(, "source": "procedural", "parting": {"x": 0})")).find("grooms[0].parting"),
            std::string::npos);
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural", "drape": {"droop": 1001})")),
            "dir/bad.json: grooms[0].drape.droop: expected a droop in [0, 1000] per metre");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "procedural", "drape": {"layer": -0.1})")),
            "dir/bad.json: grooms[0].drape.layer: expected a layer in [0, 0.1] metres");
}

TEST(Scene, GroomShapeStiffnessReachesTheSolverSettingsRange) {
  auto scene = parseScene(groomScene(R"(, "source": "procedural", "simulation": {"shape_stiffness": 0.5})"), "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_FLOAT_EQ(scene->grooms[0].simulation.shapeStiffness, 0.5f);
  for (const char* stiffness : {"-0.1", "1.5"})
    EXPECT_EQ(errorOf(groomScene(std::string(R"(, "source": "procedural", "simulation": {"shape_stiffness": )") +
                                 stiffness + "}")),
              "dir/bad.json: grooms[0].simulation.shape_stiffness: expected a shape stiffness in [0, 1]")
        << stiffness;
}

TEST(Scene, GroomRenderErrorsNameTheFieldAndTheRange) {
  const auto renderError = [](const std::string& block) {
    return errorOf(groomScene(R"(, "source": "procedural", "render": )" + block));
  };
  EXPECT_EQ(renderError(R"({"look": "red"})"),
            "dir/bad.json: grooms[0].render.look: expected \"blonde\" or \"dark\", got \"red\"");
  EXPECT_EQ(renderError(R"({"look": 1})"), "dir/bad.json: grooms[0].render.look: expected a string, got a number");
  for (const char* width : {"0", "-1e-4", "0.0101"})
    EXPECT_EQ(renderError(std::string(R"({"width": )") + width + "}"),
              "dir/bad.json: grooms[0].render.width: expected a root width in (0, 0.01] metres")
        << width;
  for (const char* scale : {"-0.01", "1.01"})
    EXPECT_EQ(renderError(std::string(R"({"tip_width_scale": )") + scale + "}"),
              "dir/bad.json: grooms[0].render.tip_width_scale: expected a tip width scale in [0, 1]")
        << scale;
  for (const char* opacity : {"0", "1.5"})
    EXPECT_EQ(renderError(std::string(R"({"opacity": )") + opacity + "}"),
              "dir/bad.json: grooms[0].render.opacity: expected an opacity in (0, 1]")
        << opacity;
  for (const char* colour : {"[1.5, 0, 0]", "[0, -0.1, 0]"})
    EXPECT_EQ(renderError(std::string(R"({"colour": )") + colour + "}"),
              "dir/bad.json: grooms[0].render.colour: expected an RGB colour with components in [0, 1]")
        << colour;
  EXPECT_EQ(renderError(R"({"min_pixel_width": 0.2})"),
            "dir/bad.json: grooms[0].render.min_pixel_width: expected a minimum width >= 0.25 pixels");
  EXPECT_EQ(renderError(R"({"lod_pixel_width": -0.5})"),
            "dir/bad.json: grooms[0].render.lod_pixel_width: expected a level-of-detail width >= 0 pixels (0: every "
            "strand drawn)");
  for (const char* kappa : {"0", "-1"})
    EXPECT_EQ(renderError(std::string(R"({"shadow_extinction": )") + kappa + "}"),
              "dir/bad.json: grooms[0].render.shadow_extinction: expected a shadow extinction > 0")
        << kappa;
  EXPECT_EQ(renderError(R"({"shadow_extinction": 1e39})"),
            "dir/bad.json: grooms[0].render.shadow_extinction: expected a finite number within float range "
            "(|x| < 3.4e38)");
  for (const char* strands : {"0", "-5", "1000001"})
    EXPECT_EQ(renderError(std::string(R"({"strands": )") + strands + "}"),
              "dir/bad.json: grooms[0].render.strands: expected a dense strand count in 1..1000000")
        << strands;
  for (const char* vertices : {"0", "1", "4097"})
    EXPECT_EQ(renderError(std::string(R"({"vertices_per_strand": )") + vertices + "}"),
              "dir/bad.json: grooms[0].render.vertices_per_strand: expected 2..4096 vertices per strand")
        << vertices;
  EXPECT_EQ(renderError(R"({"guide_blend": "triangle"})"),
            "dir/bad.json: grooms[0].render.guide_blend: expected \"single\" or \"barycentric\", got \"triangle\"");
  EXPECT_EQ(renderError(R"({"curve": "bezier"})"),
            "dir/bad.json: grooms[0].render.curve: expected \"catmull_rom\" or \"linear\", got \"bezier\"");
  for (const char* clump : {"-0.1", "1.5"})
    EXPECT_EQ(renderError(std::string(R"({"clump": )") + clump + "}"),
              "dir/bad.json: grooms[0].render.clump: expected a clump in [0, 1]")
        << clump;
  for (const char* profile : {"-1", "9", "\"deep\""})
    EXPECT_THAT(renderError(std::string(R"({"clump_profile": )") + profile + "}"),
                ::testing::HasSubstr("dir/bad.json: grooms[0].render.clump_profile: expected"))
        << profile;
  EXPECT_EQ(renderError(R"({"curl": {"radius": 0.1}})"),
            "dir/bad.json: grooms[0].render.curl.radius: expected a radius in [0, 0.05] metres");
  EXPECT_EQ(renderError(R"({"curl": {"radius": 0.001, "period": 0}})"),
            "dir/bad.json: grooms[0].render.curl.period: expected a length in [0.001, 10] metres per turn");
  EXPECT_EQ(renderError(R"({"curl": {"radius": 0.001, "variation": 2}})"),
            "dir/bad.json: grooms[0].render.curl.variation: expected a share in [0, 1]");
  EXPECT_NE(renderError(R"({"curl": {"period": 0.01}})").find("grooms[0].render.curl.radius"), std::string::npos);
  EXPECT_EQ(renderError(R"({"frizz": -1})"),
            "dir/bad.json: grooms[0].render.frizz: expected a frizz in [0, 0.01] metres");
  EXPECT_EQ(renderError(R"({"strands": 2.5})"),
            "dir/bad.json: grooms[0].render.strands: expected an integer, got a fraction");
  const std::string typo = renderError(R"({"color": [1, 0, 0]})");
  EXPECT_NE(typo.find("dir/bad.json: grooms[0].render.color: unknown field"), std::string::npos) << typo;
  EXPECT_NE(typo.find("min_pixel_width"), std::string::npos) << typo;  // lists the known ones
  EXPECT_EQ(renderError("\"dark\""), "dir/bad.json: grooms[0].render: expected an object, got a string");
}

TEST(Scene, GroomSourceMayListSeveralFilesInOrder) {
  auto scene = parseScene(groomScene(R"(, "source": ["a.tfx", "dir/b.hair", "a.tfx"])"), "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->grooms[0].sources, (std::vector<std::string>{"a.tfx", "dir/b.hair", "a.tfx"}));
  EXPECT_FALSE(scene->grooms[0].isProcedural());
  auto single = parseScene(groomScene(R"(, "source": "a.tfx")"), "x.json");
  ASSERT_TRUE(single.has_value()) << single.error().message;
  EXPECT_EQ(single->grooms[0].sources, std::vector<std::string>{"a.tfx"});
  EXPECT_FALSE(single->grooms[0].isProcedural());
  auto procedural = parseScene(groomScene(R"(, "source": "procedural")"), "x.json");
  ASSERT_TRUE(procedural.has_value()) << procedural.error().message;
  EXPECT_TRUE(procedural->grooms[0].isProcedural());
}

TEST(Scene, GroomSourceErrorsNameTheElement) {
  EXPECT_EQ(errorOf(groomScene("")), "dir/bad.json: grooms[0].source: required field is missing");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": "")")),
            "dir/bad.json: grooms[0].source: expected a .tfx/.hair asset name or \"procedural\"");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": 3)")),
            "dir/bad.json: grooms[0].source: expected a .tfx/.hair asset name, an array of them or "
            "\"procedural\", got a number");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": [])")),
            "dir/bad.json: grooms[0].source: expected at least one .tfx/.hair asset name");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": ["a.tfx", 7])")),
            "dir/bad.json: grooms[0].source[1]: expected a string, got a number");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": ["a.tfx", ""])")),
            "dir/bad.json: grooms[0].source[1]: expected a .tfx/.hair asset name");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": ["procedural"])")),
            "dir/bad.json: grooms[0].source[0]: \"procedural\" cannot be combined with groom files (write "
            "\"source\": \"procedural\")");
  EXPECT_EQ(errorOf(groomScene(R"(, "source": ["a.tfx", "procedural"])")),
            "dir/bad.json: grooms[0].source[1]: \"procedural\" cannot be combined with groom files (write "
            "\"source\": \"procedural\")");
  // invert_z applies to file lists as to single files.
  EXPECT_EQ(errorOf(groomScene(R"(, "source": ["a.tfx", "b.tfx"], "invert_z": true)")), "");
}

TEST(Scene, HairShadowsPickTheModeAndResolution) {
  const std::pair<const char*, render::HairShadowMode> modes[] = {
      {"opacity", render::HairShadowMode::kOpacityShadowMap},
      {"deep", render::HairShadowMode::kDeepOpacityMap},
      {"off", render::HairShadowMode::kOff}};
  for (const auto& [name, mode] : modes) {
    auto scene = parseScene(std::string(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                                            "hair_shadows": {"mode": ")") +
                                name + R"(", "resolution": 4096}})",
                            "x.json");
    ASSERT_TRUE(scene.has_value()) << scene.error().message;
    EXPECT_EQ(scene->hairShadows.mode, mode) << name;
    EXPECT_EQ(scene->hairShadows.resolution, 4096u) << name;
  }
  auto low = parseScene(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                            "hair_shadows": {"resolution": 16}})",
                        "x.json");
  ASSERT_TRUE(low.has_value()) << low.error().message;
  EXPECT_EQ(low->hairShadows.mode, render::HairShadowMode::kOpacityShadowMap);  // the default mode
  EXPECT_EQ(low->hairShadows.resolution, 16u);
  auto deep = parseScene(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                             "hair_shadows": {"mode": "deep"}})",
                         "x.json");
  ASSERT_TRUE(deep.has_value()) << deep.error().message;
  EXPECT_EQ(deep->hairShadows.resolution, 512u);  // the default resolution
}

TEST(Scene, HairShadowErrorsNameTheField) {
  const auto shadowError = [](const std::string& block) {
    return errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]}, "hair_shadows": )" + block +
                   "}");
  };
  EXPECT_EQ(shadowError(R"({"mode": "soft"})"),
            "dir/bad.json: hair_shadows.mode: expected \"opacity\", \"deep\" or \"off\", got \"soft\"");
  for (const char* resolution : {"15", "4097", "0"})
    EXPECT_EQ(shadowError(std::string(R"({"resolution": )") + resolution + "}"),
              "dir/bad.json: hair_shadows.resolution: expected a resolution in 16..4096 texels")
        << resolution;
  EXPECT_EQ(shadowError(R"({"resolution": 512.5})"),
            "dir/bad.json: hair_shadows.resolution: expected an integer, got a fraction");
  const std::string typo = shadowError(R"({"kind": "deep"})");
  EXPECT_NE(typo.find("dir/bad.json: hair_shadows.kind: unknown field"), std::string::npos) << typo;
  EXPECT_EQ(shadowError("true"), "dir/bad.json: hair_shadows: expected an object, got a boolean");
}

TEST(Scene, PostBlockSetsTheFramesToneMappingGainAndGlow) {
  auto plain = parseScene(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]}})", "x.json");
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  EXPECT_EQ(plain->post.toneMapping, render::ToneMapping::kLinear);  // the default unless asked
  EXPECT_FALSE(plain->post.autoGain);
  EXPECT_EQ(plain->post.glowStrength, 0.0f);
  auto post = parseScene(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                             "post": {"tone_mapping": "reinhard", "auto_gain": true, "key": 0.36, "glow": 0.5,
                                      "adaptation_seconds": 2, "god_rays": 1.5}})",
                         "x.json");
  ASSERT_TRUE(post.has_value()) << post.error().message;
  EXPECT_EQ(post->post.toneMapping, render::ToneMapping::kReinhard);
  EXPECT_TRUE(post->post.autoGain);
  EXPECT_EQ(post->post.key, 0.36f);
  EXPECT_EQ(post->post.glowStrength, 0.5f);
  EXPECT_EQ(post->post.adaptationSeconds, 2.0f);
  EXPECT_EQ(post->post.godRays, 1.5f);

  const auto postError = [](const std::string& block) {
    return errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]}, "post": )" + block + "}");
  };
  EXPECT_EQ(postError(R"({"tone_mapping": "aces"})"),
            "dir/bad.json: post.tone_mapping: expected \"linear\" or \"reinhard\", got \"aces\"");
  EXPECT_EQ(postError(R"({"key": 0})"), "dir/bad.json: post.key: expected a key value in (0, 1]");
  EXPECT_EQ(postError(R"({"glow": 1.5})"), "dir/bad.json: post.glow: expected a glow strength in [0, 1]");
  EXPECT_EQ(postError(R"({"adaptation_seconds": -1})"),
            "dir/bad.json: post.adaptation_seconds: expected an adaptation time in [0, 60] seconds");
  EXPECT_EQ(postError(R"({"god_rays": -0.5})"), "dir/bad.json: post.god_rays: expected a god-ray strength in [0, 10]");
  EXPECT_EQ(postError(R"({"auto_gain": 1})"), "dir/bad.json: post.auto_gain: expected true or false, got a number");
  EXPECT_EQ(postError(R"({"god_ray_light": -1})"), "dir/bad.json: post.god_ray_light: expected a light's index, 0 or more");
  EXPECT_EQ(postError(R"({"god_ray_light": 1})"), "dir/bad.json: post.god_ray_light: no light 1 in lights (it has 0)");
}

// A light's visible disc (a sun for the god rays to stream from): its angular radius and radiance,
// in degrees and as a multiple of the colour, reach the frame in radians.
TEST(Scene, ALightsDiscReachesTheFrameInRadians) {
  auto scene = parseScene(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                              "lights": [{"kind": "directional", "direction": [0, 0, 1]},
                                         {"kind": "directional", "direction": [0, 0, 1], "disc_radius_degrees": 2,
                                          "disc_radiance": 50}],
                              "post": {"god_rays": 1, "god_ray_light": 1}})",
                          "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->lights[0].discRadiusDegrees, 0.0f) << "no disc unless asked";
  EXPECT_EQ(scene->lights[1].discRadiusDegrees, 2.0f);
  EXPECT_EQ(scene->lights[1].discRadiance, 50.0f);
  EXPECT_EQ(scene->post.godRayLight, 1u);
  const auto lightError = [](const std::string& fields) {
    return errorOf(R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
                      "lights": [{"kind": "directional", "direction": [0, 0, 1], )" + fields + "}]}");
  };
  EXPECT_EQ(lightError(R"("disc_radius_degrees": 30)"),
            "dir/bad.json: lights[0].disc_radius_degrees: expected an angular radius in [0, 20] degrees");
  EXPECT_EQ(lightError(R"("disc_radiance": -1)"),
            "dir/bad.json: lights[0].disc_radiance: expected a radiance in [0, 1000] (a multiple of the colour)");
}

// An environment: a panorama file or the procedural sky, never both, with its range checks.
TEST(Scene, AnEnvironmentIsAPanoramaOrTheSky) {
  const std::string head = R"({"name": "x", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]}, )";
  auto none = parseScene(head + R"("lights": []})", "x.json");
  ASSERT_TRUE(none.has_value()) << none.error().message;
  EXPECT_FALSE(none->environment.has_value());
  auto panorama =
      parseScene(head + R"("environment": {"file": "env/venice_sunset_1k.hdr", "rotation_degrees": 90, "intensity": 2,
                                 "cube_size": 128}})",
                 "x.json");
  ASSERT_TRUE(panorama.has_value()) << panorama.error().message;
  EXPECT_EQ(panorama->environment->file, "env/venice_sunset_1k.hdr");
  EXPECT_EQ(panorama->environment->rotationDegrees, 90.0f);
  EXPECT_EQ(panorama->environment->intensity, 2.0f);
  EXPECT_EQ(panorama->environment->cubeSize, 128);
  EXPECT_FALSE(panorama->environment->sunLight);
  auto withSun =
      parseScene(head + R"("environment": {"file": "env/venice_sunset_1k.hdr", "sun_light": true}})", "x.json");
  ASSERT_TRUE(withSun.has_value()) << withSun.error().message;
  EXPECT_TRUE(withSun->environment->sunLight);
  auto sky = parseScene(head + R"("environment": {"sky": {"turbidity": 5, "ground_albedo": 0.2}}})", "x.json");
  ASSERT_TRUE(sky.has_value()) << sky.error().message;
  EXPECT_TRUE(sky->environment->file.empty());
  EXPECT_EQ(sky->environment->turbidity, 5.0f);
  EXPECT_EQ(sky->environment->groundAlbedo, 0.2f);
  auto plain = parseScene(head + R"("environment": {}})", "x.json");
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  EXPECT_TRUE(plain->environment->file.empty()) << "no file: the sky";

  const auto environmentError = [&](const std::string& block) {
    return errorOf(head + R"("environment": )" + block + "}");
  };
  EXPECT_EQ(environmentError(R"({"file": "a.hdr", "sky": {}})"),
            "dir/bad.json: environment.sky: expected a file or a sky, not both");
  EXPECT_EQ(environmentError(R"({"sky": {"turbidity": 12}})"),
            "dir/bad.json: environment.sky.turbidity: expected a turbidity in [1.7, 10] (2: clear, 6: hazy)");
  EXPECT_EQ(environmentError(R"({"sky": {"ground_albedo": 2}})"),
            "dir/bad.json: environment.sky.ground_albedo: expected an albedo in [0, 1]");
  EXPECT_EQ(environmentError(R"({"intensity": -1})"),
            "dir/bad.json: environment.intensity: expected an intensity in [0, 1000]");
  EXPECT_EQ(environmentError(R"({"sky": {}, "sun_light": true})"),
            "dir/bad.json: environment.sun_light: expected a panorama file to cut the sun from (the sky's sun is the "
            "first light already)");
  EXPECT_EQ(environmentError(R"({"cube_size": 4})"),
            "dir/bad.json: environment.cube_size: expected 8 to 2048 texels (or 0: the default)");
  EXPECT_NE(environmentError(R"({"sky": {"sun": 1}})").find("environment.sky.sun: unknown field"), std::string::npos);
}

TEST(Scene, ACameraOrbitTurnsItRoundItsTargetEasedInAndOut) {
  const std::string camera = R"({"name": "x", "camera": {"position": [2, 1, 0], "target": [0, 1, 0], )";
  auto scene = parseScene(camera + R"("orbit": {"degrees": 90, "seconds": 4}}, "lights": []})", "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  ASSERT_TRUE(scene->camera.orbit.has_value());
  const Camera& turning = scene->camera;
  const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-5f; };
  EXPECT_EQ(cameraPositionAt(turning, 0.0), glm::vec3(2, 1, 0));
  // A quarter turn counter-clockwise seen from above (+y): +x goes to −z.
  EXPECT_TRUE(near(cameraPositionAt(turning, 4.0), glm::vec3(0, 1, -2)));
  EXPECT_TRUE(near(cameraPositionAt(turning, 40.0), glm::vec3(0, 1, -2))) << "it stays where the turn ends";
  // Half way in time, half way round: (1 − cos(π/2))/2 = ½ of 90°.
  const float half = std::sqrt(2.0f);
  EXPECT_TRUE(near(cameraPositionAt(turning, 2.0), glm::vec3(half, 1, -half)));
  // Eased: a quarter of the time turns (1 − cos(π/4))/2 ≈ 14.6 % of the way.
  const glm::vec3 early = cameraPositionAt(turning, 1.0);
  EXPECT_NEAR(glm::degrees(std::atan2(-early.z, early.x)), 90.0 * (1.0 - std::cos(std::numbers::pi / 4.0)) / 2.0, 1e-3);
  EXPECT_NEAR(glm::length(early - turning.target), 2.0f, 1e-5f) << "the distance to the target is kept";
  auto still =
      parseScene(R"({"name": "x", "camera": {"position": [2, 1, 0], "target": [0, 1, 0]}, "lights": []})", "x.json");
  ASSERT_TRUE(still.has_value());
  EXPECT_EQ(cameraPositionAt(still->camera, 3.0), glm::vec3(2, 1, 0));

  const auto orbitError = [&](const std::string& orbit) {
    return errorOf(camera + R"("orbit": )" + orbit + R"(}, "lights": []})");
  };
  EXPECT_EQ(orbitError(R"({"degrees": 90, "seconds": 0})"),
            "dir/bad.json: camera.orbit.seconds: expected a duration in (0, 1e6] seconds");
  EXPECT_EQ(orbitError(R"({"degrees": 4000, "seconds": 1})"),
            "dir/bad.json: camera.orbit.degrees: expected a turn within ±3600 degrees");
  EXPECT_NE(orbitError(R"({"seconds": 1})").find("camera.orbit.degrees"), std::string::npos);
}

TEST(Scene, PonytailIsOneGroomOfFourFilesDrawnAs50000Strands) {
  auto scene = loadScene(kScenes / "ponytail.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->output.width, 1280);
  EXPECT_EQ(scene->output.height, 720);
  ASSERT_EQ(scene->lights.size(), 2u);  // key, then a brighter back light towards the camera
  EXPECT_GT(scene->lights[1].intensity, scene->lights[0].intensity);
  EXPECT_GT(glm::dot(scene->lights[1].direction, scene->camera.position - scene->camera.target), 0.0f);
  EXPECT_LT(glm::dot(scene->lights[0].direction, scene->camera.position - scene->camera.target), 0.0f);
  ASSERT_EQ(scene->grooms.size(), 1u);
  const Groom& groom = scene->grooms[0];
  EXPECT_EQ(groom.name, "ponytail");
  // AMD's ponytail.tfxproj order (tests/scenes/groom_loader_tests.cpp).
  EXPECT_EQ(groom.sources,
            (std::vector<std::string>{"hair/tressfx_ponytail/front_top.tfx", "hair/tressfx_ponytail/side.tfx",
                                      "hair/tressfx_ponytail/back.tfx", "hair/tressfx_ponytail/tail.tfx"}));
  EXPECT_TRUE(groom.invertZ);
  ASSERT_TRUE(groom.colliders.sdf.has_value());
  EXPECT_EQ(groom.rendering.look, render::HairLook::kBlonde);
  EXPECT_EQ(groom.rendering.denseStrands, 50'000);
  EXPECT_EQ(scene->headMotion.kind, HeadMotionKind::shake);
  EXPECT_EQ(scene->simulation.settleSeconds, 1.0f);  // with shape stiffness 0.5 the groom keeps its style
  EXPECT_EQ(scene->grooms[0].simulation.shapeStiffness, 0.5f);
  const AssetResolver resolver = testing::sharedResolver();
  for (const std::string& name : groom.sources) EXPECT_NE(resolver.find(name), nullptr) << name;
}

TEST(Scene, NaluWritesOutItsLookAndShadows) {
  // The defaults but for the layout: rooted over the whole scalp between three guides and drawn
  // towards them a little, each clump gathered towards its centre, so that 4,095 strands fall in
  // locks rather than as an even sheet, without parting into tufts (as clump 0.5, profile 3 did).
  auto scene = loadScene(kScenes / "nalu.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const GroomRendering defaults;
  const GroomRendering& rendering = scene->grooms[0].rendering;
  EXPECT_EQ(rendering.look, defaults.look);
  EXPECT_EQ(rendering.settings.width, defaults.settings.width);
  EXPECT_EQ(rendering.settings.tipWidthScale, defaults.settings.tipWidthScale);
  EXPECT_EQ(rendering.guideBlend, physics::GuideBlend::kBarycentric);
  EXPECT_FLOAT_EQ(rendering.clump, 0.3f);
  EXPECT_FLOAT_EQ(rendering.clumpProfile, 2.0f);
  EXPECT_EQ(rendering.settings.opacity, defaults.settings.opacity);
  EXPECT_EQ(rendering.settings.minimumPixelWidth, defaults.settings.minimumPixelWidth);
  EXPECT_EQ(rendering.settings.shadowExtinction, defaults.settings.shadowExtinction);
  EXPECT_EQ(rendering.denseStrands, defaults.denseStrands);
  EXPECT_EQ(scene->hairShadows.mode, render::HairShadowMode::kOpacityShadowMap);
  EXPECT_EQ(scene->hairShadows.resolution, 512u);
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

// A looping sequence starts again from its first key after its last: time wraps over first..last.
TEST(HeadMotion, LoopingKeyframesWrapOverFirstToLast) {
  const char* keys = R"([{"time": 1, "rotation_degrees": [0, 0, 0]}, {"time": 3, "rotation_degrees": [0, 40, 0]}])";
  auto scene = parseScene(std::string(R"({"name": "k", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
    "meshes": [{"name": "head", "source": "procedural:sphere"}],
    "animation": {"head": {"mesh": "head", "motion": "keyframes", "loop": true, "keyframes": )") +
                              keys + "}}}",
                          "k.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const HeadMotion& motion = scene->headMotion;
  EXPECT_TRUE(motion.loop);
  EXPECT_EQ(motion.poseAt(0.5f).rotationDegrees.y, 0.0f);            // before the first: held
  EXPECT_NEAR(motion.poseAt(3.5f).rotationDegrees.y, 10.0f, 1e-4f);  // 1.5 s into the period of 2 s
  EXPECT_NEAR(motion.poseAt(8.0f).rotationDegrees.y, 20.0f, 1e-4f);  // 3 periods on, halfway
  // One key has nothing to loop over; a periodic motion has no keys to loop.
  EXPECT_NE(errorOf(R"({"name": "k", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
      "meshes": [{"name": "head", "source": "procedural:sphere"}],
      "animation": {"head": {"mesh": "head", "motion": "keyframes", "loop": true, "keyframes": [{"time": 2}]}}})")
                .find("animation.head.loop: expected at least two keyframes to loop over"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"name": "k", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
      "meshes": [{"name": "head", "source": "procedural:sphere"}],
      "animation": {"head": {"mesh": "head", "motion": "turn", "amplitude_degrees": 20, "frequency_hz": 1,
                             "loop": true}}})")
                .find("animation.head.loop"),
            std::string::npos);
}

}  // namespace
}  // namespace mane::scenes
