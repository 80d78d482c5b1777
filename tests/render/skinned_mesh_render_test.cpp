// A skinned, morphing mesh drawn by the Renderer (MeshData::skinning, Renderer::updateSkinning):
// deformed on the GPU (render/passes/skinning_pass.hpp) into the vertex buffer every pass draws.
//
// Reference: the same mesh deformed on the CPU by physics::SkinnedMesh::deform and drawn as a
// dynamic mesh (Renderer::updateMesh), with the same material, model matrix, camera and light.
// Both paths compute the same formula in float in the same order; they differ by float rounding
// (fused multiply-adds, the driver's own arithmetic), a few ulps of a position, which can flip
// a pixel on a silhouette or move a shade by one step of 8 bits. The tolerance: at least 99.9 %
// of the pixels within 2/255 in every channel (measured on lavapipe: every pixel equal, for both
// methods and both materials; the test prints its figures). That the bent picture really is
// bent: over 3 % of its pixels differ from the bind-pose picture's by more than 24/255
// (measured: about 18 %).
//
// The rig: a tube along x from −0.8 to 0.8 m, radius 0.15 m, on two joints; joint 1 bends the
// right half about the z axis through the origin, the middle blended over x ∈ [−0.25, 0.25]. A
// morph target bulges the tube in its middle. Both joints also lift the tube by 0.1 m: the
// joint matrices already carry the character into the world, and the instance's model matrix
// (a turn about y and a shift) is applied after them.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "physics/skinning.hpp"
#include "render/png.hpp"
#include "render/renderer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{192, 128};
constexpr int kRings = 24;     // along the tube
constexpr int kSegments = 16;  // around it

struct Tube {
  physics::SkinnedMeshData skin;
  std::vector<glm::vec2> uvs;
};

Tube makeTube(physics::SkinningMethod method) {
  Tube tube;
  physics::SkinnedMeshData& d = tube.skin;
  d.influencesPerVertex = 2;
  d.jointCount = 2;
  d.method = method;
  physics::MorphTarget bulge{.name = "bulge"};
  for (int r = 0; r <= kRings; ++r) {
    const float x = -0.8f + 1.6f * float(r) / kRings;
    const float t = std::clamp((x + 0.25f) / 0.5f, 0.0f, 1.0f);
    const float toJoint1 = t * t * (3.0f - 2.0f * t);
    for (int s = 0; s <= kSegments; ++s) {
      const float angle = 2.0f * std::numbers::pi_v<float> * float(s) / kSegments;
      const glm::vec3 radial(0.0f, std::cos(angle), std::sin(angle));
      d.positions.push_back(glm::vec3(x, 0.0f, 0.0f) + 0.15f * radial);
      d.normals.push_back(radial);
      tube.uvs.emplace_back(float(s) / kSegments, float(r) / kRings);
      d.joints.insert(d.joints.end(), {0u, 1u});
      d.weights.insert(d.weights.end(), {1.0f - toJoint1, toJoint1});
      bulge.positionDeltas.push_back(0.08f * std::max(0.0f, 1.0f - std::abs(x) / 0.5f) * radial);
    }
  }
  d.morphTargets.push_back(bulge);
  for (int r = 0; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      const auto at = [](int ring, int segment) { return std::uint32_t(ring * (kSegments + 1) + segment); };
      // Counter-clockwise seen from outside.
      d.indices.insert(d.indices.end(), {at(r, s), at(r + 1, s + 1), at(r + 1, s), at(r, s), at(r, s + 1),
                                         at(r + 1, s + 1)});
    }
  return tube;
}

GpuSkinnedMesh toGpu(const physics::SkinnedMeshData& d) {
  GpuSkinnedMesh gpu{.positions = d.positions,
                     .normals = d.normals,
                     .tangents = d.tangents,
                     .influencesPerVertex = std::uint32_t(d.influencesPerVertex),
                     .joints = d.joints,
                     .weights = d.weights,
                     .jointCount = std::uint32_t(d.jointCount),
                     .method = d.method == physics::SkinningMethod::DualQuaternion ? GpuSkinningMethod::DualQuaternion
                                                                                    : GpuSkinningMethod::LinearBlend};
  for (const physics::MorphTarget& target : d.morphTargets)
    gpu.morphTargets.push_back({target.positionDeltas, target.normalDeltas, target.tangentDeltas});
  return gpu;
}

