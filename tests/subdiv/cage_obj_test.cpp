// OBJ cages: the OpenSubdiv regression-shape dialect, and errors that name the line.
//
// Oracles: hand-counted contents of small inline files; the real catmark_*.obj cages from
// ../shared/assets (counts of their v/vt/f/t lines, taken with grep).

#include <string>

#include <gtest/gtest.h>

#include "tests/scenes/test_support.hpp"
#include "subdiv/cage_obj.hpp"

namespace mane::subdiv {
namespace {

// A cube with one texture coordinate per corner of the unfolded cross, a crease and a corner.
constexpr const char* kTaggedCube = R"(# cube
v -1 -1  1
v  1 -1  1
v -1  1  1
v  1  1  1
v -1  1 -1
v  1  1 -1
v -1 -1 -1
v  1 -1 -1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
s off
f 1/1/1 2/2/1 4/3/1 3/4/1
f 3/1 4/2 6/3 5/4
f 5/1/1 6/2/1 8/3/1 7/4/1
f -2/1 -1/2 2/3 1/4
f 2/1 8/2 6/3 4/4
f 7/1 1/2 3/3 5/4
t crease 2/1/0 0 1 3.5
t crease 3/2/0 2 3 5 1 2
t corner 1/1/0 7 4
t interpolateboundary 1/0/0 1
)";

std::string errorOf(const std::string& text) {
  auto cage = parseCageObj(text, "test.obj");
  return cage ? std::string("(no error)") : cage.error().message;
}

TEST(CageObj, ReadsPositionsFacesUvsAndTags) {
  auto cage = parseCageObj(kTaggedCube, "cube.obj");
  ASSERT_TRUE(cage.has_value()) << cage.error().message;
  EXPECT_EQ(cage->positions.size(), 8u);
  EXPECT_EQ(cage->faceSizes.size(), 6u);
  EXPECT_EQ(cage->uvs.size(), 4u);
  ASSERT_EQ(cage->faceUvIndices.size(), 24u);
  EXPECT_EQ(cage->faceUvIndices[2], 2u);
  // "-2/1 -1/2 2/3 1/4" with 8 vertices read: 7, 8, 2, 1 (1-based) → 6, 7, 1, 0.
  EXPECT_EQ(cage->faceVertices[12], 6u);
  EXPECT_EQ(cage->faceVertices[13], 7u);
  ASSERT_EQ(cage->creases.size(), 3u);  // one, then a chain of three vertices → two edges
  EXPECT_FLOAT_EQ(cage->creases[0].sharpness, 3.5f);
  EXPECT_EQ(cage->creases[2].a, 3u);
  EXPECT_EQ(cage->creases[2].b, 5u);
  EXPECT_FLOAT_EQ(cage->creases[2].sharpness, 2.0f);
  ASSERT_EQ(cage->corners.size(), 1u);
  EXPECT_EQ(cage->corners[0].vertex, 7u);
  EXPECT_FLOAT_EQ(cage->corners[0].sharpness, 4.0f);
  EXPECT_EQ(cage->boundary, BoundaryInterpolation::kEdgeOnly);
}

TEST(CageObj, MalformedLinesNameTheLine) {
  const std::string header = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_NE(errorOf(header + "v 1 2 x\nf 1 2 3\n").find("test.obj:4:"), std::string::npos);
  EXPECT_NE(errorOf(header + "v 1 2\n").find("needs 3 numbers"), std::string::npos);
  EXPECT_NE(errorOf(header + "f 1 2 4\n").find("test.obj:4: vertex index 4 is out of range"), std::string::npos);
  EXPECT_NE(errorOf(header + "f 1 2 0\n").find("'0' is not a valid vertex index"), std::string::npos);
  EXPECT_NE(errorOf(header + "f 1 2\n").find("at least 3 vertices"), std::string::npos);
  EXPECT_NE(errorOf(header + "vt 0 0\nf 1/1 2 3\n").find("test.obj:5: some corners"), std::string::npos);
  EXPECT_NE(errorOf(header + "vt 0 0\nf 1/1 2/1 3/1\nv 1 1 0\nf 2 4 3\n").find("test.obj:7: this face has no texture"),
            std::string::npos);
  EXPECT_NE(errorOf(header + "bogus 1\n").find("test.obj:4: unknown statement 'bogus'"), std::string::npos);
  EXPECT_NE(errorOf(header + "f 1 2 3\nt hole 1/0/0 0\n").find("test.obj:5: unsupported tag 'hole'"),
            std::string::npos);
  EXPECT_NE(errorOf(header + "f 1 2 3\nt crease 2/1/0 0 1\n").find("announces 3 arguments but has 2"),
            std::string::npos);
  EXPECT_NE(errorOf(header + "f 1 2 3\nt crease 2/1/0 0 1 nan\n").find("not a finite number"), std::string::npos);
  EXPECT_NE(errorOf(header).find("no faces"), std::string::npos);
}

TEST(CageObj, ValidationErrorsPointAtTheFaceOrTagLine) {
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 2 0\nf 1 2 3\n";
  // Zero area: three collinear vertices on line 6.
  EXPECT_NE(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 2 1 4\n").find("test.obj:6: face 1 has zero area"),
            std::string::npos);
  // Non-manifold: edge (0, 1) used by three faces; the third is on line 9.
  EXPECT_NE(errorOf(triangle + "v 0 -1 0\nv 0 0 1\nf 2 1 5\nf 1 2 6\n").find("test.obj:9: edge (0, 1)"),
            std::string::npos);
  EXPECT_NE(errorOf(triangle + "f 2 1 1\n").find("test.obj:6: face 1 uses vertex 0 twice"), std::string::npos);
  EXPECT_NE(errorOf(triangle + "t crease 2/1/0 0 3 1\n").find("test.obj:6: a crease names edge (0, 3)"),
            std::string::npos);
  EXPECT_NE(errorOf(triangle + "t corner 1/1/0 9 1\n").find("test.obj:6: a corner names vertex 9"), std::string::npos);
  EXPECT_NE(errorOf(triangle + "t corner 1/1/0 1 -2\n").find("test.obj:6: the corner at vertex 1 has sharpness"),
            std::string::npos);
}

TEST(CageObj, MissingFileIsAnError) {
  auto cage = loadCageObj("/nonexistent/cage.obj");
  ASSERT_FALSE(cage.has_value());
  EXPECT_NE(cage.error().message.find("/nonexistent/cage.obj"), std::string::npos);
}

struct RegressionShape {
  const char* name;
  std::size_t vertices, uvs, faces, creases;
};

TEST(CageObj, LoadsEveryCatmarkRegressionShape) {
  // Counts from the files themselves (grep -c '^v ' etc.); crease tags are single edges.
  const RegressionShape shapes[] = {
      {"catmark_bishop.obj", 917, 4, 968, 224}, {"catmark_cube.obj", 8, 14, 6, 0},
      {"catmark_pawn.obj", 601, 4, 588, 120},   {"catmark_pyramid.obj", 5, 8, 5, 0},
      {"catmark_rook.obj", 768, 4, 777, 280},   {"catmark_tent.obj", 16, 16, 9, 0},
      {"catmark_torus.obj", 32, 45, 32, 0},     {"catmark_torus_creases0.obj", 32, 4, 32, 8},
  };
  for (const RegressionShape& shape : shapes) {
    MANE_RESOLVE_OR_SKIP(file, std::string("subdiv/opensubdiv/") + shape.name);
    auto cage = loadCageObj(file);
    ASSERT_TRUE(cage.has_value()) << cage.error().message;
    EXPECT_EQ(cage->positions.size(), shape.vertices) << shape.name;
    EXPECT_EQ(cage->uvs.size(), shape.uvs) << shape.name;
    EXPECT_EQ(cage->faceSizes.size(), shape.faces) << shape.name;
    EXPECT_EQ(cage->creases.size(), shape.creases) << shape.name;
    EXPECT_TRUE(cage->hasUvs()) << shape.name;
  }
}

}  // namespace
}  // namespace mane::subdiv
