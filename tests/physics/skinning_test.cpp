// Skinning against hand-computed vertices on a two-joint rig, the candy-wrapper collapse of
// linear blend skinning under a twist (and dual quaternions keeping the radius), normals under
// non-uniform scale and mirroring, morphs before skinning, and bad input rejected by vertex.
//
// The rig: joint 0 at the origin, joint 1 one metre along +x (its bind pose is a translation by
// (1, 0, 0), so its inverse bind matrix translates by (−1, 0, 0)). Posing joint 1 by a rotation
// R turns everything bound to it about the pivot (1, 0, 0): M1 = T(1,0,0)·R·T(−1,0,0).

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/skeleton.hpp"
#include "physics/skinning.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;

constexpr float kPi = std::numbers::pi_v<float>;

// Float rounding of a few products of metre-sized numbers: well under a micrometre.
constexpr float kTolerance = 1e-6f;

/// Joint matrices of the rig with joint 1 turned by `angle` (radians) about `axis`, both
/// computed through the skeleton (world · inverse bind), as a character would.
std::vector<glm::mat4> rigJointMatrices(float angle, const glm::vec3& axis) {
  std::vector<SkeletonNode> nodes(2);
  nodes[1].parent = 0;
  nodes[1].rest.translation = glm::vec3(1.0f, 0.0f, 0.0f);
  auto skeleton = Skeleton::create(nodes);
  EXPECT_TRUE(skeleton.has_value());
  Pose pose = skeleton->restPose();
  pose.local[1].rotation = glm::angleAxis(angle, axis);
  auto world = skeleton->worldMatrices(pose);
  EXPECT_TRUE(world.has_value());
  const glm::mat4 inverseBind1 = glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f));
  return {(*world)[0], (*world)[1] * inverseBind1};
}

/// A mesh of single points, each bound to joints 0 and 1 with the given weights of joint 1.
SkinnedMeshData twoJointPoints(const std::vector<glm::vec3>& points, const std::vector<float>& weightOfJoint1,
                               SkinningMethod method) {
  SkinnedMeshData data;
  data.positions = points;
  data.influencesPerVertex = 2;
  data.jointCount = 2;
  data.method = method;
  for (std::size_t v = 0; v < points.size(); ++v) {
    data.joints.insert(data.joints.end(), {0u, 1u});
    data.weights.insert(data.weights.end(), {1.0f - weightOfJoint1[v], weightOfJoint1[v]});
  }
  return data;
}

std::vector<glm::vec3> deformed(const SkinnedMeshData& data, const std::vector<glm::mat4>& joints) {
  auto mesh = SkinnedMesh::create(data);
  EXPECT_TRUE(mesh.has_value()) << mesh.error().message;
  DeformedSurface out;
  auto ok = mesh->deform(joints, {}, out);
  EXPECT_TRUE(ok.has_value()) << ok.error().message;
  return out.positions;
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance, const char* what) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
  EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

/// Four points of the rig with joint 1 bent by 90° about +z (Rz(90°) takes (x, y) to (−y, x)
/// about the pivot (1, 0, 0)): on joint 0 only, on joint 1 only, half each, ¾ on joint 1.
std::vector<glm::vec3> bentRigPoints(SkinningMethod method) {
  const std::vector<glm::vec3> points = {
      {0.5f, 0.2f, 0.0f}, {2.0f, 0.0f, 0.0f}, {1.0f, 0.5f, 0.0f}, {1.5f, 0.0f, 0.0f}};
  return deformed(twoJointPoints(points, {0.0f, 1.0f, 0.5f, 0.75f}, method),
                  rigJointMatrices(0.5f * kPi, {0.0f, 0.0f, 1.0f}));
}

TEST(Skinning, LinearBlendMatchesHandComputedVerticesOfABentRig) {
  const auto out = bentRigPoints(SkinningMethod::LinearBlend);
  // Only joint 0 (identity): unchanged.
  expectNear(out[0], {0.5f, 0.2f, 0.0f}, kTolerance, "on joint 0");
  // Only joint 1: offset (1, 0, 0) from the pivot turns to (0, 1, 0): (1, 1, 0).
  expectNear(out[1], {1.0f, 1.0f, 0.0f}, kTolerance, "on joint 1");
  // Half each: ½·(1, 0.5, 0) + ½·((1, 0, 0) + Rz·(0, 0.5, 0) = (0.5, 0, 0)) = (0.75, 0.25, 0).
  expectNear(out[2], {0.75f, 0.25f, 0.0f}, kTolerance, "half and half");
  // ¼·(1.5, 0, 0) + ¾·((1, 0, 0) + Rz·(0.5, 0, 0) = (1, 0.5, 0)) = (1.125, 0.375, 0).
  expectNear(out[3], {1.125f, 0.375f, 0.0f}, kTolerance, "a quarter and three quarters");
}

