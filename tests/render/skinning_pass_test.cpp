// The skinning compute pass (render/passes/skinning_pass.hpp) against the CPU path it mirrors,
// physics::SkinnedMesh::deform, on every vertex:
// - RobotExpressive posed by its clips, the head's expression morph targets blended in, by linear
//   blend and by dual-quaternion skinning;
// - a hand-built two-joint tube (a twist and a bend, a morph target, a scaled armature), with 2
//   influences per vertex and with 5 (the pass's second group of four). The robot has no
//   tangents; the tube has, of both handednesses.
//
// Tolerances. Both paths evaluate the same formula in float from the same inputs (the DQS
// joints are decomposed in double on both sides), but the GPU may order, fuse and round sqrt and
// division differently, by a few ulp per operation. A position is a few dozen operations deep on
// values no larger than the posed joints' reach, so its error is some 1e-6 of the mesh's size;
// 1e-5 × the size leaves a margin of ten. A normal is a renormalised product of such values:
// its direction agrees to about 1e-6 rad where the skinned frame is well conditioned; 1e-4 rad
// allows for thin, strongly blended regions where the cofactor's length is small.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/skinning.hpp"
#include "render/passes/skinning_pass.hpp"
#include "scenes/gltf_character.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

using ::testing::HasSubstr;

constexpr double kPositionTolerance = 1e-5;  // × the mesh's size
constexpr double kAngleTolerance = 1e-4;     // radians

GpuSkinnedMesh toGpu(const physics::SkinnedMeshData& data) {
  GpuSkinnedMesh mesh{.positions = data.positions,
                      .normals = data.normals,
                      .tangents = data.tangents,
                      .influencesPerVertex = static_cast<std::uint32_t>(data.influencesPerVertex),
                      .joints = data.joints,
                      .weights = data.weights,
                      .jointCount = static_cast<std::uint32_t>(data.jointCount),
                      .morphTargets = {},
                      .method = data.method == physics::SkinningMethod::DualQuaternion
                                    ? GpuSkinningMethod::DualQuaternion
                                    : GpuSkinningMethod::LinearBlend};
  for (const physics::MorphTarget& target : data.morphTargets)
    mesh.morphTargets.push_back({target.positionDeltas, target.normalDeltas, target.tangentDeltas});
  return mesh;
}

double angle(const glm::vec3& a, const glm::vec3& b) {
  const glm::dvec3 da(a), db(b);
  return std::atan2(glm::length(glm::cross(da, db)), glm::dot(da, db));
}

/// The largest differences between the GPU's output and the CPU's over every vertex.
struct Agreement {
  double position = 0.0;  // max |gpu − cpu|, metres
  double size = 0.0;      // the CPU mesh's bounding-box diagonal, metres
  double normalAngle = 0.0;
  double tangentAngle = 0.0;
  std::size_t handednessMismatches = 0;
  std::size_t vertices = 0;

  void add(const Agreement& other) {
    position = std::max(position, other.position);
    normalAngle = std::max(normalAngle, other.normalAngle);
    tangentAngle = std::max(tangentAngle, other.tangentAngle);
    handednessMismatches += other.handednessMismatches;
    vertices += other.vertices;
  }
};

class SkinningPassTest : public testing::VulkanTest {
protected:
  /// Deforms `mesh` on the CPU and the GPU with the same inputs and compares every vertex.
  Agreement compare(const physics::SkinnedMesh& mesh, std::span<const glm::mat4> joints,
                    std::span<const float> morphWeights) {
    Agreement result;
    physics::DeformedSurface cpu;
    auto deformed = mesh.deform(joints, morphWeights, cpu);
    EXPECT_TRUE(deformed) << deformed.error().message;
    auto pass = SkinningPass::create(device(), toGpu(mesh.data()), {.hostReadable = true});
    EXPECT_TRUE(pass) << pass.error().message;
    if (!deformed || !pass) return result;
    auto updated = (*pass)->update(joints, morphWeights);
    EXPECT_TRUE(updated) << updated.error().message;
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });
    const auto positions = (*pass)->mappedPositions();
    const auto normals = (*pass)->mappedNormals();
    const auto tangents = (*pass)->mappedTangents();
    EXPECT_EQ(positions.size(), cpu.positions.size());
    glm::dvec3 low(INFINITY), high(-INFINITY);
    for (std::size_t v = 0; v < cpu.positions.size(); ++v) {
      low = glm::min(low, glm::dvec3(cpu.positions[v]));
      high = glm::max(high, glm::dvec3(cpu.positions[v]));
      result.position = std::max(result.position, glm::length(glm::dvec3(positions[v]) - glm::dvec3(cpu.positions[v])));
      if (!cpu.normals.empty())
        result.normalAngle = std::max(result.normalAngle, angle(glm::vec3(normals[v]), cpu.normals[v]));
      if (!cpu.tangents.empty()) {
        result.tangentAngle = std::max(result.tangentAngle, angle(glm::vec3(tangents[v]), glm::vec3(cpu.tangents[v])));
        result.handednessMismatches += tangents[v].w != cpu.tangents[v].w;
      }
    }
    result.size = glm::length(high - low);
    result.vertices = cpu.positions.size();
    return result;
  }
};

