// loadCharacter on the shared assets, against values computed here from the raw files
// (nlohmann::json and the buffer bytes, tests/scenes/gltf_raw.hpp), never through the loader:
// morph targets at known weights (glTF 2.0 §3.7.2.2: p = p_base + Σ w_i·Δp_i), weight
// animations at their key times, and RobotExpressive's clips, facial targets, skins and bind
// pose.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gltf_raw.hpp"
#include "scenes/gltf_character.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::RawGltf;

glm::dvec3 rawVec3(const std::vector<double>& values, std::size_t index) {
  return {values[3 * index], values[3 * index + 1], values[3 * index + 2]};
}

/// Deforms mesh `m` of `character` with `weights` and its own joint matrix set to identity, so
/// the result stays in the mesh's own space, where the raw file's numbers live.
physics::DeformedSurface morphedInMeshSpace(const Character& character, std::size_t m,
                                            const std::vector<float>& weights) {
  const CharacterMesh& mesh = character.meshes[m];
  EXPECT_EQ(mesh.skin, -1);
  physics::DeformedSurface out;
  auto ok = mesh.surface.deform(std::vector<glm::mat4>{glm::mat4(1.0f)}, weights, out);
  EXPECT_TRUE(ok) << ok.error().message;
  return out;
}

/// Expected morphed positions (and normals, when the file has them) of every primitive of mesh
/// `meshIndex`, from the raw accessors.
void expectMorphedLikeTheSpec(const RawGltf& raw, int meshIndex, const physics::DeformedSurface& out,
                              const std::vector<float>& weights, double tolerance) {
  std::size_t first = 0;
  for (const auto& primitive : raw.json.at("meshes").at(meshIndex).at("primitives")) {
    const auto& attributes = primitive.at("attributes");
    const auto base = raw.accessor(attributes.at("POSITION").get<int>());
    const std::size_t count = base.size() / 3;
    std::vector<glm::dvec3> expected(count);
    std::vector<glm::dvec3> expectedNormals;
    std::vector<double> baseNormals;
    if (attributes.contains("NORMAL")) {
      baseNormals = raw.accessor(attributes.at("NORMAL").get<int>());
      expectedNormals.resize(count);
    }
    for (std::size_t v = 0; v < count; ++v) {
      expected[v] = rawVec3(base, v);
      if (!baseNormals.empty()) expectedNormals[v] = rawVec3(baseNormals, v);
    }
    const auto& targets = primitive.at("targets");
    for (std::size_t t = 0; t < targets.size(); ++t) {
      const auto deltas = raw.accessor(targets[t].at("POSITION").get<int>());
      for (std::size_t v = 0; v < count; ++v) expected[v] += double(weights[t]) * rawVec3(deltas, v);
      if (!baseNormals.empty() && targets[t].contains("NORMAL")) {
        const auto normalDeltas = raw.accessor(targets[t].at("NORMAL").get<int>());
        for (std::size_t v = 0; v < count; ++v) expectedNormals[v] += double(weights[t]) * rawVec3(normalDeltas, v);
      }
    }
    for (std::size_t v = 0; v < count; ++v) {
      const glm::dvec3 actual(out.positions[first + v]);
      EXPECT_LT(glm::length(actual - expected[v]), tolerance) << "vertex " << first + v;
      if (!expectedNormals.empty()) {
        const glm::dvec3 normal(out.normals[first + v]);
        EXPECT_LT(glm::length(normal - glm::normalize(expectedNormals[v])), 1e-6) << "normal " << first + v;
      }
    }
    first += count;
  }
  EXPECT_EQ(first, out.positions.size());
}