TEST(Skinning, DualQuaternionMatchesHandComputedVerticesOfABentRig) {
  const auto out = bentRigPoints(SkinningMethod::DualQuaternion);
  expectNear(out[0], {0.5f, 0.2f, 0.0f}, kTolerance, "on joint 0");
  expectNear(out[1], {1.0f, 1.0f, 0.0f}, kTolerance, "on joint 1");
  // Both joint motions are rotations about the same axis through (1, 0, 0), so their blend is a
  // rotation about that axis too (conjugating by the pivot's translation is linear in the
  // quaternion). Its angle: the blended quaternion w0·(0,0,0,1) + w1·(0,0,sin 45°,cos 45°) has
  // half-angle atan2(w1·sin 45°, w0 + w1·cos 45°).
  const auto blendedAngle = [](float w1) {
    const float s = std::sin(0.25f * kPi);
    return 2.0f * std::atan2(w1 * s, (1.0f - w1) + w1 * s);
  };
  // Half each: exactly 45°; offset (0, 0.5, 0) turns to 0.5·(−sin 45°, cos 45°, 0).
  const float half = blendedAngle(0.5f);
  EXPECT_NEAR(half, 0.25f * kPi, 1e-6f);
  expectNear(out[2], {1.0f - 0.5f * std::sin(half), 0.5f * std::cos(half), 0.0f}, kTolerance, "half and half");
  expectNear(out[2], {0.6464466f, 0.3535534f, 0.0f}, kTolerance, "half and half, in numbers");
  // ¾ on joint 1: 2·atan2(0.530330, 0.780330) = 68.38°, not ¾·90° = 67.5° (the blend is not
  // linear in the angle); offset (0.5, 0, 0) turns to 0.5·(cos θ, sin θ, 0).
  const float threeQuarters = blendedAngle(0.75f);
  expectNear(out[3], {1.0f + 0.5f * std::cos(threeQuarters), 0.5f * std::sin(threeQuarters), 0.0f}, kTolerance,
             "a quarter and three quarters");
}

/// Mean distance from the x axis of a ring of `count` points of radius `radius` at x = 1 whose
/// weight of joint 1 is `w1`, with joint 1 twisted by `angle` about x.
float twistedRingRadius(SkinningMethod method, float w1, float angle, float radius) {
  const auto joints = rigJointMatrices(angle, {1.0f, 0.0f, 0.0f});
  constexpr int kCount = 32;
  std::vector<glm::vec3> ring;
  for (int i = 0; i < kCount; ++i) {
    const float phi = 2.0f * kPi * static_cast<float>(i) / kCount;
    ring.emplace_back(1.0f, radius * std::cos(phi), radius * std::sin(phi));
  }
  const auto out = deformed(twoJointPoints(ring, std::vector<float>(kCount, w1), method), joints);
  float sum = 0.0f;
  float smallest = 1e30f;
  float largest = 0.0f;
  for (const glm::vec3& p : out) {
    const float r = std::hypot(p.y, p.z);
    sum += r;
    smallest = std::min(smallest, r);
    largest = std::max(largest, r);
  }
  // A twist about the tube's own axis shrinks (or keeps) every point of the ring alike.
  EXPECT_NEAR(smallest, largest, 1e-6f);
  return sum / kCount;
}

