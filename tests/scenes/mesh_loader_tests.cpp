// The mesh loaders on every glTF and mesh asset the project ships, checked against counts
// published in ../shared/assets/README.md and, where the README gives none, against counts
// and bounds derived here straight from the files (glTF JSON read with nlohmann, not
// tinygltf; OBJ text counted line by line).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "scenes/obj_loader.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using testing::readFile;
using testing::sharedResolver;

/// What the glTF JSON says the default scene holds.
struct GltfExpectation {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  Bounds bounds{glm::vec3(1e30f), glm::vec3(-1e30f)};
  /// Whether every mesh node's transform keeps the axes (rotations by multiples of 90°): then the
  /// transformed accessor boxes are the exact bounds, otherwise only boxes around them.
  bool boundsExact = true;
};

/// Whether `m` maps each axis onto one axis: each column of its linear part has one nonzero entry.
bool keepsAxes(const glm::mat4& m) {
  for (int column = 0; column < 3; ++column) {
    const glm::vec3 c(m[column]);
    const float largest = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
    int nonzero = 0;
    for (int row = 0; row < 3; ++row) nonzero += std::abs(c[row]) > 1e-6f * largest;
    if (nonzero != 1) return false;
  }
  return true;
}

nlohmann::json gltfJson(const std::filesystem::path& file) {
  const std::string bytes = readFile(file);
  if (bytes.compare(0, 4, "glTF") == 0) {
    std::uint32_t chunkLength = 0;
    std::memcpy(&chunkLength, bytes.data() + 12, 4);
    return nlohmann::json::parse(bytes.substr(20, chunkLength));
  }
  return nlohmann::json::parse(bytes);
}

glm::mat4 nodeMatrix(const nlohmann::json& node) {
  if (node.contains("matrix")) {
    const auto m = node["matrix"].get<std::vector<float>>();
    return glm::make_mat4(m.data());
  }
  glm::mat4 t(1.0f);
  if (node.contains("translation")) {
    const auto v = node["translation"].get<std::vector<float>>();
    t = glm::translate(t, glm::make_vec3(v.data()));
  }
  if (node.contains("rotation")) {
    const auto q = node["rotation"].get<std::vector<float>>();
    t = t * glm::mat4_cast(glm::quat(q[3], q[0], q[1], q[2]));
  }
  if (node.contains("scale")) {
    const auto s = node["scale"].get<std::vector<float>>();
    t = glm::scale(t, glm::make_vec3(s.data()));
  }
  return t;
}

void expectNode(const nlohmann::json& gltf, int index, const glm::mat4& parent, GltfExpectation& out) {
  const auto& node = gltf["nodes"][static_cast<std::size_t>(index)];
  const glm::mat4 world = parent * nodeMatrix(node);
  if (node.contains("mesh")) {
    out.boundsExact = out.boundsExact && keepsAxes(world);
    for (const auto& primitive : gltf["meshes"][node["mesh"].get<std::size_t>()]["primitives"]) {
      const auto& position = gltf["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()];
      const std::size_t count = position["count"].get<std::size_t>();
      out.vertices += count;
      out.triangles += primitive.contains("indices")
                           ? gltf["accessors"][primitive["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3
                           : count / 3;
      const auto lo = position["min"].get<std::vector<float>>();
      const auto hi = position["max"].get<std::vector<float>>();
      for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1], (corner & 4) ? hi[2] : lo[2]);
        const glm::vec3 w = glm::vec3(world * glm::vec4(p, 1.0f));
        out.bounds.min = glm::min(out.bounds.min, w);
        out.bounds.max = glm::max(out.bounds.max, w);
      }
    }
  }
  if (node.contains("children")) {
    for (const auto& child : node["children"]) expectNode(gltf, child.get<int>(), world, out);
  }
}

GltfExpectation expectGltf(const std::filesystem::path& file) {
  const nlohmann::json gltf = gltfJson(file);
  GltfExpectation out;
  const int scene = gltf.value("scene", 0);
  for (const auto& root : gltf["scenes"][static_cast<std::size_t>(scene)]["nodes"]) {
    expectNode(gltf, root.get<int>(), glm::mat4(1.0f), out);
  }
  return out;
}