TEST(CharacterMorphTargets, SimpleMorphAtKnownWeightsGivesBasePlusWeightedDeltas) {
  MANE_RESOLVE_OR_SKIP(file, "gltf/SimpleMorph/glTF/SimpleMorph.gltf");
  auto character = loadCharacter(file);
  ASSERT_TRUE(character) << character.error().message;
  const RawGltf raw = RawGltf::read(file);
  ASSERT_EQ(character->meshes.size(), 1u);
  EXPECT_EQ(character->meshes[0].surface.morphTargetCount(), 2u);
  // The mesh's default weights (mesh.weights = [0.5, 0.5]) are the rest pose's.
  const physics::Pose rest = character->skeleton.restPose();
  EXPECT_THAT(rest.morphWeights[0], ElementsAre(0.5f, 0.5f));
  // Coordinates of order 1: float rounding of two products and sums stays below 1e-6.
  for (const std::vector<float>& weights : {rest.morphWeights[0], std::vector<float>{0.25f, 0.75f},
                                            std::vector<float>{1.0f, 0.0f}, std::vector<float>{-0.5f, 2.0f}}) {
    expectMorphedLikeTheSpec(raw, 0, morphedInMeshSpace(*character, 0, weights), weights, 1e-6);
  }
}

TEST(CharacterMorphTargets, AnimatedMorphCubeAtKnownWeightsGivesBasePlusWeightedDeltas) {
  MANE_RESOLVE_OR_SKIP(file, "gltf/AnimatedMorphCube/glTF/AnimatedMorphCube.gltf");
  auto character = loadCharacter(file);
  ASSERT_TRUE(character) << character.error().message;
  const RawGltf raw = RawGltf::read(file);
  ASSERT_EQ(character->meshes.size(), 1u);
  const CharacterMesh& cube = character->meshes[0];
  EXPECT_EQ(cube.surface.morphTargetCount(), 2u);
  // POSITION, NORMAL and TANGENT deltas are all read.
  for (const physics::MorphTarget& target : cube.surface.data().morphTargets) {
    EXPECT_EQ(target.positionDeltas.size(), 24u);
    EXPECT_EQ(target.normalDeltas.size(), 24u);
    EXPECT_EQ(target.tangentDeltas.size(), 24u);
  }
  // A 2 cm cube: 1e-8 m is ~100 float ulps of its coordinates.
  for (const std::vector<float>& weights :
       {std::vector<float>{0.0f, 0.0f}, std::vector<float>{0.3f, 0.6f}, std::vector<float>{1.0f, 1.0f}}) {
    expectMorphedLikeTheSpec(raw, 0, morphedInMeshSpace(*character, 0, weights), weights, 1e-8);
  }
}

/// At each key time of the file's weight animation, the sampled weights are the key's values
/// (LINEAR at u = 0 is v_k exactly).
void expectWeightKeysReproduced(const std::filesystem::path& file) {
  auto character = loadCharacter(file);
  ASSERT_TRUE(character) << character.error().message;
  const RawGltf raw = RawGltf::read(file);
  const auto& sampler = raw.json.at("animations").at(0).at("samplers").at(0);
  const auto times = raw.accessor(sampler.at("input").get<int>());
  const auto values = raw.accessor(sampler.at("output").get<int>());
  const std::size_t targets = values.size() / times.size();
  ASSERT_EQ(character->clips.size(), 1u);
  ASSERT_EQ(targets, 2u);
  EXPECT_FLOAT_EQ(character->clips[0].duration(), static_cast<float>(times.back()));
  for (std::size_t k = 0; k < times.size(); ++k) {
    physics::Pose pose = character->skeleton.restPose();
    ASSERT_TRUE(character->clips[0].apply(static_cast<float>(times[k]), pose));
    for (std::size_t t = 0; t < targets; ++t) {
      EXPECT_EQ(pose.morphWeights[0][t], static_cast<float>(values[k * targets + t])) << "key " << k << " target " << t;
    }
  }
}

TEST(CharacterAnimation, SimpleMorphWeightAnimationAtKeyTimesEqualsTheKeys) {
  MANE_RESOLVE_OR_SKIP(file, "gltf/SimpleMorph/glTF/SimpleMorph.gltf");
  expectWeightKeysReproduced(file);
}

TEST(CharacterAnimation, AnimatedMorphCubeWeightAnimationAtKeyTimesEqualsTheKeys) {
  MANE_RESOLVE_OR_SKIP(file, "gltf/AnimatedMorphCube/glTF/AnimatedMorphCube.gltf");
  expectWeightKeysReproduced(file);
}