TEST(Skinning, AtANinetyDegreeTwistDualQuaternionsKeepTheTubeRadiusWhereLinearBlendCollapses) {
  constexpr float kRadius = 0.1f;
  const float twist = 0.5f * kPi;
  // LBS averages the point turned by 0° and by 90°: radius r·|½(1 + i)| = r·cos 45° = 0.7071·r
  // with weights ½/½; r·|¼ + ¾i| = 0.7906·r with ¼/¾.
  const float lbsHalf = twistedRingRadius(SkinningMethod::LinearBlend, 0.5f, twist, kRadius) / kRadius;
  const float lbsQuarter = twistedRingRadius(SkinningMethod::LinearBlend, 0.75f, twist, kRadius) / kRadius;
  EXPECT_NEAR(lbsHalf, std::cos(0.25f * kPi), 1e-5f);                        // measured 0.70711
  EXPECT_NEAR(lbsQuarter, std::sqrt(0.25f * 0.25f + 0.75f * 0.75f), 1e-5f);  // measured 0.79057
  // DQS turns the ring rigidly by the blended angle: the radius stays r (within 1 %; in fact
  // within float rounding, measured 1.00000).
  const float dqsHalf = twistedRingRadius(SkinningMethod::DualQuaternion, 0.5f, twist, kRadius) / kRadius;
  const float dqsQuarter = twistedRingRadius(SkinningMethod::DualQuaternion, 0.75f, twist, kRadius) / kRadius;
  EXPECT_NEAR(dqsHalf, 1.0f, 0.01f);
  EXPECT_NEAR(dqsQuarter, 1.0f, 0.01f);
  EXPECT_NEAR(dqsHalf, 1.0f, 1e-5f);
}

TEST(Skinning, DualQuaternionsHandleAUniformlyScaledArmature) {
  // Exporters often scale the whole armature (RobotExpressive: 100×). Every joint matrix is then
  // 100·(rigid motion); DQS splits off the stretch, so the result is 100× the unscaled one.
  auto joints = rigJointMatrices(0.5f * kPi, {0.0f, 0.0f, 1.0f});
  const glm::mat4 scale = glm::scale(glm::mat4(1.0f), glm::vec3(100.0f));
  for (glm::mat4& m : joints) m = scale * m;
  const auto out = deformed(twoJointPoints({{1.0f, 0.5f, 0.0f}}, {0.5f}, SkinningMethod::DualQuaternion), joints);
  expectNear(out[0], 100.0f * glm::vec3(0.6464466f, 0.3535534f, 0.0f), 100.0f * kTolerance, "scaled half and half");
}

TEST(Skinning, LinearBlendNormalsUseTheInverseTransposeUnderNonUniformScale) {
  // Stretching x by 2 turns the plane x + y = 1 (normal (1, 1, 0)/√2) into x/2 + y = 1, whose
  // normal is (1, 2, 0)/√5 (= M⁻ᵀ·n normalised); its tangent (1, −1, 0)/√2 becomes (2, −1, 0)/√5.
  SkinnedMeshData data;
  data.positions = {{0.5f, 0.5f, 0.0f}};
  data.normals = {glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f))};
  data.tangents = {glm::vec4(glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f)), 1.0f)};
  data.influencesPerVertex = 1;
  data.joints = {0};
  data.weights = {1.0f};
  data.jointCount = 1;
  auto mesh = SkinnedMesh::create(data);
  ASSERT_TRUE(mesh) << mesh.error().message;
  DeformedSurface out;
  const glm::mat4 stretch = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f, 1.0f, 1.0f));
  ASSERT_TRUE(mesh->deform(std::vector<glm::mat4>{stretch}, {}, out));
  expectNear(out.positions[0], {1.0f, 0.5f, 0.0f}, kTolerance, "position");
  expectNear(out.normals[0], glm::vec3(1.0f, 2.0f, 0.0f) / std::sqrt(5.0f), kTolerance, "normal");
  expectNear(glm::vec3(out.tangents[0]), glm::vec3(2.0f, -1.0f, 0.0f) / std::sqrt(5.0f), kTolerance, "tangent");
  EXPECT_NEAR(glm::dot(out.normals[0], glm::vec3(out.tangents[0])), 0.0f, kTolerance);
  EXPECT_EQ(out.tangents[0].w, 1.0f);

  // A mirror (x → −x) flips the normal with the surface and the tangent frame's handedness.
  const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  ASSERT_TRUE(mesh->deform(std::vector<glm::mat4>{mirror}, {}, out));
  expectNear(out.normals[0], glm::vec3(-1.0f, 1.0f, 0.0f) / std::sqrt(2.0f), kTolerance, "mirrored normal");
  EXPECT_EQ(out.tangents[0].w, -1.0f);
}

