// scenes/mesh_simplify: meshoptimizer's simplifier as the scenes use it, checked against the
// shapes' own geometry: a sphere's area and volume (analytic), closedness (every edge shared, by
// position), its uv seam kept, each vertex's attributes where they were, and the Stanford bunny's
// extent and area against the full scan.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "scenes/mesh_simplify.hpp"
#include "scenes/obj_loader.hpp"
#include "scenes/procedural.hpp"
#include "scenes/scene.hpp"
#include "scenes/world.hpp"
#include "subdivision_test_shapes.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

struct Measures {
  double area = 0.0;
  double volume = 0.0;  ///< signed: positive for outward-wound closed meshes
};

Measures measure(const Mesh& mesh) {
  Measures m;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    m.area += 0.5 * glm::length(glm::cross(b - a, c - a));
    m.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return m;
}

// 64 rings × 128 segments (16,128 triangles) down to at most 1,000: still closed, outward, with
// its area and volume within 2 % and 3 % of the unit sphere's (an inscribed polyhedron of 500
// vertices spread evenly has about 1 % less area), and every triangle's centroid within the error
// meshoptimizer reports (plus the flat-triangle sag it allows) of the sphere.
TEST(MeshSimplify, ASphereKeepsItsShapeClosedAndOutward) {
  const Mesh sphere = makeSphere(64, 128, 1.0f);
  auto simplified = simplifyMesh(sphere, {.targetTriangles = 1000, .maxRelativeError = 0.02f});
  ASSERT_TRUE(simplified.has_value()) << simplified.error().message;
  const Mesh& mesh = simplified->mesh;
  EXPECT_LE(mesh.triangleCount(), 1000u);
  EXPECT_GE(mesh.triangleCount(), 500u) << "the error bound should allow getting near the target";
  EXPECT_EQ(testing::unmatchedEdges(mesh), 0u);
  const Measures m = measure(mesh);
  EXPECT_NEAR(m.area, 4.0 * std::numbers::pi, 0.02 * 4.0 * std::numbers::pi);
  EXPECT_NEAR(m.volume, 4.0 / 3.0 * std::numbers::pi, 0.03 * 4.0 / 3.0 * std::numbers::pi);
  EXPECT_GT(simplified->error, 0.0f);
  EXPECT_LE(simplified->error, 0.02f * 2.0f) << "within the bound: 2 % of the 2 m extent";
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::vec3 centroid =
        (mesh.positions[mesh.indices[t]] + mesh.positions[mesh.indices[t + 1]] + mesh.positions[mesh.indices[t + 2]]) /
        3.0f;
    ASSERT_GT(glm::length(centroid), 1.0f - 0.04f - 2.0f * simplified->error) << "triangle " << t / 3;
  }
}

// Each surviving vertex keeps its own normal and uv: the input has exactly one vertex with that
// position and uv (the seam's copies differ in u), and it must carry the same normal.
TEST(MeshSimplify, VerticesKeepTheirAttributesAndTheSeamStaysSplit) {
  const Mesh sphere = makeSphere(32, 64, 2.0f);
  using Key = std::tuple<float, float, float, float, float>;
  std::map<Key, glm::vec3> normals;
  for (std::size_t i = 0; i < sphere.positions.size(); ++i) {
    const glm::vec3 p = sphere.positions[i];
    normals[{p.x, p.y, p.z, sphere.uvs[i].x, sphere.uvs[i].y}] = sphere.normals[i];
  }
  auto simplified = simplifyMesh(sphere, {.targetTriangles = 600});
  ASSERT_TRUE(simplified.has_value()) << simplified.error().message;
  const Mesh& mesh = simplified->mesh;
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  std::size_t onSeam = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = mesh.positions[i];
    const auto found = normals.find({p.x, p.y, p.z, mesh.uvs[i].x, mesh.uvs[i].y});
    ASSERT_NE(found, normals.end()) << "vertex " << i << " is no input vertex";
    EXPECT_EQ(found->second, mesh.normals[i]) << "vertex " << i;
    if (mesh.uvs[i].x == 0.0f || mesh.uvs[i].x == 1.0f) ++onSeam;
  }
  EXPECT_GE(onSeam, 4u) << "the u = 0 / u = 1 seam keeps copies of both sides";
  EXPECT_EQ(testing::unmatchedEdges(mesh), 0u) << "the seam's two sides still meet";
  // No triangle straddles the seam: its u values span less than half the texture.
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const float u0 = mesh.uvs[mesh.indices[t]].x, u1 = mesh.uvs[mesh.indices[t + 1]].x,
                u2 = mesh.uvs[mesh.indices[t + 2]].x;
    ASSERT_LT(std::max({u0, u1, u2}) - std::min({u0, u1, u2}), 0.5f) << "triangle " << t / 3;
  }
}

// At or under the target the triangles stay as they are; the two unused pole copies go.
TEST(MeshSimplify, AMeshUnderTheTargetOnlyLosesItsUnusedVertices) {
  const Mesh sphere = makeSphere(8, 16, 1.0f);
  auto simplified = simplifyMesh(sphere, {.targetTriangles = sphere.triangleCount()});
  ASSERT_TRUE(simplified.has_value()) << simplified.error().message;
  EXPECT_EQ(simplified->mesh.triangleCount(), sphere.triangleCount());
  EXPECT_EQ(simplified->mesh.vertexCount(), sphere.vertexCount() - 2);
  EXPECT_EQ(simplified->error, 0.0f);
  for (std::size_t t = 0; t < sphere.indices.size(); ++t)
    ASSERT_EQ(simplified->mesh.positions[simplified->mesh.indices[t]], sphere.positions[sphere.indices[t]]);
}

