// glTF loader on small files written here, each exercising one feature the shipped samples
// lack (sparse accessors, interleaving, u8/u32 indices, missing buffer views, mirroring),
// and on broken files, where the error must name the file and the problem.

#include <gtest/gtest.h>

#include <cstring>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scenes/gltf_loader.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using testing::ScratchDir;

std::string base64(const std::vector<unsigned char>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t a = bytes[i];
    const std::uint32_t b = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    const std::uint32_t c = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t n = (a << 16) | (b << 8) | c;
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

/// Appends values as raw little-endian bytes.
template <class T>
void put(std::vector<unsigned char>& bytes, std::initializer_list<T> values) {
  for (T v : values) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    bytes.insert(bytes.end(), raw, raw + sizeof(T));
  }
}

/// A one-triangle glTF around `buffer`, with the given accessors, views and primitive.
nlohmann::json document(const std::vector<unsigned char>& buffer, nlohmann::json views, nlohmann::json accessors,
                        nlohmann::json primitive, nlohmann::json nodes = nlohmann::json::array({{{"mesh", 0}}})) {
  return {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", nodes},
      {"meshes", {{{"primitives", {primitive}}}}},
      {"buffers", {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}}},
      {"bufferViews", views},
      {"accessors", accessors},
  };
}

// The triangle (0,0,0) (1,0,0) (0,1,0), normal +Z.
const float kTriangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