/// Joint 1 bent by 70° about z, both lifted 0.1 m.
std::vector<glm::mat4> bentJoints() {
  const glm::mat4 lift = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.1f, 0.0f));
  return {lift, lift * glm::rotate(glm::mat4(1.0f), 70.0f * std::numbers::pi_v<float> / 180.0f, glm::vec3(0, 0, 1))};
}
const std::vector<float> kMorphWeights{0.8f};

struct Comparison {
  double withinTolerance = 0.0;  ///< share of pixels whose channels all differ by ≤ 2
  int maxDifference = 0;
  double clearlyDifferent = 0.0;  ///< share whose largest channel difference is > 24
};

Comparison compare(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  Comparison c;
  std::size_t within = 0, different = 0;
  const std::size_t pixels = a.size() / 4;
  for (std::size_t p = 0; p < pixels; ++p) {
    int largest = 0;
    for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(int(a[4 * p + k]) - int(b[4 * p + k])));
    within += largest <= 2;
    different += largest > 24;
    c.maxDifference = std::max(c.maxDifference, largest);
  }
  c.withinTolerance = double(within) / double(pixels);
  c.clearlyDifferent = double(different) / double(pixels);
  return c;
}

class SkinnedMeshRender : public testing::VulkanTest {
protected:
  void SetUp() override {
    VulkanTest::SetUp();
    auto created = Renderer::create(device(), {.extent = kExtent});
    ASSERT_TRUE(created.has_value()) << created.error().message;
    renderer = std::move(*created);
  }

  std::vector<std::uint8_t> render(std::size_t mesh, std::size_t material) {
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(0.05f, -0.1f, 0.0f)) *
                            glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0.0f, 1.0f, 0.0f));
    const FrameInput frame{.camera = {.position = {0.0f, 0.2f, 2.2f}, .target = {0.0f, 0.1f, 0.0f}},
                           .lights = {{.direction = glm::normalize(glm::vec3(0.3f, 0.6f, 1.0f)), .intensity = 1.5f}},
                           .instances = {{.mesh = mesh, .material = material, .model = model}},
                           .ambient = glm::vec3(0.05f)};
    auto timings = renderer->render(frame);
    EXPECT_TRUE(timings.has_value()) << timings.error().message;
    auto rgba = renderer->readOutput();
    EXPECT_TRUE(rgba.has_value());
    return rgba ? *rgba : std::vector<std::uint8_t>{};
  }

  std::unique_ptr<Renderer> renderer;
};