TEST(MeshSimplify, BadSettingsAndMeshesAreErrors) {
  const Mesh sphere = makeSphere(8, 16, 1.0f);
  EXPECT_EQ(simplifyMesh(sphere, {.targetTriangles = 0}).error().message, "simplifying to 0 triangles");
  for (const float error : {0.0f, -0.1f, 1.5f, std::nanf("")})
    EXPECT_NE(simplifyMesh(sphere, {.targetTriangles = 10, .maxRelativeError = error})
                  .error()
                  .message.find("error bound must be in (0, 1]"),
              std::string::npos)
        << error;
  Mesh broken = sphere;
  broken.indices[7] = std::uint32_t(broken.positions.size());
  EXPECT_NE(simplifyMesh(broken, {.targetTriangles = 10}).error().message.find("index 7 is"), std::string::npos);
  broken = sphere;
  broken.normals.pop_back();
  EXPECT_NE(simplifyMesh(broken, {.targetTriangles = 10}).error().message.find("normals or uvs do not match"),
            std::string::npos);
  broken = sphere;
  broken.indices.pop_back();
  EXPECT_NE(simplifyMesh(broken, {.targetTriangles = 10}).error().message.find("not a multiple of 3"),
            std::string::npos);
}

// The real scan, as nalu draws it: 69,451 triangles down to 8,000. Its extent is unchanged to
// 0.5 % (the silhouette holds) and its area (the fur's skin) to 2 %.
TEST(MeshSimplify, TheStanfordBunnyAt8000TrianglesKeepsItsExtentAndArea) {
  MANE_RESOLVE_OR_SKIP(file, "meshes/stanford-bunny.obj");
  auto bunny = loadMesh(file);
  ASSERT_TRUE(bunny.has_value()) << bunny.error().message;
  auto simplified = simplifyMesh(*bunny, {.targetTriangles = 8000});
  ASSERT_TRUE(simplified.has_value()) << simplified.error().message;
  const Mesh& mesh = simplified->mesh;
  EXPECT_LE(mesh.triangleCount(), 8000u);
  EXPECT_GE(mesh.triangleCount(), 7000u);
  const glm::vec3 before = bunny->bounds().size(), after = mesh.bounds().size();
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(after[axis], before[axis], 0.005f * before[axis]) << axis;
  const double area = measure(*bunny).area;
  EXPECT_NEAR(measure(mesh).area, area, 0.02 * area);
  std::printf("bunny: %zu → %zu triangles, error %.3g (extent %.3g)\n", bunny->triangleCount(), mesh.triangleCount(),
              simplified->error, double(std::max({before.x, before.y, before.z})));
}

/// A scene with one mesh entry; `meshFields` completes the mesh object.
std::string sceneWithMesh(const std::string& meshFields) {
  return R"({"name": "x", "camera": {"position": [0, 0, 4], "target": [0, 0, 0]},
             "meshes": [{"name": "ball", "source": "procedural:sphere")" +
         meshFields + "}]}";
}

std::string errorOf(const std::string& meshFields) {
  auto scene = parseScene(sceneWithMesh(meshFields), "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

// A scene's `simplify` block: the World draws the simplified triangles (the procedural sphere has
// 32 × 64 cells, 3,968 triangles).
TEST(SceneSimplify, TheWorldDrawsTheSimplifiedMesh) {
  auto plain = parseScene(sceneWithMesh(""), "x.json");
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  EXPECT_FALSE(plain->meshes[0].simplify.has_value());
  auto scene = parseScene(sceneWithMesh(R"(, "simplify": {"triangles": 500, "max_error": 0.05})"), "x.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  ASSERT_TRUE(scene->meshes[0].simplify.has_value());
  EXPECT_EQ(scene->meshes[0].simplify->triangles, 500);
  EXPECT_EQ(scene->meshes[0].simplify->maxRelativeError, 0.05f);
  EXPECT_EQ(
      parseScene(sceneWithMesh(R"(, "simplify": {"triangles": 500})"), "x.json")->meshes[0].simplify->maxRelativeError,
      0.01f);
  auto world = World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::StaticScene statics = world->staticScene();
  ASSERT_EQ(statics.meshes.size(), 1u);
  EXPECT_LE(statics.meshes[0].indices.size(), 3u * 500u);
  EXPECT_GE(statics.meshes[0].indices.size(), 3u * 250u);
  EXPECT_EQ(testing::unmatchedEdges(statics.meshes[0]), 0u);
}

TEST(SceneSimplify, ErrorsNameTheFieldPath) {
  EXPECT_EQ(errorOf(R"(, "simplify": {"triangles": 0})"),
            "dir/bad.json: meshes[0].simplify.triangles: expected at least 1 triangle");
  EXPECT_NE(errorOf(R"(, "simplify": {})").find("meshes[0].simplify.triangles"), std::string::npos);
  EXPECT_EQ(errorOf(R"(, "simplify": {"triangles": 10, "max_error": 0})"),
            "dir/bad.json: meshes[0].simplify.max_error: expected an error in (0, 1] of the mesh's extent");
  EXPECT_NE(errorOf(R"(, "simplify": {"triangles": 10, "ratio": 0.5})").find("meshes[0].simplify.ratio: unknown field"),
            std::string::npos);
  EXPECT_EQ(errorOf(R"(, "subdivision": {}, "simplify": {"triangles": 10})"),
            "dir/bad.json: meshes[0].simplify: a subdivided mesh is drawn from its limit surface: simplify its cage "
            "instead");
}

}  // namespace
}  // namespace mane::scenes