TEST(GltfLoader, ReadsInterleavedAttributesWithUnsignedByteIndices) {
  std::vector<unsigned char> buffer;
  for (int v = 0; v < 3; ++v) {  // position then normal, stride 24
    put<float>(buffer, {kTriangle[3 * v], kTriangle[3 * v + 1], kTriangle[3 * v + 2]});
    put<float>(buffer, {0, 0, 1});
  }
  put<std::uint8_t>(buffer, {0, 1, 2, 0});  // padded to 4
  const auto gltf =
      document(buffer,
               {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 72}, {"byteStride", 24}},
                {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 3}}},
               {{{"bufferView", 0},
                 {"componentType", 5126},
                 {"count", 3},
                 {"type", "VEC3"},
                 {"min", {0, 0, 0}},
                 {"max", {1, 1, 0}}},
                {{"bufferView", 0}, {"byteOffset", 12}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                {{"bufferView", 1}, {"componentType", 5121}, {"count", 3}, {"type", "SCALAR"}}},
               {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}});
  ScratchDir dir;
  auto mesh = loadGltf(dir.write("interleaved.gltf", gltf.dump()));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  ASSERT_EQ(mesh->vertexCount(), 3u);
  EXPECT_EQ(mesh->positions[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh->normals[2], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh->indices, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(GltfLoader, AppliesSparseValuesOverAnAccessorWithoutBufferView) {
  // POSITION has no buffer view (all zeros) and sparse entries for vertices 1 and 2;
  // unsigned-int indices; no normals, so they are computed: +Z for this winding.
  std::vector<unsigned char> buffer;
  put<std::uint32_t>(buffer, {0, 1, 2});   // indices, 12 bytes
  put<std::uint16_t>(buffer, {1, 2});      // sparse indices, 4 bytes
  put<float>(buffer, {1, 0, 0, 0, 1, 0});  // sparse values, 24 bytes
  const auto gltf = document(
      buffer,
      {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 12}},
       {{"buffer", 0}, {"byteOffset", 12}, {"byteLength", 4}},
       {{"buffer", 0}, {"byteOffset", 16}, {"byteLength", 24}}},
      {{{"componentType", 5126},
        {"count", 3},
        {"type", "VEC3"},
        {"min", {0, 0, 0}},
        {"max", {1, 1, 0}},
        {"sparse",
         {{"count", 2}, {"indices", {{"bufferView", 1}, {"componentType", 5123}}}, {"values", {{"bufferView", 2}}}}}},
       {{"bufferView", 0}, {"componentType", 5125}, {"count", 3}, {"type", "SCALAR"}}},
      {{"attributes", {{"POSITION", 0}}}, {"indices", 1}});
  ScratchDir dir;
  auto mesh = loadGltf(dir.write("sparse.gltf", gltf.dump()));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  ASSERT_EQ(mesh->vertexCount(), 3u);
  EXPECT_EQ(mesh->positions[0], glm::vec3(0, 0, 0));
  EXPECT_EQ(mesh->positions[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh->positions[2], glm::vec3(0, 1, 0));
  for (const glm::vec3& n : mesh->normals) EXPECT_NEAR(glm::distance(n, {0, 0, 1}), 0.0f, 1e-6f);
}

/// The triangle kTriangle as one float VEC3 accessor declaring `count` positions (3 is right;
/// others test the loader's checks), used by `primitive` under `nodes`.
nlohmann::json triangleDocument(std::uint64_t count, nlohmann::json primitive,
                                nlohmann::json nodes = nlohmann::json::array({{{"mesh", 0}}})) {
  std::vector<unsigned char> buffer;
  for (float f : kTriangle) put<float>(buffer, {f});
  return document(buffer, {{{"buffer", 0}, {"byteLength", 36}}},
                  {{{"bufferView", 0},
                    {"componentType", 5126},
                    {"count", count},
                    {"type", "VEC3"},
                    {"min", {0, 0, 0}},
                    {"max", {1, 1, 0}}}},
                  primitive, nodes);
}

/// A non-indexed triangle under `nodes`, written to `dir`.
Result<Mesh> loadTriangleUnder(const ScratchDir& dir, nlohmann::json nodes, int mode = 4) {
  auto primitive = nlohmann::json{{"attributes", {{"POSITION", 0}}}};
  if (mode != 4) primitive["mode"] = mode;
  const auto gltf = triangleDocument(3, primitive, nodes);
  return loadGltf(dir.write("triangle.gltf", gltf.dump()));
}

TEST(GltfLoader, ComposesNodeTransformsParentFirst) {
  // Parent translates by (10, 0, 0); child scales by 2: (1,0,0) → (12, 0, 0).
  ScratchDir dir;
  auto mesh =
      loadTriangleUnder(dir, {{{"translation", {10, 0, 0}}, {"children", {1}}}, {{"mesh", 0}, {"scale", {2, 2, 2}}}});
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  EXPECT_EQ(mesh->positions[1], glm::vec3(12, 0, 0));
  EXPECT_EQ(mesh->positions[2], glm::vec3(10, 2, 0));
  EXPECT_EQ(mesh->indices, (std::vector<std::uint32_t>{0, 1, 2}));  // generated for no indices
}

TEST(GltfLoader, MirroringNodeKeepsTrianglesFacingTheirNormals) {
  ScratchDir dir;
  auto mesh = loadTriangleUnder(dir, {{{"mesh", 0}, {"scale", {-1, 1, 1}}}});
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  const auto& p = mesh->positions;
  const auto& i = mesh->indices;
  const glm::vec3 face = glm::cross(p[i[1]] - p[i[0]], p[i[2]] - p[i[0]]);
  EXPECT_GT(glm::dot(face, mesh->normals[0]), 0.0f);
}

TEST(GltfLoader, RejectsLinePrimitivesNamingTheMode) {
  ScratchDir dir;
  auto mesh = loadTriangleUnder(dir, {{{"mesh", 0}}}, 1);
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("triangle.gltf"), std::string::npos);
  EXPECT_NE(mesh.error().message.find("LINES (1)"), std::string::npos) << mesh.error().message;
  EXPECT_NE(mesh.error().message.find("only TRIANGLES"), std::string::npos);
}

TEST(GltfLoader, RejectsTriangleStripsToo) {
  ScratchDir dir;
  auto mesh = loadTriangleUnder(dir, {{{"mesh", 0}}}, 5);
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("TRIANGLE_STRIP"), std::string::npos);
}

