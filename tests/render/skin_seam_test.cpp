// Texture-space diffusion across uv seams (render/passes/skin_uv_seams.hpp) on a real head:
// LeePerrySmith (../shared/assets/head), at nalu's scale, lit by one directional light and an
// ambient term. A point on a seam edge has two places in the irradiance map, one per side; the
// skin there is one surface, so both places must hold the same diffused irradiance, which is
// what the final pass reads on either side of the seam. The measure: at three points along
// every seam edge, |E_a − E_b| / max(E_a, E_b) per RGB channel, as the final pass samples the
// map (bilinear, at the edge's uv on each side); against the same head without skirts.
//
// The seam edges themselves are checked against an independent count: 375 on this mesh, from a
// brute-force script over the file's accessors (every pair of triangles sharing two welded
// positions, compared by uv).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/passes/skin_diffusion_pass.hpp"
#include "render/passes/skinning_pass.hpp"
#include "render/passes/skin_uv_seams.hpp"
#include "scenes/gltf_loader.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

using SkinSeamTest = testing::VulkanTest;

// LeePerrySmith, as loaded from the shared assets (skipped where they are not installed).
class SkinSeamHead : public SkinSeamTest {
protected:
  void SetUp() override {
    SkinSeamTest::SetUp();
    MANE_RESOLVE_OR_SKIP(file, "head/LeePerrySmith/LeePerrySmith.glb");
    auto loaded = scenes::loadGltf(file);
    ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
    head = std::move(*loaded);
  }
  MeshData meshData() const {
    return {.positions = head.positions, .normals = head.normals, .uvs = head.uvs, .indices = head.indices};
  }

  scenes::Mesh head;
};

constexpr std::uint32_t kSize = 1024;

// `map` (kSize², row-major) sampled as a linear, clamp-to-edge sampler does at uv.
glm::vec3 bilinear(const std::vector<glm::vec4>& map, glm::vec2 uv) {
  const glm::vec2 texel = uv * float(kSize) - 0.5f;
  const glm::ivec2 base = glm::ivec2(glm::floor(texel));
  const glm::vec2 f = texel - glm::vec2(base);
  const auto at = [&](int x, int y) {
    x = std::clamp(x, 0, int(kSize) - 1);
    y = std::clamp(y, 0, int(kSize) - 1);
    return glm::vec3(map[std::size_t(y) * kSize + std::size_t(x)]);
  };
  return glm::mix(glm::mix(at(base.x, base.y), at(base.x + 1, base.y), f.x),
                  glm::mix(at(base.x, base.y + 1), at(base.x + 1, base.y + 1), f.x), f.y);
}

// The goal: the two sides within 3 % of the irradiance.
constexpr double kGoal = 0.03;

struct Mismatch {
  double over = 0.0;  // the share of seam points (and channels) past kGoal
  double mean = 0.0, p95 = 0.0, worst = 0.0;
};

Mismatch measure(const std::vector<glm::vec4>& map, const std::vector<UvSeamEdge>& seams,
                 std::span<const glm::vec2> uvs) {
  std::vector<double> values;
  for (const UvSeamEdge& seam : seams) {
    // A side squashed in uv (the bust's underside maps to one point) has no texels to match.
    const auto texels = [&](int side) {
      return glm::distance(uvs[seam.ends[side][0]], uvs[seam.ends[side][1]]) * kSize;
    };
    if (texels(0) < 0.25f || texels(1) < 0.25f) continue;
    for (const float t : {1.0f / 6.0f, 0.5f, 5.0f / 6.0f}) {
      const auto side = [&](int s) { return bilinear(map, glm::mix(uvs[seam.ends[s][0]], uvs[seam.ends[s][1]], t)); };
      const glm::vec3 a = side(0), b = side(1);
      for (int c = 0; c < 3; ++c) values.push_back(std::abs(a[c] - b[c]) / std::max({a[c], b[c], 1e-6f}));
    }
  }
  Mismatch result;
  if (values.empty()) return result;
  for (const double v : values) result.over += v > kGoal ? 1.0 / double(values.size()) : 0.0;
  std::ranges::sort(values);
  for (const double v : values) result.mean += v / double(values.size());
  result.p95 = values[values.size() * 95 / 100];
  result.worst = values.back();
  return result;
}