// Materials: Lambert (forward surfaces) and pre-integrated skin (the deferred G-buffer).
TEST_F(SkinnedMeshRender, TheGpuSkinnedMeshMatchesTheCpuDeformedOneAndIsNotTheBindPose) {
  for (const auto method : {physics::SkinningMethod::LinearBlend, physics::SkinningMethod::DualQuaternion}) {
    const bool dqs = method == physics::SkinningMethod::DualQuaternion;
    SCOPED_TRACE(dqs ? "dual quaternions" : "linear blend");
    const Tube tube = makeTube(method);
    auto cpu = physics::SkinnedMesh::create(tube.skin);
    ASSERT_TRUE(cpu) << cpu.error().message;
    const GpuSkinnedMesh gpu = toGpu(cpu->data());
    const MeshData skinned{.positions = tube.skin.positions,
                           .normals = tube.skin.normals,
                           .uvs = tube.uvs,
                           .indices = tube.skin.indices,
                           .skinning = &gpu};
    MeshData dynamic = skinned;
    dynamic.skinning = nullptr;
    dynamic.dynamic = true;
    const StaticScene scene{
        .meshes = {skinned, dynamic},
        .materials = {{.baseColor = {0.8f, 0.6f, 0.5f}},
                      {.baseColor = {0.8f, 0.6f, 0.5f}, .shading = SurfaceShading::kSkin}}};
    ASSERT_TRUE(renderer->setScene(scene).has_value());

    for (std::size_t material = 0; material < 2; ++material) {
      SCOPED_TRACE(material == 0 ? "Lambert" : "skin");
      const std::vector<std::uint8_t> rest = render(0, material);
      ASSERT_TRUE(renderer->updateSkinning(0, bentJoints(), kMorphWeights).has_value());
      const std::vector<std::uint8_t> onGpu = render(0, material);
      physics::DeformedSurface deformed;
      ASSERT_TRUE(cpu->deform(bentJoints(), kMorphWeights, deformed));
      ASSERT_TRUE(renderer->updateMesh(1, deformed.positions, deformed.normals).has_value());
      const std::vector<std::uint8_t> onCpu = render(1, material);
      // Back to the bind pose for the next material's rest picture.
      const std::vector<glm::mat4> identity(2, glm::mat4(1.0f));
      ASSERT_TRUE(renderer->updateSkinning(0, identity, std::vector<float>{0.0f}).has_value());

      std::string name = "/tmp/mane_skinned_";
      name += dqs ? "dqs_" : "lbs_";
      name += material == 0 ? "lambert" : "skin";
      ASSERT_TRUE(writePng(name + "_gpu.png", kExtent.width, kExtent.height, onGpu));
      ASSERT_TRUE(writePng(name + "_cpu.png", kExtent.width, kExtent.height, onCpu));
      ASSERT_TRUE(writePng(name + "_rest.png", kExtent.width, kExtent.height, rest));

      const Comparison same = compare(onGpu, onCpu);
      const Comparison bent = compare(onGpu, rest);
      std::printf("%s %s: GPU vs CPU %.4f %% of pixels within 2/255, max difference %d; bent vs rest %.2f %% differ "
                  "by more than 24/255\n",
                  dqs ? "DQS" : "LBS", material == 0 ? "Lambert" : "skin", 100.0 * same.withinTolerance,
                  same.maxDifference, 100.0 * bent.clearlyDifferent);
      EXPECT_GE(same.withinTolerance, 0.999);
      EXPECT_GE(bent.clearlyDifferent, 0.03) << "the bent tube must not be drawn in its bind pose";
    }
  }
}

TEST_F(SkinnedMeshRender, BadSkinningRequestsAreErrors) {
  const Tube tube = makeTube(physics::SkinningMethod::DualQuaternion);
  const GpuSkinnedMesh gpu = toGpu(tube.skin);
  const MeshData skinned{.positions = tube.skin.positions,
                         .normals = tube.skin.normals,
                         .uvs = tube.uvs,
                         .indices = tube.skin.indices,
                         .skinning = &gpu};
  MeshData plain = skinned;
  plain.skinning = nullptr;
  ASSERT_TRUE(renderer->setScene({.meshes = {skinned, plain}, .materials = {{}}}).has_value());
  const auto message = [](const Result<void>& result) { return result ? std::string() : result.error().message; };
  const std::vector<glm::mat4> joints = bentJoints();

  EXPECT_NE(message(renderer->updateSkinning(2, joints, kMorphWeights)).find("mesh 2 is not a skinned mesh"),
            std::string::npos);
  EXPECT_NE(message(renderer->updateSkinning(1, joints, kMorphWeights)).find("mesh 1 is not a skinned mesh"),
            std::string::npos);
  const std::string counts = message(renderer->updateSkinning(0, std::vector<glm::mat4>(3), kMorphWeights));
  EXPECT_NE(counts.find("2 joint matrices and 1 morph weights; got 3 and 1"), std::string::npos) << counts;
  std::vector<glm::mat4> nan = joints;
  nan[1][3][0] = std::nanf("");
  EXPECT_NE(message(renderer->updateSkinning(0, nan, kMorphWeights)).find("joint matrix 1 has a NaN"),
            std::string::npos);
  EXPECT_NE(message(renderer->updateSkinning(0, joints, std::vector<float>{INFINITY})).find("NaN or infinite"),
            std::string::npos);
  std::vector<glm::mat4> mirrored = joints;
  mirrored[0] = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  EXPECT_NE(message(renderer->updateSkinning(0, mirrored, kMorphWeights)).find("mirrors"), std::string::npos);
  EXPECT_NE(message(renderer->updateMesh(0, tube.skin.positions, tube.skin.normals)).find("not a dynamic mesh"),
            std::string::npos);
  EXPECT_NE(message(renderer->replaceMesh(0, plain)).find("skinned"), std::string::npos);

  // A skinned mesh's bind pose must come with as many positions and normals as the skin has.
  const MeshData truncated{.positions = std::span(tube.skin.positions).first(10),
                           .normals = std::span(tube.skin.normals).first(10),
                           .skinning = &gpu};
  EXPECT_NE(message(renderer->setScene({.meshes = {truncated}, .materials = {{}}})).find("a skinned mesh needs"),
            std::string::npos);
}