TEST(RobotExpressive, HasItsClipsFacialTargetsAndSkins) {
  MANE_RESOLVE_OR_SKIP(file, "characters/RobotExpressive/RobotExpressive.glb");
  auto robot = loadCharacter(file);
  ASSERT_TRUE(robot) << robot.error().message;
  std::vector<std::string> names;
  for (const physics::AnimationClip& clip : robot->clips) names.push_back(clip.name());
  EXPECT_THAT(names, ElementsAre("Dance", "Death", "Idle", "Jump", "No", "Punch", "Running", "Sitting", "Standing",
                                 "ThumbsUp", "Walking", "WalkJump", "Wave", "Yes"));
  for (const std::string& name : names) {
    auto clip = robot->findClip(name);
    ASSERT_TRUE(clip) << clip.error().message;
    EXPECT_EQ((*clip)->name(), name);
    EXPECT_GT((*clip)->duration(), 0.0f);
  }
  auto head = robot->findMesh("Head");
  ASSERT_TRUE(head) << head.error().message;
  EXPECT_THAT(robot->meshes[*head].morphTargetNames, ElementsAre("Angry", "Surprised", "Sad"));
  auto surprised = robot->findMorphTarget(*head, "Surprised");
  ASSERT_TRUE(surprised) << surprised.error().message;
  EXPECT_EQ(*surprised, 1u);
  ASSERT_EQ(robot->skins.size(), 2u);
  for (const CharacterSkin& skin : robot->skins) {
    EXPECT_EQ(skin.joints.size(), 43u);
    EXPECT_EQ(skin.inverseBindMatrices.size(), 43u);
  }

  auto missingClip = robot->findClip("Moonwalk");
  ASSERT_FALSE(missingClip);
  EXPECT_THAT(missingClip.error().message, HasSubstr(file.string()));
  EXPECT_THAT(missingClip.error().message, HasSubstr("no animation named 'Moonwalk'"));
  EXPECT_THAT(missingClip.error().message, HasSubstr("'Wave'"));
  auto missingTarget = robot->findMorphTarget(*head, "Happy");
  ASSERT_FALSE(missingTarget);
  EXPECT_THAT(missingTarget.error().message, HasSubstr("mesh 'Head' has no morph target named 'Happy'"));
  EXPECT_THAT(missingTarget.error().message, HasSubstr("'Angry', 'Surprised', 'Sad'"));
}

