// Subdivision surfaces in scene files: a mesh entry's `subdivision` block makes the World draw the
// Catmull-Clark limit surface, tessellated for the scene's camera.
//
// Oracles: a closed cage gives a closed mesh (every directed edge matched by its reverse, by
// position: UV seams split vertices, not the surface); the limit surface of a fine sphere cage
// is a sphere, so its curvature is 1/R; errors name the JSON path.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "physics/sdf.hpp"
#include "scenes/gltf_loader.hpp"
#include "scenes/scene.hpp"
#include "scenes/subdivided_mesh.hpp"
#include "scenes/world.hpp"
#include "test_support.hpp"
#include "subdivision_test_shapes.hpp"

namespace mane::scenes {
namespace {

using testing::quadSphereObj;
using testing::unmatchedEdges;

const std::filesystem::path kScenes = std::filesystem::path(MANE_SOURCE_DIR) / "scenes";

/// A scene with one skin material and one mesh entry; `meshFields` completes the mesh object.
std::string sceneWithMesh(const std::string& meshFields) {
  return R"({"name": "x", "output": {"width": 640, "height": 480},
             "camera": {"position": [0, 0, 4], "target": [0, 0, 0]},
             "materials": [{"name": "skin", "kind": "skin"}],
             "meshes": [{"name": "ball", "material": "skin")" +
         meshFields + "}]}";
}

std::string errorOf(const std::string& meshFields) {
  auto scene = parseScene(sceneWithMesh(meshFields), "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

Result<World> worldOf(const std::string& text, const std::filesystem::path& file = "x.json") {
  auto scene = parseScene(text, file);
  if (!scene) return std::unexpected(scene.error());
  return World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
}

TEST(SceneSubdivision, IsOffUnlessAskedAndTakesItsFields) {
  auto plain = parseScene(sceneWithMesh(R"(, "source": "procedural:sphere")"), "x.json");
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  EXPECT_FALSE(plain->meshes[0].subdivision.has_value());
  auto defaults = parseScene(sceneWithMesh(R"(, "source": "procedural:sphere", "subdivision": {})"), "x.json");
  ASSERT_TRUE(defaults.has_value()) << defaults.error().message;
  ASSERT_TRUE(defaults->meshes[0].subdivision.has_value());
  EXPECT_EQ(defaults->meshes[0].subdivision->maxPixelError, 1.0f);
  EXPECT_EQ(defaults->meshes[0].subdivision->isolation, 2);
  EXPECT_EQ(defaults->meshes[0].subdivision->maxDepth, 10);
  EXPECT_FALSE(defaults->meshes[0].subdivision->capHoles);
  auto chosen = parseScene(sceneWithMesh(R"(, "source": "procedural:sphere", "subdivision":
      {"max_pixel_error": 0.5, "isolation": 3, "max_depth": 6, "cap_holes": true})"),
                           "x.json");
  ASSERT_TRUE(chosen.has_value()) << chosen.error().message;
  EXPECT_EQ(chosen->meshes[0].subdivision->maxPixelError, 0.5f);
  EXPECT_EQ(chosen->meshes[0].subdivision->isolation, 3);
  EXPECT_EQ(chosen->meshes[0].subdivision->maxDepth, 6);
  EXPECT_TRUE(chosen->meshes[0].subdivision->capHoles);
  EXPECT_FALSE(chosen->meshes[0].subdivision->coarseCage.has_value());
  auto coarse = parseScene(sceneWithMesh(R"(, "source": "procedural:sphere", "subdivision":
      {"coarse_cage": {"triangles": 300, "max_error": 0.02}})"),
                           "x.json");
  ASSERT_TRUE(coarse.has_value()) << coarse.error().message;
  ASSERT_TRUE(coarse->meshes[0].subdivision->coarseCage.has_value());
  EXPECT_EQ(coarse->meshes[0].subdivision->coarseCage->triangles, 300);
  EXPECT_EQ(coarse->meshes[0].subdivision->coarseCage->maxRelativeError, 0.02f);
}

TEST(SceneSubdivision, ErrorsNameTheFieldPath) {
  const std::string source = R"(, "source": "procedural:sphere", )";
  EXPECT_NE(errorOf(source + R"("subdivision": {"isolation": 0})").find("meshes[0].subdivision.isolation"),
            std::string::npos);
  EXPECT_NE(errorOf(source + R"("subdivision": {"max_pixel_error": -1})").find("meshes[0].subdivision.max_pixel_error"),
            std::string::npos);
  EXPECT_NE(errorOf(source + R"("subdivision": {"max_depth": 11})").find("meshes[0].subdivision.max_depth"),
            std::string::npos);
  EXPECT_NE(errorOf(source + R"("subdivision": {"levels": 2})").find("meshes[0].subdivision.levels: unknown field"),
            std::string::npos);
  EXPECT_NE(errorOf(source + R"("subdivision": 2)").find("meshes[0].subdivision: expected an object"),
            std::string::npos);
  EXPECT_NE(errorOf(source + R"("subdivision": {"cap_holes": 1})").find("meshes[0].subdivision.cap_holes"),
            std::string::npos);
  EXPECT_NE(
      errorOf(source + R"("subdivision": {"coarse_cage": {}})").find("meshes[0].subdivision.coarse_cage.triangles"),
      std::string::npos);
  EXPECT_NE(errorOf(source + R"("subdivision": {"coarse_cage": {"triangles": 0}})")
                .find("meshes[0].subdivision.coarse_cage.triangles"),
            std::string::npos);
  EXPECT_NE(errorOf(source + R"("subdivision": {"coarse_cage": {"triangles": 9, "max_error": 2}})")
                .find("meshes[0].subdivision.coarse_cage.max_error"),
            std::string::npos);
}

TEST(SceneSubdivision, SubdividedSphereIsClosedWithTheSpheresCurvature) {
  testing::ScratchDir dir;
  dir.write("sphere.obj", quadSphereObj(32, 16));
  const std::filesystem::path scene = dir.write("scene.json", sceneWithMesh(R"(, "source": "sphere.obj",
      "subdivision": {"max_pixel_error": 0.5, "isolation": 3})"));
  auto world = worldOf(testing::readFile(scene), scene);
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::StaticScene frame = world->staticScene();
  const render::MeshData& mesh = frame.meshes.at(0);
  EXPECT_GT(mesh.indices.size() / 3, 2u * 32u * 16u) << "the camera at 4 radii asks for more than the cage";
  EXPECT_EQ(unmatchedEdges(mesh), 0u);
  ASSERT_EQ(mesh.curvatures.size(), mesh.positions.size());
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  // The limit surface of a 32 × 16 sphere cage lies a little inside it (B-spline smoothing of
  // the cage's chords: about 1 %), with outward normals; 1/r per unit is then 1/radius within
  // 3 %. Not near the poles: they are extraordinary points of valence 32 whose Gregory end caps
  // only approximate second derivatives (off by up to 5× there), and the adaptive tessellation
  // puts many vertices in their small isolated patches; the test keeps |y| < 0.9.
  float worst = 0.0f;
  std::size_t checked = 0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const float radius = glm::length(mesh.positions[v]);
    EXPECT_NEAR(radius, 1.0f, 0.02f);
    EXPECT_GT(glm::dot(mesh.normals[v], mesh.positions[v] / radius), 0.99f);
    if (std::abs(mesh.positions[v].y) >= 0.9f) continue;
    worst = std::max(worst, std::abs(mesh.curvatures[v] * radius - 1.0f));
    ++checked;
  }
  EXPECT_GT(checked, mesh.positions.size() / 4);
  EXPECT_LT(worst, 0.03f);
}

// nalu.json's head: the LeePerrySmith scan (file units, about 8 tall) drawn through a coarse
// cage of 3,000 simplified triangles paired into quads. Oracle: the scan itself. The limit
// surface must stay within a small distance of it both ways (tessellated vertices against the
// scan's distance field, scan vertices against the tessellation's), and be closed like it.
TEST(SceneSubdivision, CoarseCageOfTheHeadScanStaysOnTheScan) {
  auto scan = testing::sharedResolver().lookup("head/LeePerrySmith/LeePerrySmith.glb");
  ASSERT_TRUE(scan.has_value()) << scan.error().message;
  if (!scan->path) GTEST_SKIP() << scan->missingReason;
  auto scanMesh = loadGltf(*scan->path);
  ASSERT_TRUE(scanMesh.has_value()) << scanMesh.error().message;
  const glm::vec3 centre = scanMesh->bounds().centre();
  const auto number = [](float x) { return std::to_string(x); };
  auto world = worldOf(R"({"name": "head", "output": {"width": 1280, "height": 720},
      "camera": {"position": [)" +
                       number(centre.x) + ", " + number(centre.y) + ", " + number(centre.z + 20.0f) +
                       R"(], "target": [)" + number(centre.x) + ", " + number(centre.y) + ", " + number(centre.z) +
                       R"(], "fov_degrees": 40, "near": 0.1, "far": 100},
      "materials": [{"name": "skin", "kind": "skin"}],
      "meshes": [{"name": "head", "source": "head/LeePerrySmith/LeePerrySmith.glb", "material": "skin",
                  "subdivision": {"isolation": 1, "coarse_cage": {"triangles": 3000, "max_error": 0.05}}}]})");
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::StaticScene statics = world->staticScene();
  const render::MeshData& limit = statics.meshes.at(0);
  EXPECT_EQ(unmatchedEdges(limit), 0u);
  EXPECT_GT(limit.indices.size() / 3, 3000u);

  const physics::SdfSettings fine{.resolution = 128, .bandCells = 3};
  auto scanField = physics::SignedDistanceField::build(scanMesh->positions, scanMesh->indices, fine);
  ASSERT_TRUE(scanField.has_value()) << scanField.error().message;
  auto limitField = physics::SignedDistanceField::build(limit.positions, limit.indices, fine);
  ASSERT_TRUE(limitField.has_value()) << limitField.error().message;
  const auto distances = [](const physics::SignedDistanceField& field, std::span<const glm::vec3> points) {
    float worst = 0.0f;
    double sum = 0.0;
    for (const glm::vec3& p : points) {
      const float d = std::abs(field.sample(p));
      worst = std::max(worst, d);
      sum += d;
    }
    return std::pair{worst, float(sum / double(points.size()))};
  };
  const auto [limitWorst, limitMean] = distances(*scanField, limit.positions);
  const auto [scanWorst, scanMean] = distances(*limitField, scanMesh->positions);
  // Measured: means 0.011 and 0.017, worst 0.09 and 0.11 units (the simplifier itself reached
  // 0.02); in nalu.json's scale (0.025 m per unit) 0.3–0.4 mm on average and under 3 mm at
  // worst, where the limit surface rounds the cage's sharpest corners (ear rims, nostrils).
  const float height = scanMesh->bounds().size().y;
  EXPECT_LT(limitMean, 0.003f * height) << "worst " << limitWorst << " mean " << limitMean;
  EXPECT_LT(scanMean, 0.003f * height) << "worst " << scanWorst << " mean " << scanMean;
  EXPECT_LT(limitWorst, 0.02f * height);
  EXPECT_LT(scanWorst, 0.02f * height);
}

TEST(SceneSubdivision, ObjCageKeepsItsQuadsAndCreases) {
  // A cube with all twelve edges infinitely sharp: its limit surface is the cube itself, six
  // flat faces at ±1 (a smooth cube would shrink towards a rounded blob inside ±0.8).
  testing::ScratchDir dir;
  std::string obj =
      "v -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 -1\nv 1 -1 -1\n"
      "f 1 2 4 3\nf 3 4 6 5\nf 5 6 8 7\nf 7 8 2 1\nf 2 8 6 4\nf 7 1 3 5\n";
  for (const auto& [a, b] : std::vector<std::pair<int, int>>{
           {0, 1}, {1, 3}, {3, 2}, {2, 0}, {2, 4}, {3, 5}, {4, 5}, {4, 6}, {5, 7}, {6, 7}, {6, 0}, {7, 1}})
    obj += "t crease 2/1/0 " + std::to_string(a) + " " + std::to_string(b) + " 10\n";
  dir.write("sharp_cube.obj", obj);
  const std::filesystem::path scene = dir.write("scene.json", sceneWithMesh(R"(, "source": "sharp_cube.obj",
      "subdivision": {"isolation": 1})"));
  auto world = worldOf(testing::readFile(scene), scene);
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::MeshData mesh = world->staticScene().meshes.at(0);
  EXPECT_EQ(unmatchedEdges(mesh), 0u);
  for (const glm::vec3& p : mesh.positions) {
    const float largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    EXPECT_NEAR(largest, 1.0f, 1e-5f) << "every limit point lies on a face of the cube";
  }
}

TEST(SceneSubdivision, BadCageIsAnErrorNamingTheMeshAndTheFile) {
  testing::ScratchDir dir;
  // Three faces on one edge: non-manifold.
  dir.write("fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  const std::filesystem::path scene = dir.write("scene.json", sceneWithMesh(R"(, "source": "fin.obj",
      "subdivision": {})"));
  auto world = worldOf(testing::readFile(scene), scene);
  ASSERT_FALSE(world.has_value());
  EXPECT_NE(world.error().message.find("mesh 'ball'"), std::string::npos) << world.error().message;
  EXPECT_NE(world.error().message.find("fin.obj"), std::string::npos) << world.error().message;
}

TEST(SceneSubdivision, CappingClosesAnOpenCageWithASharpRim) {
  // An open box (no top): one loop of four boundary edges.
  subdiv::Cage box;
  box.positions = {{-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, -1}, {1, -1, -1}};
  box.faceSizes = {4, 4, 4, 4, 4};
  box.faceVertices = {0, 1, 3, 2, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4};
  EXPECT_EQ(capBoundaryLoops(box), 1u);
  ASSERT_EQ(box.faceSizes.size(), 6u);
  EXPECT_EQ(box.creases.size(), 4u);
  EXPECT_TRUE(subdiv::validateCage(box).has_value()) << "the cap is wound like its neighbours";
  EXPECT_EQ(capBoundaryLoops(box), 0u) << "nothing left open";
}

TEST(SceneSubdivision, ChessSceneLoadsClosedTranslucentPieces) {
  auto scene = loadScene(kScenes / "chess.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_EQ(scene->output.width, 640);
  EXPECT_EQ(scene->output.height, 480);
  ASSERT_EQ(scene->meshes.size(), 3u);
  auto world = World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  if (!world->notes().empty()) GTEST_SKIP() << "chess pieces missing: " << world->notes().front();
  const render::StaticScene frame = world->staticScene();
  for (std::size_t m = 0; m < 3; ++m) {
    EXPECT_GT(frame.meshes[m].indices.size() / 3, 2000u) << world->scene().meshes[m].name;
    EXPECT_EQ(unmatchedEdges(frame.meshes[m]), 0u) << world->scene().meshes[m].name << " must be closed";
  }
  // The scene's one material; the renderer's default material comes after it.
  EXPECT_EQ(frame.materials.front().translucency.method, render::TranslucencyMethod::kVoxelLut);
}

}  // namespace
}  // namespace mane::scenes