TEST_F(SkinSeamHead, TheHeadsDiffusedIrradianceAgreesAcrossItsUvSeams) {
  const MeshData mesh = meshData();
  const std::vector<UvSeamEdge> seams = findUvSeams(mesh.positions, mesh.uvs, mesh.indices);
  ASSERT_EQ(seams.size(), 375u);
  const std::size_t drawn =
      textureSpaceDrawList(mesh.positions, mesh.uvs, mesh.indices, SkinDiffusionMesh::kDefaultSeamReach).size() / 3;
  std::printf("[ seams   ] %zu skirt triangles beside the mesh's %zu\n", drawn - mesh.indices.size() / 3,
              mesh.indices.size() / 3);
  // nalu.json's scale and key light (from the upper right front), and an ambient tenth of it.
  const glm::mat4 model = glm::mat4(glm::mat3(0.025f));
  const DirectionalLight key{
      .direction = glm::normalize(glm::vec3(-0.25f, 0.4f, 0.88f)), .color = glm::vec3(1.0f), .intensity = 1.0f};
  const SkinIrradianceInput input{.model = model, .lights = std::span(&key, 1), .ambient = glm::vec3(0.1f)};

  struct Result {
    Mismatch irradiance, diffused;
  };
  const auto run = [&](float seamReach) {
    auto pass = SkinDiffusionPass::create(device(), {.size = kSize});
    EXPECT_TRUE(pass.has_value()) << pass.error().message;
    auto uploaded = SkinDiffusionMesh::create(device(), mesh, seamReach);
    EXPECT_TRUE(uploaded.has_value()) << uploaded.error().message;
    Result result;
    if (!pass || !uploaded) return result;
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { pass->record(commands, *uploaded, input); });
    auto irradiance = pass->readIrradiance();
    auto diffused = pass->readDiffusedIrradiance();
    EXPECT_TRUE(irradiance && diffused);
    if (!irradiance || !diffused) return result;
    return Result{measure(*irradiance, seams, mesh.uvs), measure(*diffused, seams, mesh.uvs)};
  };
  const Result without = run(0.0f);
  const Result with = run(SkinDiffusionMesh::kDefaultSeamReach);
  const auto print = [](const char* what, const Mismatch& m) {
    std::printf(
        "[ seams   ] %-31s past 3 %%: %5.2f %% of the points; mean %5.2f %%, 95th percentile %5.2f %%, "
        "worst %5.2f %%\n",
        what, 100.0 * m.over, 100.0 * m.mean, 100.0 * m.p95, 100.0 * m.worst);
  };
  print("diffused irradiance, no skirts", without.diffused);
  print("diffused irradiance, skirts", with.diffused);
  print("irradiance, skirts", with.irradiance);

  // Before the blurs, the skirts hold the surface across each seam: the two sides agree as the
  // unfolding's accuracy allows (without skirts the border's bilinear taps read the empty map).
  EXPECT_LE(with.irradiance.mean, 0.01);
  // After them, the light crosses the seams. Measured: 37.7 % of the points past 3 % without
  // skirts, 13.2 % with (mean 6.5 % → 2.0 %). The goal, every point within 3 %, is not met: what
  // remains lies on the mouth's inner islands, packed within 10 texels of the map's top edge,
  // where no skirt fits, and in gutters narrower than the blurs, where the skirts of two
  // islands meet halfway.
  EXPECT_LE(with.diffused.mean, kGoal);
  EXPECT_LE(with.diffused.over, 0.15);
  EXPECT_LE(with.diffused.over, 0.5 * without.diffused.over);
}