TEST(Skinning, MorphTargetsApplyBeforeSkinning) {
  // Target 0 moves the vertex up 0.2 m, target 1 along x 0.4 m: with weights 0.5 and 0.25 the
  // rest point (2, 0, 0) becomes (2.1, 0.1, 0), which joint 1 (90° about z at (1, 0, 0)) takes
  // to (1, 0, 0) + Rz·(1.1, 0.1, 0) = (0.9, 1.1, 0). Skinning first would give a different
  // point: (1, 1, 0) + (0.1, 0.1, 0) = (1.1, 1.1, 0).
  SkinnedMeshData data = twoJointPoints({{2.0f, 0.0f, 0.0f}}, {1.0f}, SkinningMethod::LinearBlend);
  data.normals = {{0.0f, 1.0f, 0.0f}};
  data.morphTargets.resize(2);
  data.morphTargets[0].positionDeltas = {{0.0f, 0.2f, 0.0f}};
  data.morphTargets[0].normalDeltas = {{1.0f, -1.0f, 0.0f}};  // the normal tips to +x at weight 1
  data.morphTargets[1].positionDeltas = {{0.4f, 0.0f, 0.0f}};
  auto mesh = SkinnedMesh::create(data);
  ASSERT_TRUE(mesh) << mesh.error().message;
  DeformedSurface out;
  const std::vector<float> weights = {0.5f, 0.25f};
  for (SkinningMethod method : {SkinningMethod::LinearBlend, SkinningMethod::DualQuaternion}) {
    mesh->setMethod(method);
    ASSERT_TRUE(mesh->deform(rigJointMatrices(0.5f * kPi, {0.0f, 0.0f, 1.0f}), weights, out));
    expectNear(out.positions[0], {0.9f, 1.1f, 0.0f}, kTolerance, "morphed then skinned");
    // Morphed normal (0.5, 0.5, 0) normalised, then turned 90°: (−1, 1, 0)/√2.
    expectNear(out.normals[0], glm::vec3(-1.0f, 1.0f, 0.0f) / std::sqrt(2.0f), kTolerance, "normal");
  }
}

TEST(Skinning, WeightsAreRenormalisedAndTheSameInputGivesTheSameBits) {
  SkinnedMeshData data = twoJointPoints({{1.0f, 0.5f, 0.0f}}, {0.5f}, SkinningMethod::LinearBlend);
  data.weights = {3.0f, 1.0f};  // sums to 4: becomes 0.75 / 0.25
  auto mesh = SkinnedMesh::create(data);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->data().weights[0], 0.75f);
  EXPECT_EQ(mesh->data().weights[1], 0.25f);
  DeformedSurface first;
  DeformedSurface second;
  const auto joints = rigJointMatrices(1.0f, glm::normalize(glm::vec3(0.3f, 0.4f, 1.0f)));
  ASSERT_TRUE(mesh->deform(joints, {}, first));
  ASSERT_TRUE(mesh->deform(joints, {}, second));
  EXPECT_EQ(first.positions, second.positions);
}

TEST(Skinning, BadInputIsRejectedNamingTheVertex) {
  SkinnedMeshData zeroSum =
      twoJointPoints({{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}}, {0.5f, 0.5f}, SkinningMethod::LinearBlend);
  zeroSum.weights[2] = zeroSum.weights[3] = 0.0f;
  auto result = SkinnedMesh::create(zeroSum);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("vertex 1"));
  EXPECT_THAT(result.error().message, HasSubstr("sum to 0"));

  SkinnedMeshData badJoint = twoJointPoints({{0.0f, 0.0f, 0.0f}}, {0.5f}, SkinningMethod::LinearBlend);
  badJoint.joints[1] = 7;
  result = SkinnedMesh::create(badJoint);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.error().message, HasSubstr("joint 7"));

  SkinnedMeshData negative = twoJointPoints({{0.0f, 0.0f, 0.0f}}, {0.5f}, SkinningMethod::LinearBlend);
  negative.weights[0] = -0.5f;
  EXPECT_FALSE(SkinnedMesh::create(negative));

  auto mesh = SkinnedMesh::create(twoJointPoints({{0.0f, 0.0f, 0.0f}}, {0.5f}, SkinningMethod::DualQuaternion));
  ASSERT_TRUE(mesh);
  DeformedSurface out;
  auto deformedOk = mesh->deform(std::vector<glm::mat4>(1, glm::mat4(1.0f)), {}, out);
  ASSERT_FALSE(deformedOk);
  EXPECT_THAT(deformedOk.error().message, HasSubstr("needs 2 joint matrices"));
  // DQS cannot express a mirror; LBS can.
  const std::vector<glm::mat4> mirrored = {glm::mat4(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f))};
  deformedOk = mesh->deform(mirrored, {}, out);
  ASSERT_FALSE(deformedOk);
  EXPECT_THAT(deformedOk.error().message, HasSubstr("mirrors"));
  mesh->setMethod(SkinningMethod::LinearBlend);
  EXPECT_TRUE(mesh->deform(mirrored, {}, out));
}