/// Every .gltf/.glb the manifest lists: the test covers new samples automatically.
std::vector<std::string> gltfAssetNames() {
  std::vector<std::string> names;
  const AssetResolver resolver = sharedResolver();
  for (const AssetEntry& entry : resolver.entries()) {
    const std::string& n = entry.name;
    if (n.ends_with(".gltf") || n.ends_with(".glb")) names.push_back(n);
  }
  return names;
}

TEST(GltfAssets, ManifestListsEveryGltfFileInTheSharedFolder) {
  MANE_RESOLVE_OR_SKIP(box, "gltf/BoxTextured/glTF-Binary/BoxTextured.glb");
  const std::filesystem::path root = box.parent_path().parent_path().parent_path().parent_path();
  const auto names = gltfAssetNames();
  const std::set<std::string> listed(names.begin(), names.end());
  std::size_t seen = 0;
  for (const auto& item : std::filesystem::recursive_directory_iterator(root)) {
    const std::string ext = item.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    ++seen;
    EXPECT_TRUE(listed.contains(item.path().lexically_relative(root).generic_string())) << item.path();
  }
  EXPECT_EQ(seen, listed.size());
  EXPECT_GE(seen, 8u);  // 6 samples under gltf/, LeePerrySmith, the converted ponytail head
}

TEST(GltfAssets, EveryFileLoadsWithTheCountsAndBoundsItsJsonDeclares) {
  const auto names = gltfAssetNames();
  ASSERT_FALSE(names.empty());
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    MANE_RESOLVE_OR_SKIP(file, name);
    auto mesh = loadMesh(file);
    ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
    EXPECT_EQ(validate(*mesh), "");
    const GltfExpectation expected = expectGltf(file);
    EXPECT_EQ(mesh->vertexCount(), expected.vertices);
    EXPECT_EQ(mesh->triangleCount(), expected.triangles);
    EXPECT_EQ(mesh->normals.size(), mesh->positions.size());
    // Accessor min/max are exact. Where every node rotation is a multiple of 90° the transformed
    // accessor boxes are the exact bounds; elsewhere (RobotExpressive's joints) they contain
    // them. 1e-4 relative covers float rounding of the transforms.
    const Bounds got = mesh->bounds();
    const float tolerance = 1e-4f * glm::length(expected.bounds.size()) + 1e-5f;
    EXPECT_TRUE(expected.boundsExact || name.starts_with("characters/")) << "only the character turns its nodes freely";
    for (int axis = 0; axis < 3; ++axis) {
      if (expected.boundsExact) {
        EXPECT_NEAR(got.min[axis], expected.bounds.min[axis], tolerance) << "axis " << axis;
        EXPECT_NEAR(got.max[axis], expected.bounds.max[axis], tolerance) << "axis " << axis;
      } else {
        EXPECT_GE(got.min[axis], expected.bounds.min[axis] - tolerance) << "axis " << axis;
        EXPECT_LE(got.max[axis], expected.bounds.max[axis] + tolerance) << "axis " << axis;
      }
    }
    for (const glm::vec3& n : mesh->normals) {
      ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
    }
  }
}

TEST(GltfAssets, PublishedCountsFromTheAssetsReadme) {
  struct Case {
    const char* name;
    std::size_t vertices;  // 0: the README gives none
    std::size_t triangles;
  };
  const Case cases[] = {
      {"head/LeePerrySmith/LeePerrySmith.glb", 9279, 17684},
      {"gltf/BoxTextured/glTF/BoxTextured.gltf", 0, 12},
      {"gltf/BoxTextured/glTF-Binary/BoxTextured.glb", 0, 12},
      {"gltf/BoxTextured/glTF-Embedded/BoxTextured.gltf", 0, 12},
      {"gltf/Flower/Flower.glb", 0, 80},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    MANE_RESOLVE_OR_SKIP(file, c.name);
    auto mesh = loadMesh(file);
    ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
    if (c.vertices != 0) {
      EXPECT_EQ(mesh->vertexCount(), c.vertices);
    }
    EXPECT_EQ(mesh->triangleCount(), c.triangles);
  }
}