// Fur grown on a skinned mesh follows it: the shells and fins draw the deformed vertices, and the
// fins' silhouette test and the fur's shadow strands take the deformed pose (FurPass::setPose).
// Reference: the same fur on a static mesh whose bind pose is the CPU-deformed tube. Their fur
// differs slightly by construction: the mean edge length (the shadow strands' width) is measured
// on each mesh's own bind pose, and a fin on an edge seen exactly edge-on can flip with a few
// ulps of position. Tolerance: 97 % of the pixels within 8/255 (measured on lavapipe: 99.4 %; the
// two pictures show the same bent, furred tube). Each frame draws one of the two furs, and only
// the drawn one may cast a shadow: the other's, left from the frame before, would darken it.
TEST_F(SkinnedMeshRender, FurOnASkinnedMeshFollowsIt) {
  const Tube tube = makeTube(physics::SkinningMethod::LinearBlend);
  auto cpu = physics::SkinnedMesh::create(tube.skin);
  ASSERT_TRUE(cpu) << cpu.error().message;
  const GpuSkinnedMesh gpu = toGpu(cpu->data());
  physics::DeformedSurface deformed;
  ASSERT_TRUE(cpu->deform(bentJoints(), kMorphWeights, deformed));
  // A photo of speckled fur: luminance from a hash of the texel.
  std::vector<std::uint8_t> rgba(64 * 64 * 4);
  for (std::uint32_t i = 0; i < 64 * 64; ++i) {
    const std::uint32_t hash = (i * 2654435761u) >> 24;
    rgba[4 * i] = std::uint8_t(hash);
    rgba[4 * i + 1] = std::uint8_t(hash * 3 / 4);
    rgba[4 * i + 2] = std::uint8_t(hash / 2);
    rgba[4 * i + 3] = 255;
  }
  const MaterialData fur{.albedo = TextureData{64, 64, rgba},
                         .shading = SurfaceShading::kFur,
                         .fur = {.layers = 8, .thickness = 0.03f}};
  const StaticScene scene{.meshes = {{.positions = tube.skin.positions,
                                      .normals = tube.skin.normals,
                                      .uvs = tube.uvs,
                                      .indices = tube.skin.indices,
                                      .skinning = &gpu},
                                     {.positions = deformed.positions,
                                      .normals = deformed.normals,
                                      .uvs = tube.uvs,
                                      .indices = tube.skin.indices}},
                          .materials = {fur},
                          .furs = {{.mesh = 0, .material = 0}, {.mesh = 1, .material = 0}}};
  ASSERT_TRUE(renderer->setScene(scene).has_value());
  const std::vector<std::uint8_t> rest = render(0, 0);
  ASSERT_TRUE(renderer->updateSkinning(0, bentJoints(), kMorphWeights).has_value());
  const std::vector<std::uint8_t> onGpu = render(0, 0);
  const std::vector<std::uint8_t> onCpu = render(1, 0);
  ASSERT_TRUE(writePng("/tmp/mane_skinned_fur_gpu.png", kExtent.width, kExtent.height, onGpu));
  ASSERT_TRUE(writePng("/tmp/mane_skinned_fur_cpu.png", kExtent.width, kExtent.height, onCpu));
  ASSERT_TRUE(writePng("/tmp/mane_skinned_fur_rest.png", kExtent.width, kExtent.height, rest));

  std::size_t within = 0;
  for (std::size_t p = 0; p < onGpu.size() / 4; ++p) {
    int largest = 0;
    for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(int(onGpu[4 * p + k]) - int(onCpu[4 * p + k])));
    within += largest <= 8;
  }
  const double share = double(within) / double(onGpu.size() / 4);
  const Comparison bent = compare(onGpu, rest);
  std::printf("fur: GPU vs CPU %.4f %% of pixels within 8/255; bent vs rest %.2f %% differ by more than 24/255\n",
              100.0 * share, 100.0 * bent.clearlyDifferent);
  EXPECT_GE(share, 0.97);
  EXPECT_GE(bent.clearlyDifferent, 0.03);
}

}  // namespace
}  // namespace mane::render