void expectAgreement(const Agreement& agreement, const char* what) {
  EXPECT_GT(agreement.vertices, 0u) << what;
  EXPECT_LE(agreement.position, kPositionTolerance * agreement.size) << what;
  EXPECT_LE(agreement.normalAngle, kAngleTolerance) << what;
  EXPECT_LE(agreement.tangentAngle, kAngleTolerance) << what;
  EXPECT_EQ(agreement.handednessMismatches, 0u) << what;
}

void reportAgreement(const Agreement& agreement, const char* what) {
  std::printf("%s: %zu vertices, size %.4g m: position %.3g m (%.3g of the size), normal %.3g rad, tangent %.3g rad\n",
              what, agreement.vertices, agreement.size, agreement.position, agreement.position / agreement.size,
              agreement.normalAngle, agreement.tangentAngle);
}

// ---- RobotExpressive ---------------------------------------------------------------------------

struct PoseCase {
  const char* clip;
  float time;
  physics::SkinningMethod method;
  const char* label;
};

TEST_F(SkinningPassTest, RobotExpressiveAgreesWithTheCpuOnEveryVertex) {
  MANE_RESOLVE_OR_SKIP(file, "characters/RobotExpressive/RobotExpressive.glb");
  auto robot = scenes::loadCharacter(file);
  ASSERT_TRUE(robot) << robot.error().message;
  auto head = robot->findMesh("Head");
  ASSERT_TRUE(head) << head.error().message;
  auto angry = robot->findMorphTarget(*head, "Angry");
  auto surprised = robot->findMorphTarget(*head, "Surprised");
  ASSERT_TRUE(angry && surprised);

  const PoseCase cases[] = {
      {"Walking", 0.3f, physics::SkinningMethod::LinearBlend, "Walking 0.3 s, LBS"},
      {"Walking", 0.3f, physics::SkinningMethod::DualQuaternion, "Walking 0.3 s, DQS"},
      {"Dance", 1.1f, physics::SkinningMethod::LinearBlend, "Dance 1.1 s, LBS"},
      {"Dance", 1.1f, physics::SkinningMethod::DualQuaternion, "Dance 1.1 s, DQS"},
  };
  for (const PoseCase& pose : cases) {
    auto clip = robot->findClip(pose.clip);
    ASSERT_TRUE(clip) << clip.error().message;
    physics::Pose posed = robot->skeleton.restPose();
    ASSERT_TRUE((*clip)->apply(pose.time, posed));
    std::vector<float>& expression = posed.morphWeights[robot->meshes[*head].node];
    std::ranges::fill(expression, 0.0f);
    expression[*angry] = 0.7f;
    expression[*surprised] = 0.3f;
    auto world = robot->skeleton.worldMatrices(posed);
    ASSERT_TRUE(world) << world.error().message;

    Agreement all;
    for (std::size_t m = 0; m < robot->meshes.size(); ++m) {
      physics::SkinnedMesh mesh = robot->meshes[m].surface;
      mesh.setMethod(pose.method);
      auto joints = robot->jointMatrices(m, *world);
      ASSERT_TRUE(joints) << joints.error().message;
      const Agreement agreement = compare(mesh, *joints, posed.morphWeights[robot->meshes[m].node]);
      expectAgreement(agreement, robot->meshes[m].name.c_str());
      all.add(agreement);
      all.size = std::max(all.size, agreement.size);
    }
    reportAgreement(all, pose.label);
  }
}

// ---- A two-joint tube --------------------------------------------------------------------------