TEST(GltfLoader, MissingAccessorIsNamed) {
  const auto gltf = triangleDocument(3, {{"attributes", {{"POSITION", 0}, {"NORMAL", 7}}}});
  ScratchDir dir;
  auto mesh = loadGltf(dir.write("missing.gltf", gltf.dump()));
  ASSERT_FALSE(mesh.has_value());
  const std::string& message = mesh.error().message;
  EXPECT_NE(message.find("missing.gltf"), std::string::npos) << message;
  EXPECT_NE(message.find("accessor"), std::string::npos) << message;
  EXPECT_NE(message.find('7'), std::string::npos) << message;
}

TEST(GltfLoader, AccessorPastTheEndOfItsViewIsAnError) {
  const auto gltf = triangleDocument(4, {{"attributes", {{"POSITION", 0}}}});
  ScratchDir dir;
  auto mesh = loadGltf(dir.write("short.gltf", gltf.dump()));
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("short.gltf"), std::string::npos);
  EXPECT_NE(mesh.error().message.find("buffer view 0"), std::string::npos) << mesh.error().message;
}

// A count whose byte size wraps around 2^64 (2^62 × 12 bytes = 0 mod 2^64) or merely exceeds
// memory must be refused before anything is allocated or copied.
TEST(GltfLoader, HostileAccessorCountsAreRefusedBeforeAllocating) {
  for (const std::uint64_t count : {std::uint64_t(1) << 62, std::uint64_t(1) << 40, std::uint64_t(1) << 26}) {
    const auto gltf = triangleDocument(count, {{"attributes", {{"POSITION", 0}}}});
    ScratchDir dir;
    auto mesh = loadGltf(dir.write("huge.gltf", gltf.dump()));
    ASSERT_FALSE(mesh.has_value()) << count;
    EXPECT_NE(mesh.error().message.find("huge.gltf"), std::string::npos);
    EXPECT_NE(mesh.error().message.find(std::to_string(count)), std::string::npos) << mesh.error().message;
  }
}

// Node 0 and node 1 both list node 2 as a child: a DAG, which glTF forbids. Chained, such
// sharing would multiply the work exponentially; it is reported instead.
TEST(GltfLoader, NodeWithTwoParentsIsAnError) {
  ScratchDir dir;
  auto mesh = loadTriangleUnder(dir, {{{"children", {1, 2}}}, {{"children", {2}}}, {{"mesh", 0}}});
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("node 2 is reached twice"), std::string::npos) << mesh.error().message;
}

TEST(GltfLoader, TruncatedGlbSaysTruncated) {
  MANE_RESOLVE_OR_SKIP(head, "head/LeePerrySmith/LeePerrySmith.glb");
  const std::string bytes = testing::readFile(head);
  ScratchDir dir;
  for (std::size_t keep : {std::size_t{10}, std::size_t{1000}, bytes.size() - 1}) {
    SCOPED_TRACE(keep);
    auto mesh = loadGltf(dir.write("cut.glb", bytes.substr(0, keep)));
    ASSERT_FALSE(mesh.has_value());
    EXPECT_NE(mesh.error().message.find("cut.glb"), std::string::npos);
    EXPECT_NE(mesh.error().message.find("truncated"), std::string::npos) << mesh.error().message;
  }
}

TEST(GltfLoader, BadJsonNamesTheFile) {
  ScratchDir dir;
  auto mesh = loadGltf(dir.write("bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ }"));
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("bad.gltf"), std::string::npos);
  EXPECT_NE(mesh.error().message.find("not a valid glTF"), std::string::npos) << mesh.error().message;
}

TEST(GltfLoader, MissingExternalBufferIsAnError) {
  ScratchDir dir;
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", 36}, {"uri", "gone.bin"}}}},
  };
  auto mesh = loadGltf(dir.write("external.gltf", gltf.dump()));
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("external.gltf"), std::string::npos);
  EXPECT_NE(mesh.error().message.find("gone.bin"), std::string::npos) << mesh.error().message;
}

TEST(GltfLoader, NonExistentFile) {
  auto mesh = loadGltf("/nonexistent/mane/head.glb");
  ASSERT_FALSE(mesh.has_value());
  EXPECT_EQ(mesh.error().message, "/nonexistent/mane/head.glb: file not found");
}

}  // namespace
}  // namespace mane::scenes
