// OBJ loader on small files written here: de-duplication, fan triangulation, and errors.

#include <gtest/gtest.h>

#include "scenes/obj_loader.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using testing::ScratchDir;

TEST(ObjLoader, QuadBecomesTwoTrianglesSharingItsFirstCorner) {
  ScratchDir dir;
  auto mesh = loadObj(dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  EXPECT_EQ(mesh->indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(mesh->normals.size(), 4u);
  EXPECT_NEAR(mesh->normals[0].z, 1.0f, 1e-6f);  // counter-clockwise seen from +Z
}

TEST(ObjLoader, SplitsVerticesOnlyWhereTheUvDiffers) {
  // Two triangles share positions 1 and 3; the shared edge has the same uv on one corner
  // and a different one on the other: 4 positions → 5 vertices.
  ScratchDir dir;
  auto mesh = loadObj(dir.write("seam.obj",
                                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                                "f 1/1 2/2 3/3\nf 1/1 3/5 4/4\n"));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  EXPECT_EQ(mesh->vertexCount(), 5u);
  EXPECT_EQ(mesh->triangleCount(), 2u);
  ASSERT_EQ(mesh->uvs.size(), 5u);
  EXPECT_EQ(mesh->uvs[1], glm::vec2(1.0f, 1.0f));  // OBJ v flipped to image-top origin
}

TEST(ObjLoader, KeepsFileNormalsWhenEveryCornerHasOne) {
  ScratchDir dir;
  auto mesh = loadObj(dir.write("normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -1\nf 1//1 2//1 3//1\n"));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  EXPECT_EQ(mesh->normals[0], glm::vec3(0, 0, -1));  // the file's, not the computed +Z
}

TEST(ObjLoader, OutOfRangeVertexIndexIsAnErrorNamingFileAndFace) {
  ScratchDir dir;
  auto mesh = loadObj(dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n"));
  ASSERT_FALSE(mesh.has_value());
  const std::string& message = mesh.error().message;
  EXPECT_NE(message.find("broken.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("face 2"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 9"), std::string::npos) << message;
  EXPECT_NE(message.find("out of range"), std::string::npos) << message;
}

TEST(ObjLoader, OutOfRangeIndexInALargePolygonDoesNotCrash) {
  ScratchDir dir;
  auto mesh = loadObj(dir.write("pentagon.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 40 50\n"));
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("vertex 40"), std::string::npos) << mesh.error().message;
}

TEST(ObjLoader, OutOfRangeNormalIndexIsAnError) {
  ScratchDir dir;
  auto mesh = loadObj(dir.write("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n"));
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("normal 2"), std::string::npos) << mesh.error().message;
}

TEST(ObjLoader, FileWithoutFacesIsAnError) {
  ScratchDir dir;
  auto mesh = loadObj(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n"));
  ASSERT_FALSE(mesh.has_value());
  EXPECT_NE(mesh.error().message.find("points.obj"), std::string::npos);
  EXPECT_NE(mesh.error().message.find("no faces"), std::string::npos) << mesh.error().message;
}

TEST(ObjLoader, NonExistentFile) {
  auto mesh = loadObj("/nonexistent/mane/bunny.obj");
  ASSERT_FALSE(mesh.has_value());
  EXPECT_EQ(mesh.error().message, "/nonexistent/mane/bunny.obj: file not found");
}

TEST(MeshLoader, DispatchesByExtensionCaseInsensitively) {
  ScratchDir dir;
  auto mesh = loadMesh(dir.write("TRI.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  EXPECT_EQ(mesh->triangleCount(), 1u);
  auto other = loadMesh(dir.write("mesh.ply", "ply\n"));
  ASSERT_FALSE(other.has_value());
  EXPECT_NE(other.error().message.find("mesh.ply"), std::string::npos);
  EXPECT_NE(other.error().message.find("unsupported mesh format"), std::string::npos);
}

}  // namespace
}  // namespace mane::scenes