// A tube along x from 0 to 2 (radius 0.2, rings of 8), joint 1 at x = 1; the weight of joint 1
// rises linearly over x ∈ [0.5, 1.5]. Each vertex has `influences` influences: its two joints,
// then zero-weight ones. One morph target bulges the middle.
physics::SkinnedMesh twoJointTube(std::size_t influences, physics::SkinningMethod method) {
  physics::SkinnedMeshData data;
  data.influencesPerVertex = influences;
  data.jointCount = 2;
  data.method = method;
  physics::MorphTarget bulge{.name = "bulge"};
  constexpr int kRings = 17;
  constexpr int kSides = 8;
  for (int ring = 0; ring < kRings; ++ring) {
    const float x = 2.0f * float(ring) / float(kRings - 1);
    const float w1 = std::clamp(x - 0.5f, 0.0f, 1.0f);
    for (int side = 0; side < kSides; ++side) {
      const float a = 2.0f * std::numbers::pi_v<float> * float(side) / kSides;
      const glm::vec3 radial(0.0f, std::cos(a), std::sin(a));
      data.positions.push_back(glm::vec3(x, 0.0f, 0.0f) + 0.2f * radial);
      data.normals.push_back(radial);
      data.tangents.emplace_back(0.0f, -std::sin(a), std::cos(a), side % 2 == 0 ? 1.0f : -1.0f);
      for (std::size_t i = 0; i < influences; ++i) {
        data.joints.push_back(i == 1 ? 1u : 0u);
        data.weights.push_back(i == 0 ? 1.0f - w1 : i == 1 ? w1 : 0.0f);
      }
      const float middle = std::max(0.0f, 1.0f - std::abs(x - 1.0f));
      bulge.positionDeltas.push_back(0.05f * middle * radial);
      bulge.normalDeltas.push_back(glm::vec3(0.3f * middle, 0.0f, 0.0f));
      bulge.tangentDeltas.push_back(glm::vec3(0.1f * middle, 0.0f, 0.0f));
    }
  }
  data.morphTargets.push_back(std::move(bulge));
  auto mesh = physics::SkinnedMesh::create(std::move(data));
  EXPECT_TRUE(mesh) << mesh.error().message;
  return std::move(*mesh);
}

// Joint 1 twisted 90° about the tube and bent 60° about z around x = 1, the whole armature scaled
// 1.5× and moved: world(joint)·inverseBind(joint).
std::vector<glm::mat4> twistAndBend() {
  const glm::mat4 armature = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.2f, 0.1f)), glm::vec3(1.5f));
  glm::mat4 joint1 = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  joint1 = glm::rotate(joint1, std::numbers::pi_v<float> / 3.0f, glm::vec3(0.0f, 0.0f, 1.0f));
  joint1 = glm::rotate(joint1, std::numbers::pi_v<float> / 2.0f, glm::vec3(1.0f, 0.0f, 0.0f));
  joint1 = glm::translate(joint1, glm::vec3(-1.0f, 0.0f, 0.0f));
  return {armature, armature * joint1};
}

TEST_F(SkinningPassTest, TwoJointTubeAgreesWithTheCpuOnEveryVertex) {
  const std::vector<glm::mat4> joints = twistAndBend();
  const float morphWeights[] = {0.6f};
  for (std::size_t influences : {2u, 5u}) {
    for (auto method : {physics::SkinningMethod::LinearBlend, physics::SkinningMethod::DualQuaternion}) {
      const std::string what = std::to_string(influences) + " influences, " +
                               (method == physics::SkinningMethod::LinearBlend ? "LBS" : "DQS");
      const Agreement agreement = compare(twoJointTube(influences, method), joints, morphWeights);
      expectAgreement(agreement, what.c_str());
      reportAgreement(agreement, what.c_str());
    }
  }
}

TEST_F(SkinningPassTest, RejectsBadMeshesAndFrames) {
  GpuSkinnedMesh tooMany = toGpu(twoJointTube(2, physics::SkinningMethod::LinearBlend).data());
  tooMany.influencesPerVertex = 9;
  auto refused = SkinningPass::create(device(), tooMany);
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("1 to 8"));

  GpuSkinnedMesh outOfRange = toGpu(twoJointTube(2, physics::SkinningMethod::DualQuaternion).data());
  outOfRange.joints[7] = 2;
  refused = SkinningPass::create(device(), outOfRange);
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("vertex 3 is bound to joint 2"));

  auto pass = SkinningPass::create(device(), toGpu(twoJointTube(2, physics::SkinningMethod::DualQuaternion).data()));
  ASSERT_TRUE(pass) << pass.error().message;
  const float weights[] = {0.0f};
  const glm::mat4 mirrored[] = {glm::mat4(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f))};
  auto updated = (*pass)->update(mirrored, weights);
  ASSERT_FALSE(updated);
  EXPECT_THAT(updated.error().message, HasSubstr("joint matrix 1 mirrors"));
  EXPECT_FALSE((*pass)->update(std::span(mirrored).first(1), weights));
}

}  // namespace
}  // namespace mane::render
