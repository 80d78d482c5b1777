// Renderer::replaceMesh: a static mesh's triangles replaced between frames by others with
// different vertex and index counts (a subdivision surface tessellated again for a new view,
// scenes::World::refineForCamera). The picture must follow the new triangles exactly: pixels
// the new mesh covers are lit as Lambert predicts in closed form (white, light along the
// normal, no ambient: sRGB(intensity)), pixels it left go back to the background; what the
// surface pass and the texture-space skin derived from the old mesh must go with it (a stale
// index or vertex count would draw the old shape or read past the new buffers, which the
// validation layers report).

#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "render/renderer.hpp"
#include "tests/render/voxel_test_shapes.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{96, 64};
// The camera at z = 2 looks at the origin with a 0.7 rad field of view: the plane z = 0 spans
// x ∈ ±1.09, y ∈ ±0.73. Columns 24 and 72 of row 32 look at x ≈ ∓0.55, y ≈ 0.
constexpr int kLeftColumn = 24;
constexpr int kRightColumn = 72;
constexpr int kRow = 32;

/// Quads in the plane z = 0 facing +z, each x ∈ [x0, x1], y ∈ [−0.5, 0.5], with uvs over the quad.
struct Quads {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;

  Quads& add(float x0, float x1) {
    const auto first = static_cast<std::uint32_t>(positions.size());
    positions.insert(positions.end(), {{x0, -0.5f, 0.0f}, {x1, -0.5f, 0.0f}, {x1, 0.5f, 0.0f}, {x0, 0.5f, 0.0f}});
    normals.insert(normals.end(), 4, glm::vec3(0.0f, 0.0f, 1.0f));
    uvs.insert(uvs.end(), {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}});
    indices.insert(indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    return *this;
  }
  MeshData data() const { return {.positions = positions, .normals = normals, .uvs = uvs, .indices = indices}; }
};

/// Per vertex, the direction from the centre of `mesh`'s box: smooth normals, +z on the front.
std::vector<glm::vec3> boxNormals(const test::TriangleMesh& mesh, const glm::vec3& centre) {
  std::vector<glm::vec3> normals;
  for (const glm::vec3& p : mesh.positions) normals.push_back(glm::normalize(p - centre));
  return normals;
}

double srgbEncode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

class ReplaceMesh : public testing::VulkanTest {
protected:
  static constexpr float kIntensity = 0.8f;

  void SetUp() override {
    VulkanTest::SetUp();
    auto created = Renderer::create(device(), {.extent = kExtent});
    ASSERT_TRUE(created.has_value()) << created.error().message;
    renderer = std::move(*created);
  }

  /// Renders the scene's mesh 0 with material 0 and returns the red channel at (column, kRow).
  std::array<int, 2> renderRedAt(int left, int right) {
    const FrameInput frame{.camera = {.position = {0, 0, 2}, .target = {0, 0, 0}},
                           .lights = {{.direction = {0, 0, 1}, .intensity = kIntensity}},
                           .instances = {{.mesh = 0, .material = 0}},
                           .ambient = glm::vec3(0.0f)};
    auto timings = renderer->render(frame);
    EXPECT_TRUE(timings.has_value()) << timings.error().message;
    auto rgba = renderer->readOutput();
    EXPECT_TRUE(rgba.has_value());
    const auto red = [&](int column) { return int((*rgba)[(std::size_t(kRow) * kExtent.width + column) * 4]); };
    return {red(left), red(right)};
  }

  const int lit = int(std::lround(255.0 * srgbEncode(kIntensity)));
  const int background = int(std::lround(255.0 * srgbEncode(FrameInput{}.background.r)));
  std::unique_ptr<Renderer> renderer;
};

// Left quad (4 vertices, 6 indices) → both quads (8, 12) → one triangle on the right (3, 3).
TEST_F(ReplaceMesh, TheNewTrianglesAreDrawnWhateverTheirCounts) {
  const Quads left = Quads().add(-1.0f, -0.1f);
  const StaticScene scene{.meshes = {left.data()}, .materials = {{.baseColor = glm::vec3(1.0f)}}};
  ASSERT_TRUE(renderer->setScene(scene).has_value());
  auto shot = renderRedAt(kLeftColumn, kRightColumn);
  EXPECT_NEAR(shot[0], lit, 1);
  EXPECT_NEAR(shot[1], background, 1);

  const Quads both = Quads().add(-1.0f, -0.1f).add(0.1f, 1.0f);
  ASSERT_TRUE(renderer->replaceMesh(0, both.data()).has_value());
  shot = renderRedAt(kLeftColumn, kRightColumn);
  EXPECT_NEAR(shot[0], lit, 1);
  EXPECT_NEAR(shot[1], lit, 1) << "the second quad is drawn";

  const std::vector<glm::vec3> triangle{{0.1f, -0.5f, 0.0f}, {1.0f, -0.5f, 0.0f}, {0.1f, 0.5f, 0.0f}};
  const std::vector<glm::vec3> normals(3, glm::vec3(0.0f, 0.0f, 1.0f));
  const std::vector<std::uint32_t> corners{0, 1, 2};
  ASSERT_TRUE(renderer->replaceMesh(0, {.positions = triangle, .normals = normals, .indices = corners}).has_value());
  shot = renderRedAt(kLeftColumn, kRightColumn - 16);  // x ≈ 0.18, y ≈ 0: inside the triangle
  EXPECT_NEAR(shot[0], background, 1) << "the left quad is gone";
  EXPECT_NEAR(shot[1], lit, 1);
}