TEST(RobotExpressive, RestPoseSkinningReproducesTheBindPoseOfTheFilesNodeTransforms) {
  MANE_RESOLVE_OR_SKIP(file, "characters/RobotExpressive/RobotExpressive.glb");
  auto robot = loadCharacter(file);
  ASSERT_TRUE(robot) << robot.error().message;
  const RawGltf raw = RawGltf::read(file);
  const std::vector<glm::dmat4> rawWorld = raw.worldMatrices();

  const physics::Pose rest = robot->skeleton.restPose();
  auto world = robot->skeleton.worldMatrices(rest);
  ASSERT_TRUE(world) << world.error().message;

  // The oracle, in double from the raw file: a skinned vertex is Σ ŵ_i·world(joint_i)·IBM_i·v with
  // ŵ the file's weights divided by their sum; a rigid mesh's vertex is world(node)·v.
  struct Expected {
    std::vector<glm::dvec3> positions;
  };
  std::vector<Expected> expected(robot->meshes.size());
  glm::dvec3 low(1e30);
  glm::dvec3 high(-1e30);
  double largestRawSum = 0.0;
  for (std::size_t m = 0; m < robot->meshes.size(); ++m) {
    const CharacterMesh& mesh = robot->meshes[m];
    const auto& node = raw.json.at("nodes").at(mesh.node);
    std::vector<glm::dmat4> jointMatrices;
    if (node.contains("skin")) {
      const auto& skin = raw.json.at("skins").at(node.at("skin").get<int>());
      const auto ibm = raw.accessor(skin.at("inverseBindMatrices").get<int>());
      for (std::size_t j = 0; j < skin.at("joints").size(); ++j) {
        glm::dmat4 inverseBind;
        for (int i = 0; i < 16; ++i) inverseBind[i / 4][i % 4] = ibm[16 * j + static_cast<std::size_t>(i)];
        jointMatrices.push_back(rawWorld.at(skin.at("joints")[j].get<std::size_t>()) * inverseBind);
      }
    }
    for (const auto& primitive : raw.json.at("meshes").at(mesh.mesh).at("primitives")) {
      const auto& attributes = primitive.at("attributes");
      const auto positions = raw.accessor(attributes.at("POSITION").get<int>());
      std::vector<double> joints, weights;
      if (!jointMatrices.empty()) {
        joints = raw.accessor(attributes.at("JOINTS_0").get<int>());
        weights = raw.accessor(attributes.at("WEIGHTS_0").get<int>());
      }
      for (std::size_t v = 0; v < positions.size() / 3; ++v) {
        const glm::dvec4 p(rawVec3(positions, v), 1.0);
        glm::dvec3 q(0.0);
        if (jointMatrices.empty()) {
          q = glm::dvec3(rawWorld.at(static_cast<std::size_t>(mesh.node)) * p);
        } else {
          const double sum = weights[4 * v] + weights[4 * v + 1] + weights[4 * v + 2] + weights[4 * v + 3];
          largestRawSum = std::max(largestRawSum, sum);
          for (std::size_t i = 0; i < 4; ++i) {
            q += weights[4 * v + i] / sum *
                 glm::dvec3(jointMatrices.at(static_cast<std::size_t>(joints[4 * v + i])) * p);
          }
        }
        expected[m].positions.push_back(q);
        low = glm::min(low, q);
        high = glm::max(high, q);
      }
    }
  }
  // The file's WEIGHTS_0 do not all sum to 1 (up to 1.755): the renormalisation matters here.
  EXPECT_GT(largestRawSum, 1.5);

  // 1e-4 relative to the robot's size: float joint matrices over a 43-bone chain carry ~1e-6
  // relative error, so this also catches a wrong bone or weight, which moves vertices by far more.
  const double size = glm::length(high - low);
  double worst = 0.0;
  for (std::size_t m = 0; m < robot->meshes.size(); ++m) {
    const CharacterMesh& mesh = robot->meshes[m];
    auto joints = robot->jointMatrices(m, *world);
    ASSERT_TRUE(joints) << joints.error().message;
    physics::DeformedSurface out;
    auto ok = mesh.surface.deform(*joints, rest.morphWeights[static_cast<std::size_t>(mesh.node)], out);
    ASSERT_TRUE(ok) << ok.error().message;
    ASSERT_EQ(out.positions.size(), expected[m].positions.size()) << mesh.name;
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
      worst = std::max(worst, glm::length(glm::dvec3(out.positions[v]) - expected[m].positions[v]) / size);
    }
  }
  EXPECT_LT(worst, 1e-4) << "largest deviation relative to the robot's size " << size;
}

TEST(RobotExpressive, EveryVertexsWeightsSumToOneAfterRenormalisation) {
  MANE_RESOLVE_OR_SKIP(file, "characters/RobotExpressive/RobotExpressive.glb");
  auto robot = loadCharacter(file);
  ASSERT_TRUE(robot) << robot.error().message;
  std::size_t skinned = 0;
  for (const CharacterMesh& mesh : robot->meshes) {
    const physics::SkinnedMeshData& data = mesh.surface.data();
    for (std::size_t v = 0; v < mesh.surface.vertexCount(); ++v) {
      float sum = 0.0f;
      for (std::size_t i = 0; i < data.influencesPerVertex; ++i) sum += data.weights[v * data.influencesPerVertex + i];
      // Four quotients w_i/Σ summed in float: a few ulps of 1.
      EXPECT_NEAR(sum, 1.0f, 1e-6f) << mesh.name << " vertex " << v;
    }
    if (mesh.skin >= 0) skinned += mesh.surface.vertexCount();
  }
  EXPECT_GT(skinned, 0u);
}

}  // namespace
}  // namespace mane::scenes