/// A few thousand vertices along a bar of five joints, four influences each, with normals,
/// tangents and one morph target: enough vertices that every thread gets a range of its own.
SkinnedMeshData manyVertexBar(SkinningMethod method) {
  SkinnedMeshData data;
  data.influencesPerVertex = 4;
  data.jointCount = 5;
  data.method = method;
  MorphTarget bulge;
  for (std::uint32_t v = 0; v < 3001; ++v) {
    const float t = float(v) / 3000.0f;
    const float angle = 0.37f * float(v);
    const glm::vec3 radial(0.0f, std::cos(angle), std::sin(angle));
    data.positions.push_back(glm::vec3(4.0f * t, 0.0f, 0.0f) + 0.2f * radial);
    data.normals.push_back(radial);
    data.tangents.push_back(glm::vec4(1.0f, 0.0f, 0.0f, v % 2 == 0 ? 1.0f : -1.0f));
    const std::uint32_t first = v < 1500 ? 0 : 1;  // joint 4 only from the middle on
    for (std::uint32_t i = 0; i < 4; ++i) {
      data.joints.push_back(first + i);
      data.weights.push_back(1.0f + std::sin(float(v + 7 * i)));
    }
    bulge.positionDeltas.push_back(0.05f * radial * std::sin(9.0f * t));
    bulge.normalDeltas.push_back(glm::vec3(0.1f * std::cos(9.0f * t), 0.0f, 0.0f));
  }
  data.morphTargets.push_back(bulge);
  return data;
}

std::vector<glm::mat4> barJoints() {
  std::vector<glm::mat4> joints;
  for (int j = 0; j < 5; ++j) {
    const glm::mat4 pivot = glm::translate(glm::mat4(1.0f), glm::vec3(float(j), 0.0f, 0.0f));
    joints.push_back(pivot * glm::rotate(glm::mat4(1.0f), 0.3f * float(j), glm::normalize(glm::vec3(0.2f, 0.3f, 1.0f))) *
                     glm::scale(glm::mat4(1.0f), glm::vec3(1.0f + 0.05f * float(j))) * glm::inverse(pivot));
  }
  return joints;
}

template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(Skinning, AnyThreadCountGivesTheSameBits) {
  // Each vertex is computed alone, from the same inputs, whichever worker takes it: memcmp-equal.
  const std::vector<glm::mat4> joints = barJoints();
  const std::vector<float> morphWeights = {0.7f};
  for (const SkinningMethod method : {SkinningMethod::LinearBlend, SkinningMethod::DualQuaternion}) {
    auto mesh = SkinnedMesh::create(manyVertexBar(method));
    ASSERT_TRUE(mesh) << mesh.error().message;
    DeformedSurface one;
    ASSERT_TRUE(mesh->deform(joints, morphWeights, one, 1));
    for (const unsigned threads : {2u, 3u}) {
      DeformedSurface many;
      ASSERT_TRUE(mesh->deform(joints, morphWeights, many, threads));
      EXPECT_TRUE(sameBytes(one.positions, many.positions)) << threads << " threads";
      EXPECT_TRUE(sameBytes(one.normals, many.normals)) << threads << " threads";
      EXPECT_TRUE(sameBytes(one.tangents, many.tangents)) << threads << " threads";
    }
  }
}

TEST(Skinning, AThreadedDeformNamesTheFirstBadVertexAsOneThreadDoes) {
  auto mesh = SkinnedMesh::create(manyVertexBar(SkinningMethod::DualQuaternion));
  ASSERT_TRUE(mesh) << mesh.error().message;
  std::vector<glm::mat4> joints = barJoints();
  // A mirror, which no rotation expresses, on the joint of the second half only: with 3 threads
  // the second and third workers both fail, and the error names vertex 1500 as one thread does.
  joints[4] = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  DeformedSurface out;
  const auto alone = mesh->deform(joints, std::vector<float>{0.0f}, out, 1);
  const auto threaded = mesh->deform(joints, std::vector<float>{0.0f}, out, 3);
  ASSERT_FALSE(alone);
  ASSERT_FALSE(threaded);
  EXPECT_EQ(alone.error().message, threaded.error().message);
  EXPECT_THAT(alone.error().message, HasSubstr("vertex 1500 is bound to joint 4"));
}

}  // namespace
}  // namespace mane::physics