TEST(GltfAssets, LeePerrySmithKeepsItsTextureCoordinatesForTheJpegMaps) {
  MANE_RESOLVE_OR_SKIP(file, "head/LeePerrySmith/LeePerrySmith.glb");
  auto mesh = loadMesh(file);
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  ASSERT_EQ(mesh->uvs.size(), mesh->positions.size());
  for (const glm::vec2& uv : mesh->uvs) {  // accessor min/max: [0.00505, 0.99493] etc.
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LE(uv.x, 1.0f);
  }
}

/// Distinct `v` positions and the triangle count a fan split gives, counted from the text.
struct ObjExpectation {
  std::size_t distinctPositions = 0;
  std::size_t triangles = 0;
};

ObjExpectation expectObj(const std::filesystem::path& file) {
  std::istringstream text(readFile(file));
  std::set<std::tuple<float, float, float>> positions;
  ObjExpectation out;
  for (std::string line; std::getline(text, line);) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      float x, y, z;
      words >> x >> y >> z;
      positions.emplace(x, y, z);
    } else if (tag == "f") {
      std::size_t corners = 0;
      for (std::string corner; words >> corner;) ++corners;
      out.triangles += corners - 2;
    }
  }
  out.distinctPositions = positions.size();
  return out;
}

std::size_t distinctPositions(const Mesh& mesh) {
  std::set<std::tuple<float, float, float>> seen;
  for (const glm::vec3& p : mesh.positions) seen.emplace(p.x, p.y, p.z);
  return seen.size();
}

TEST(ObjAssets, BunnyAndTeapotMatchTheReadme) {
  struct Case {
    const char* name;
    std::size_t vertices;
    std::size_t triangles;
  };
  for (const Case& c : {Case{"meshes/stanford-bunny.obj", 35947, 69451}, Case{"meshes/teapot.obj", 3644, 6320}}) {
    SCOPED_TRACE(c.name);
    MANE_RESOLVE_OR_SKIP(file, c.name);
    auto mesh = loadMesh(file);
    ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
    EXPECT_EQ(validate(*mesh), "");
    // Positions only: de-duplication by (v, vt, vn) keeps exactly one vertex per `v`.
    EXPECT_EQ(mesh->vertexCount(), c.vertices);
    EXPECT_EQ(distinctPositions(*mesh), expectObj(file).distinctPositions);
    EXPECT_EQ(mesh->triangleCount(), c.triangles);
    EXPECT_TRUE(mesh->uvs.empty());
    EXPECT_EQ(mesh->normals.size(), mesh->positions.size());  // computed
  }
}

TEST(ObjAssets, EverySubdivisionCageTriangulatesAsItsFaceListSays) {
  std::size_t cages = 0;
  const AssetResolver resolver = sharedResolver();
  for (const AssetEntry& entry : resolver.entries()) {
    if (!entry.name.starts_with("subdiv/") || !entry.name.ends_with(".obj")) continue;
    SCOPED_TRACE(entry.name);
    ++cages;
    MANE_RESOLVE_OR_SKIP(file, entry.name);
    auto mesh = loadMesh(file);
    ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
    EXPECT_EQ(validate(*mesh), "");
    const ObjExpectation expected = expectObj(file);
    EXPECT_EQ(mesh->triangleCount(), expected.triangles);
    // Cages with texture coordinates split vertices at UV seams; positions stay the file's.
    EXPECT_EQ(distinctPositions(*mesh), expected.distinctPositions);
    EXPECT_GE(mesh->vertexCount(), expected.distinctPositions);
  }
  EXPECT_EQ(cages, 8u);  // README: cube, torus, torus_creases0, pyramid, tent, pawn, rook, bishop
}

}  // namespace
}  // namespace mane::scenes
