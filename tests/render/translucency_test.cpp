// Translucency through the Renderer (render/passes/translucency_pass.hpp), lit from
// straight behind so the face the camera sees has N·L = −1: no diffuse, no specular, the wrap
// max(0.3 − N·L, 0) clamps to 1, and with no ambient a pixel holds exactly the light's radiance
// × T(d) × albedo. References:
//  - a box: the light crosses the box's depth, so d is its side (the depth-map method exactly,
//    the voxel table between surface voxel centres, one voxel less);
//  - the cube [−1, 1]³ with a ball hollow of radius 0.5 (the voxelized-translucency paper's
//    first test object): the depth map counts the hollow, d = 2; the voxel table subtracts its
//    chord 2√(r² − x²), d = 2 − 2√(r² − x²) at a lateral offset x;
//  - skin: a 1 mm slab transmits SkinProfile::transmittance(1 mm).
// A channel's value is read back through the 8-bit sRGB output and inverted to a thickness.

#include <cmath>

#include <gtest/gtest.h>

#include "render/luts/skin_profile.hpp"
#include "render/renderer.hpp"
#include "tests/render/voxel_test_shapes.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{128, 128};
const Camera kCamera{.position = {0, 0, 6}, .target = {0, 0, 0}, .verticalFovRadians = 0.5f};
// From the surface towards the light: straight behind the objects as the camera sees them.
const DirectionalLight kBackLight{.direction = {0, 0, -1}, .color = {1, 1, 1}, .intensity = 1.0f};

// Unwelded: every triangle its own vertices with its face normal, so flat faces shade flat.
struct FlatMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;
};

FlatMesh flatShaded(const test::TriangleMesh& mesh) {
  FlatMesh flat;
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[i]];
    const glm::vec3 b = mesh.positions[mesh.indices[i + 1]];
    const glm::vec3 c = mesh.positions[mesh.indices[i + 2]];
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    for (const glm::vec3& p : {a, b, c}) {
      flat.indices.push_back(static_cast<std::uint32_t>(flat.positions.size()));
      flat.positions.push_back(p);
      flat.normals.push_back(normal);
      flat.uvs.emplace_back(0.0f);
    }
  }
  return flat;
}

double srgbDecode(std::uint8_t value) {
  const double encoded = value / 255.0;
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

class Translucency : public testing::VulkanTest {
public:
  // Renders `mesh` under the back light and returns the linear RGB of the pixel that sees `point`.
  Result<glm::dvec3> shade(const FlatMesh& mesh, const MaterialData& material, const glm::vec3& point) {
    auto renderer = Renderer::create(device(), {.extent = kExtent});
    if (!renderer) return std::unexpected(renderer.error());
    const StaticScene scene{
        .meshes = {MeshData{
            .positions = mesh.positions, .normals = mesh.normals, .uvs = mesh.uvs, .indices = mesh.indices}},
        .materials = {material}};
    if (auto set = (*renderer)->setScene(scene); !set) return std::unexpected(set.error());
    const FrameInput frame{
        .camera = kCamera, .lights = {kBackLight}, .instances = {{.mesh = 0, .material = 0}}, .ambient = glm::vec3(0)};
    if (auto rendered = (*renderer)->render(frame); !rendered) return std::unexpected(rendered.error());
    auto rgba = (*renderer)->readOutput();
    if (!rgba) return std::unexpected(rgba.error());
    const glm::vec4 clip = kCamera.projection(1.0f) * kCamera.view() * glm::vec4(point, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const auto x = static_cast<std::size_t>((ndc.x * 0.5f + 0.5f) * kExtent.width);
    const auto y = static_cast<std::size_t>((ndc.y * 0.5f + 0.5f) * kExtent.height);
    const std::size_t i = (y * kExtent.width + x) * 4;
    return glm::dvec3(srgbDecode((*rgba)[i]), srgbDecode((*rgba)[i + 1]), srgbDecode((*rgba)[i + 2]));
  }
};

// σ per channel, 1/m: light through 1–2 m keeps a few to tens of percent, well above 8-bit steps.
const glm::vec3 kExtinction(0.5f, 1.0f, 1.5f);

MaterialData translucent(TranslucencyMethod method, int voxels = 32) {
  return {.baseColor = glm::vec3(1.0f),
          .translucency = {.method = method, .extinction = kExtinction, .voxelResolution = voxels}};
}

// The thickness each channel's exp(−σ·d) stands for, averaged over the channels.
double thicknessFrom(const glm::dvec3& linear) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) sum += -std::log(linear[c]) / kExtinction[c];
  return sum / 3.0;
}