TEST_F(SkinSeamHead, ASkinnedHeadIsLitWhereItsJointTurnedIt) {
  // The irradiance draw reads each vertex, skirts included, from the mesh's buffer, which the
  // skinning pass rewrites. The head bound to one joint turned by R must be lit as the unskinned
  // head whose model matrix turns it by R: the same map, up to float rounding.
  const MeshData mesh = meshData();
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(70.0f), glm::vec3(0.3f, 1.0f, 0.2f));
  const glm::mat4 scale = glm::mat4(glm::mat3(0.025f));
  const DirectionalLight key{.direction = glm::normalize(glm::vec3(-0.25f, 0.4f, 0.88f))};
  constexpr std::uint32_t kSmall = 256;

  const auto irradiance = [&](const SkinDiffusionMesh& drawn, const glm::mat4& model) {
    auto pass = SkinDiffusionPass::create(device(), {.size = kSmall});
    EXPECT_TRUE(pass.has_value()) << pass.error().message;
    if (!pass) return std::vector<glm::vec4>{};
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      pass->recordIrradiance(commands, drawn,
                             {.model = model, .lights = std::span(&key, 1), .ambient = glm::vec3(0.1f)});
    });
    auto read = pass->readIrradiance();
    EXPECT_TRUE(read.has_value());
    return read ? *read : std::vector<glm::vec4>{};
  };

  auto still = SkinDiffusionMesh::create(device(), mesh);
  ASSERT_TRUE(still.has_value()) << still.error().message;
  const std::vector<glm::vec4> expected = irradiance(*still, scale * turn);

  auto skinned = SkinDiffusionMesh::create(device(), mesh);
  ASSERT_TRUE(skinned.has_value()) << skinned.error().message;
  const GpuSkinnedMesh bound{.positions = head.positions,
                             .normals = head.normals,
                             .influencesPerVertex = 1,
                             .joints = std::vector<std::uint32_t>(head.positions.size(), 0),
                             .weights = std::vector<float>(head.positions.size(), 1.0f),
                             .jointCount = 1};
  auto skinning = SkinningPass::create(device(), bound, {.vertexTargets = {skinned->vertexTarget()}});
  ASSERT_TRUE(skinning.has_value()) << skinning.error().message;
  ASSERT_TRUE((*skinning)->update(std::span(&turn, 1), {}).has_value());
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*skinning)->record(commands); });
  const std::vector<glm::vec4> got = irradiance(*skinned, scale);

  ASSERT_EQ(got.size(), expected.size());
  ASSERT_FALSE(got.empty());
  double worst = 0.0;
  std::size_t covered = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].a, expected[i].a) << "texel " << i;
    covered += expected[i].a > 0.0f;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(got[i][c] - expected[i][c])));
  }
  EXPECT_GT(covered, std::size_t(kSmall) * kSmall * 9 / 10);  // islands and skirts
  // Lit irradiance up to 1.1, in half floats (a step of 2^-10 near 1): two steps.
  EXPECT_LE(worst, 2.0 / 1024.0);
}

TEST_F(SkinSeamTest, ASeamReachOutsideItsRangeIsAnError) {
  const std::vector<glm::vec3> positions{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, normals(3, glm::vec3(0, 0, 1));
  const std::vector<glm::vec2> uvs{{0, 0}, {1, 0}, {0, 1}};
  const std::vector<std::uint32_t> indices{0, 1, 2};
  const MeshData mesh{.positions = positions, .normals = normals, .uvs = uvs, .indices = indices};
  for (const float reach : {-0.1f, 0.5f, std::numeric_limits<float>::quiet_NaN()}) {
    auto created = SkinDiffusionMesh::create(device(), mesh, reach);
    ASSERT_FALSE(created.has_value()) << reach;
    EXPECT_NE(created.error().message.find("seam reach"), std::string::npos) << created.error().message;
  }
  EXPECT_TRUE(SkinDiffusionMesh::create(device(), mesh, 0.0f).has_value());
}

}  // namespace
}  // namespace mane::render