// Texture-space skin draws its irradiance over its own copy of the mesh: replaced too, or the
// new quad would read irradiance never written for it. With the specular term off, a uniformly
// lit quad keeps its irradiance through the blurs (render/passes/skin_diffusion_pass.hpp), so it
// shades as Lambert.
TEST_F(ReplaceMesh, TextureSpaceSkinFollowsTheNewMesh) {
  const MaterialData skin{
      .baseColor = glm::vec3(1.0f),
      .shading = SurfaceShading::kSkin,
      .skin = {.diffusion = SkinDiffusion::kTextureSpace, .irradianceSize = 256, .specularIntensity = 0.0f}};
  const Quads left = Quads().add(-1.0f, -0.1f);
  ASSERT_TRUE(renderer->setScene({.meshes = {left.data()}, .materials = {skin}}).has_value());
  auto shot = renderRedAt(kLeftColumn, kRightColumn);
  EXPECT_NEAR(shot[1], background, 1);
  const Quads right = Quads().add(0.1f, 1.0f).add(2.0f, 3.0f);  // the second off screen
  ASSERT_TRUE(renderer->replaceMesh(0, right.data()).has_value());
  shot = renderRedAt(kLeftColumn, kRightColumn);
  EXPECT_NEAR(shot[0], background, 1);
  EXPECT_NEAR(shot[1], lit, 2);
}

// A voxel-translucent mesh's thickness table belongs to its triangles: replacing the mesh drops
// it, and the next frame builds one for the new triangles (a table of the old, smaller box
// would leave the new one's far half without thickness; here the check is that the frame
// renders, under validation, and shows the new box).
TEST_F(ReplaceMesh, AVoxelTranslucentMeshGetsANewThicknessTable) {
  const MaterialData amber{.baseColor = glm::vec3(1.0f),
                           .translucency = {.method = TranslucencyMethod::kVoxelLut, .voxelResolution = 12}};
  const test::TriangleMesh small = test::box({-0.9f, -0.3f, -0.3f}, {-0.2f, 0.3f, 0.3f});
  const std::vector<glm::vec3> smallNormals = boxNormals(small, {-0.55f, 0.0f, 0.0f});
  ASSERT_TRUE(
      renderer
          ->setScene({.meshes = {{.positions = small.positions, .normals = smallNormals, .indices = small.indices}},
                      .materials = {amber}})
          .has_value());
  auto shot = renderRedAt(kLeftColumn, kRightColumn);
  EXPECT_GT(shot[0], background + 10);
  EXPECT_NEAR(shot[1], background, 1);
  const test::TriangleMesh wide = test::box({-0.9f, -0.3f, -0.3f}, {0.9f, 0.3f, 0.3f});
  const std::vector<glm::vec3> wideNormals = boxNormals(wide, glm::vec3(0.0f));
  ASSERT_TRUE(renderer->replaceMesh(0, {.positions = wide.positions, .normals = wideNormals, .indices = wide.indices})
                  .has_value());
  shot = renderRedAt(kLeftColumn, kRightColumn);
  EXPECT_GT(shot[1], background + 10) << "the wider box is drawn";
}

TEST_F(ReplaceMesh, BadRequestsAreErrorsThatNameTheMesh) {
  const Quads left = Quads().add(-1.0f, -0.1f);
  MeshData cloth = left.data();
  cloth.dynamic = true;
  ASSERT_TRUE(renderer->setScene({.meshes = {left.data(), cloth}, .materials = {{}}}).has_value());
  auto missing = renderer->replaceMesh(2, left.data());
  ASSERT_FALSE(missing.has_value());
  EXPECT_NE(missing.error().message.find("no mesh 2"), std::string::npos) << missing.error().message;
  auto dynamic = renderer->replaceMesh(1, left.data());
  ASSERT_FALSE(dynamic.has_value());
  EXPECT_NE(dynamic.error().message.find("mesh 1 is dynamic"), std::string::npos) << dynamic.error().message;
  const std::vector<std::uint32_t> past{0, 1, 9};
  auto broken = renderer->replaceMesh(0, {.positions = left.positions, .indices = past});
  ASSERT_FALSE(broken.has_value());
  EXPECT_NE(broken.error().message.find("mesh 0: index 2 is 9"), std::string::npos) << broken.error().message;
  const std::vector<float> curvatures{1.0f};
  auto counts =
      renderer->replaceMesh(0, {.positions = left.positions, .indices = left.indices, .curvatures = curvatures});
  ASSERT_FALSE(counts.has_value());
  EXPECT_NE(counts.error().message.find("1 curvatures for 4 positions"), std::string::npos) << counts.error().message;
  // A failed replacement leaves the mesh as it was.
  EXPECT_NEAR(renderRedAt(kLeftColumn, kRightColumn)[0], lit, 1);
}

}  // namespace
}  // namespace mane::render