TEST_F(Translucency, DepthMapThicknessOfABoxIsItsSide) {
  const FlatMesh box = flatShaded(test::box(glm::vec3(-1.0f), glm::vec3(1.0f)));
  for (glm::vec3 point : {glm::vec3(0, 0, 1), glm::vec3(0.6f, -0.4f, 1)}) {
    auto linear = shade(box, translucent(TranslucencyMethod::kDepthMap), point);
    ASSERT_TRUE(linear.has_value()) << linear.error().message;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR((*linear)[c], std::exp(-2.0 * kExtinction[c]), 0.006) << "channel " << c;
  }
}

TEST_F(Translucency, VoxelThicknessOfABoxIsItsSideWithinAVoxel) {
  const FlatMesh box = flatShaded(test::box(glm::vec3(-1.0f), glm::vec3(1.0f)));
  const double voxel = 2.0 / 32;
  auto linear = shade(box, translucent(TranslucencyMethod::kVoxelLut), {0.3f, 0.2f, 1.0f});
  ASSERT_TRUE(linear.has_value()) << linear.error().message;
  // Between the centres of the two surface voxels: half a voxel in from each face.
  EXPECT_NEAR(thicknessFrom(*linear), 2.0 - voxel, 0.5 * voxel);
}

TEST_F(Translucency, TheVoxelTableSubtractsTheHollowAndTheDepthMapDoesNot) {
  const FlatMesh cube = flatShaded(test::combined(test::box(glm::vec3(-1.0f), glm::vec3(1.0f)),
                                                  test::sphere(glm::vec3(0.0f), 0.5f, 48, 96, /*inward=*/true)));
  const double voxel = 2.0 / 32;
  for (float x : {0.0f, 0.3f}) {
    const glm::vec3 point(x, 0.0f, 1.0f);
    auto depth = shade(cube, translucent(TranslucencyMethod::kDepthMap), point);
    auto voxels = shade(cube, translucent(TranslucencyMethod::kVoxelLut), point);
    ASSERT_TRUE(depth.has_value()) << depth.error().message;
    ASSERT_TRUE(voxels.has_value()) << voxels.error().message;
    const double hollowChord = 2.0 * std::sqrt(0.25 - double(x) * x);
    EXPECT_NEAR(thicknessFrom(*depth), 2.0, 0.02) << "x = " << x;
    EXPECT_NEAR(thicknessFrom(*voxels), 2.0 - hollowChord - voxel, 1.5 * voxel) << "x = " << x;
  }
}

TEST_F(Translucency, ThinSkinTransmitsItsProfile) {
  // A 1 mm slab, 0.2 m across, seen face on.
  const FlatMesh slab = flatShaded(test::box(glm::vec3(-0.1f, -0.1f, -0.0005f), glm::vec3(0.1f, 0.1f, 0.0005f)));
  MaterialData skin{.baseColor = glm::vec3(1.0f),
                    .shading = SurfaceShading::kSkin,
                    .translucency = {.method = TranslucencyMethod::kDepthMap}};
  auto linear = shade(slab, skin, {0.0f, 0.0f, 0.0005f});
  ASSERT_TRUE(linear.has_value()) << linear.error().message;
  const glm::dvec3 expected = SkinProfile{}.transmittance(1.0);
  // Flat skin (curvature 0) facing away from the light has no diffuse or specular of its own.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR((*linear)[c], expected[c], 0.006) << "channel " << c;
}

TEST_F(Translucency, AnOpenMeshCannotHaveAVoxelTable) {
  test::TriangleMesh quad;
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  auto linear = shade(flatShaded(quad), translucent(TranslucencyMethod::kVoxelLut), {0, 0, 0});
  ASSERT_FALSE(linear.has_value());
  EXPECT_NE(linear.error().message.find("mesh 0"), std::string::npos) << linear.error().message;
  EXPECT_NE(linear.error().message.find("voxel thickness table"), std::string::npos) << linear.error().message;
}

TEST_F(Translucency, ATableOverTheDevicesStorageBufferRangeIsAnError) {
  // The cube at N = 128: ~150,000 surface voxels, a table of tens of GB.
  const FlatMesh box = flatShaded(test::box(glm::vec3(-1.0f), glm::vec3(1.0f)));
  auto linear = shade(box, translucent(TranslucencyMethod::kVoxelLut, 128), {0, 0, 1});
  ASSERT_FALSE(linear.has_value());
  EXPECT_NE(linear.error().message.find("N = 128"), std::string::npos) << linear.error().message;
}

}  // namespace
}  // namespace mane::render
