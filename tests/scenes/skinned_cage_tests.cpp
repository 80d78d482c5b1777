// A subdivided cage skinned each frame (scenes::SkinnedCage): an open tube along +y, 8 quads
// around × 12 along, bound to two joints (the lower half to joint 0, the upper half to joint 1,
// blended smoothly over the middle four rings), bent at the elbow about z and seen from the side
// (+z) by a fixed camera at 1280×720.
//
// Oracles: the tessellator's own screen-space bound (subdiv/tessellator.hpp), measured
// independently here along every output edge against the limit surface at the same ptex
// parameter, with the tessellator tests' allowance of 10 %; a limit surface built from scratch
// for the skinned cage (so the pose really reached the surface the triangles lie on); the rest
// pose's tessellation, which a pose that comes back to rest must give again; and bit-equality
// across repeats and thread counts.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "physics/skinning.hpp"
#include "scenes/skinned_cage.hpp"
#include "subdiv/limit.hpp"

namespace mane::scenes {
namespace {

constexpr int kAround = 8;
constexpr int kAlong = 12;
constexpr float kRadius = 0.05f;  // metres
constexpr float kLength = 0.6f;   // metres
constexpr float kElbowY = 0.5f * kLength;
// Joint 1's weight rises smoothly from 0 at ring 4 to 1 at ring 8 (of rings 0..12).
constexpr int kBlendFirstRing = 4;
constexpr int kBlendLastRing = 8;
constexpr glm::vec2 kViewport{1280.0f, 720.0f};
constexpr float kTargetPixels = 1.0f;

/// Vertex (ring r, segment s) of the tube: ring r at height r·L/12, counter-clockwise from outside.
subdiv::Cage tubeCage() {
  subdiv::Cage cage;
  for (int r = 0; r <= kAlong; ++r)
    for (int s = 0; s < kAround; ++s) {
      const float angle = 2.0f * float(M_PI) * float(s) / float(kAround);
      cage.positions.emplace_back(kRadius * std::sin(angle), kLength * float(r) / float(kAlong),
                                  kRadius * std::cos(angle));
    }
  const auto at = [](int r, int s) { return std::uint32_t(r * kAround + s % kAround); };
  for (int r = 0; r < kAlong; ++r)
    for (int s = 0; s < kAround; ++s) {
      cage.faceSizes.push_back(4);
      cage.faceVertices.insert(cage.faceVertices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
    }
  return cage;
}

/// Two influences per vertex: joint 0 (the lower arm) and joint 1 (the upper), smoothstep across
/// the blend rings.
physics::SkinnedMeshData tubeSkin(physics::SkinningMethod method) {
  physics::SkinnedMeshData skin{.influencesPerVertex = 2, .jointCount = 2, .method = method};
  for (int r = 0; r <= kAlong; ++r) {
    const float t = std::clamp(float(r - kBlendFirstRing) / float(kBlendLastRing - kBlendFirstRing), 0.0f, 1.0f);
    const float upper = t * t * (3.0f - 2.0f * t);
    for (int s = 0; s < kAround; ++s) {
      skin.joints.insert(skin.joints.end(), {0u, 1u});
      skin.weights.insert(skin.weights.end(), {1.0f - upper, upper});
    }
  }
  return skin;
}

/// Joint 1 turned by `degrees` about the z axis through the elbow; joint 0 stays.
std::array<glm::mat4, 2> elbowBent(float degrees) {
  const glm::vec3 elbow(0.0f, kElbowY, 0.0f);
  const glm::mat4 upper = glm::translate(glm::mat4(1.0f), elbow) *
                          glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 0, 1)) *
                          glm::translate(glm::mat4(1.0f), -elbow);
  return {glm::mat4(1.0f), upper};
}

/// From the side: a camera 1 m along +z, 40° vertical field, the whole tube in view straight or
/// bent; the tube is about 100 pixels wide.
glm::mat4 sideView() {
  const glm::vec3 target(-0.05f, 0.3f, 0.0f);
  const glm::mat4 projection = glm::perspective(glm::radians(40.0f), kViewport.x / kViewport.y, 0.01f, 10.0f);
  return projection * glm::lookAt(target + glm::vec3(0.0f, 0.0f, 1.0f), target, glm::vec3(0, 1, 0));
}

std::unique_ptr<SkinnedCage> makeTube(physics::SkinningMethod method = physics::SkinningMethod::DualQuaternion,
                                      float targetPixels = kTargetPixels) {
  auto cage =
      SkinnedCage::create(tubeCage(), tubeSkin(method), {.maxPixelError = targetPixels}, {.keepPtexCoordinates = true});
  EXPECT_TRUE(cage.has_value()) << cage.error().message;
  return cage ? std::move(*cage) : nullptr;
}

struct Frame {
  Mesh mesh;
  std::vector<float> inverseRadius;
  bool written = false;
};

/// Poses `tube` with the elbow at `degrees` and tessellates it into `frame`, which keeps what
/// the last call wrote when this one writes nothing (as a renderer's mesh would).
Frame poseAndTessellate(SkinnedCage& tube, float degrees, Frame frame = {}, unsigned threads = 1) {
  const auto joints = elbowBent(degrees);
  auto posed = tube.pose(joints, {}, threads);
  EXPECT_TRUE(posed.has_value()) << posed.error().message;
  frame.written = tube.tessellate(sideView(), kViewport, frame.mesh, frame.inverseRadius, threads);
  return frame;
}

/// Triangles on the cage faces of the blend rings (quads only: ptex face = cage face, ring-major).
std::size_t elbowTriangles(const SkinnedCage& tube) {
  const subdiv::TessellatedMesh& mesh = tube.tessellation();
  return std::size_t(std::count_if(mesh.trianglePtexFaces.begin(), mesh.trianglePtexFaces.end(), [](std::uint32_t f) {
    const int ring = int(f) / kAround;
    return ring >= kBlendFirstRing && ring < kBlendLastRing;
  }));
}

glm::dvec2 toPixels(const glm::mat4& viewProjection, const glm::dvec3& p) {
  const glm::dvec4 clip = glm::dmat4(viewProjection) * glm::dvec4(p, 1.0);
  return (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(kViewport);
}

/// The largest pixel distance between the output edges and `surface` at the same ptex
/// parameter, 7 samples inside every edge.
double worstEdgeError(const subdiv::LimitSurface& surface, const subdiv::TessellatedMesh& mesh) {
  const glm::mat4 view = sideView();
  double worst = 0.0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = 3 * t + k, b = 3 * t + (k + 1) % 3;
      const glm::dvec3 pa(mesh.positions[mesh.indices[a]]), pb(mesh.positions[mesh.indices[b]]);
      const glm::dvec2 ua(mesh.cornerPtexCoordinates[a]), ub(mesh.cornerPtexCoordinates[b]);
      for (int s = 1; s < 8; ++s) {
        const double f = s / 8.0;
        const glm::dvec2 uv = glm::mix(ua, ub, f);
        const glm::dvec3 onSurface = surface.evaluatePosition(mesh.trianglePtexFaces[t], uv.x, uv.y);
        worst = std::max(worst, glm::length(toPixels(view, glm::mix(pa, pb, f)) - toPixels(view, onSurface)));
      }
    }
  return worst;
}

/// Edges with other than two triangles, leaving out the tube's two open ends (ptex v = 0 on the
/// first ring of faces, v = 1 on the last): 0 when the mesh has no cracks or T-junctions.
std::size_t unpairedInnerEdges(const subdiv::TessellatedMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  std::map<std::pair<std::uint32_t, std::uint32_t>, bool> atAnEnd;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const int ring = int(mesh.trianglePtexFaces[t]) / kAround;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = 3 * t + k, b = 3 * t + (k + 1) % 3;
      const auto edge = std::minmax(mesh.weldedVertex[mesh.indices[a]], mesh.weldedVertex[mesh.indices[b]]);
      ++uses[edge];
      const float va = mesh.cornerPtexCoordinates[a].y, vb = mesh.cornerPtexCoordinates[b].y;
      atAnEnd[edge] = (ring == 0 && va == 0.0f && vb == 0.0f) || (ring == kAlong - 1 && va == 1.0f && vb == 1.0f);
    }
  }
  return std::size_t(
      std::count_if(uses.begin(), uses.end(), [&](const auto& use) { return use.second != 2 && !atAnEnd[use.first]; }));
}

bool sameBits(const Mesh& a, const Mesh& b) {
  const auto equalBytes = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           std::equal(reinterpret_cast<const char*>(x.data()), reinterpret_cast<const char*>(x.data() + x.size()),
                      reinterpret_cast<const char*>(y.data()));
  };
  return equalBytes(a.positions, b.positions) && equalBytes(a.normals, b.normals) && equalBytes(a.uvs, b.uvs) &&
         a.indices == b.indices;
}

TEST(SkinnedCage, BendingTheElbowAddsTrianglesWhereTheCurvatureRose) {
  auto tube = makeTube();
  ASSERT_NE(tube, nullptr);
  const Frame rest = poseAndTessellate(*tube, 0.0f);
  const std::size_t restElbow = elbowTriangles(*tube);
  const Frame bent = poseAndTessellate(*tube, 90.0f);
  const std::size_t bentElbow = elbowTriangles(*tube);
  ASSERT_TRUE(rest.written && bent.written);
  // Measured: 256 triangles at rest, 947 bent within the blend rings; over the whole tube 768
  // and 1610 (the straight parts keep theirs). The straight tube is curved only around its
  // circumference; bent, the elbow's faces curve along the tube too, so the chords there need
  // more cells to stay within a pixel.
  EXPECT_GE(double(bentElbow), 2.0 * double(restElbow)) << "rest " << restElbow << ", bent " << bentElbow;
  RecordProperty("elbow_triangles_rest", int(restElbow));
  RecordProperty("elbow_triangles_bent", int(bentElbow));
  RecordProperty("triangles_rest", int(rest.mesh.triangleCount()));
  RecordProperty("triangles_bent", int(bent.mesh.triangleCount()));
}

TEST(SkinnedCage, TheTrianglesLieOnThePosedLimitSurfaceWithinTheTargetWithoutCracks) {
  for (const auto method : {physics::SkinningMethod::LinearBlend, physics::SkinningMethod::DualQuaternion}) {
    auto tube = makeTube(method);
    ASSERT_NE(tube, nullptr);
    const Frame bent = poseAndTessellate(*tube, 90.0f);
    ASSERT_TRUE(bent.written);
    const subdiv::TessellatedMesh& mesh = tube->tessellation();
    ASSERT_EQ(mesh.positions.size(), bent.mesh.positions.size());

    // The reference: the cage skinned by the skin alone and refined from scratch.
    physics::SkinnedMeshData data = tubeSkin(method);
    data.positions = tubeCage().positions;
    auto skin = physics::SkinnedMesh::create(std::move(data));
    ASSERT_TRUE(skin.has_value()) << skin.error().message;
    physics::DeformedSurface skinned;
    const auto joints = elbowBent(90.0f);
    ASSERT_TRUE(skin->deform(joints, {}, skinned).has_value());
    subdiv::Cage posedCage = tubeCage();
    posedCage.positions = skinned.positions;
    auto reference = subdiv::LimitSurface::create(posedCage);
    ASSERT_TRUE(reference.has_value()) << reference.error().message;

    // Every vertex at its ptex point of the reference surface: float rounding of a double
    // evaluation, far below a pixel (1 µm ≈ 0.001 px here).
    double worstOffset = 0.0;
    for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
      const glm::dvec2 uv(mesh.cornerPtexCoordinates[corner]);
      const glm::dvec3 onSurface = reference->evaluatePosition(mesh.trianglePtexFaces[corner / 3], uv.x, uv.y);
      worstOffset =
          std::max(worstOffset, glm::length(glm::dvec3(bent.mesh.positions[mesh.indices[corner]]) - onSurface));
    }
    EXPECT_LT(worstOffset, 1e-6);
    // Between the vertices, within the target (+10 %, the tessellator tests' bound).
    EXPECT_LE(worstEdgeError(*reference, mesh), 1.1 * kTargetPixels);
    // And no cracks where the bend made neighbouring faces split to different depths.
    EXPECT_EQ(unpairedInnerEdges(mesh), 0u);
  }
}

TEST(SkinnedCage, PosesAreDeterministicAcrossRepeatsAndThreadCounts) {
  // A quarter-pixel target: enough limit points that the tessellator gives the second thread
  // a share of them (it hands out points by the thousand).
  constexpr float kFine = 0.25f;
  auto one = makeTube(physics::SkinningMethod::DualQuaternion, kFine);
  auto two = makeTube(physics::SkinningMethod::DualQuaternion, kFine);
  ASSERT_NE(one, nullptr);
  ASSERT_NE(two, nullptr);
  const Frame first = poseAndTessellate(*one, 90.0f);
  (void)poseAndTessellate(*one, 30.0f);
  const Frame again = poseAndTessellate(*one, 90.0f);
  const Frame threaded = poseAndTessellate(*two, 90.0f, {}, 2);
  ASSERT_TRUE(first.written && again.written && threaded.written);
  ASSERT_GT(two->statistics().limitPoints, 2048u);
  EXPECT_TRUE(sameBits(first.mesh, again.mesh));
  EXPECT_TRUE(sameBits(first.mesh, threaded.mesh));
  EXPECT_EQ(first.inverseRadius, threaded.inverseRadius);
}

TEST(SkinnedCage, StraighteningGivesTheRestTessellationBack) {
  auto tube = makeTube();
  ASSERT_NE(tube, nullptr);
  Frame bind;
  ASSERT_TRUE(tube->tessellate(sideView(), kViewport, bind.mesh, bind.inverseRadius, 1));
  const Frame rest = poseAndTessellate(*tube, 0.0f, bind);
  const Frame bent = poseAndTessellate(*tube, 90.0f, rest);
  const Frame straightened = poseAndTessellate(*tube, 0.0f, bent);
  EXPECT_TRUE(straightened.written);
  // The same pose gives the same mesh: the tessellation depends on the pose, not on the ones
  // before it.
  EXPECT_TRUE(sameBits(rest.mesh, straightened.mesh));
  // Skinning by identity joints reproduces the bind pose up to rounding of the blend, which
  // may move a cell's error across the target; here it does not even change the count.
  EXPECT_EQ(bind.mesh.triangleCount(), straightened.mesh.triangleCount());
}

TEST(SkinnedCage, AHeldPoseKeepsItsTrianglesAndAMovedCageIsTessellatedAgain) {
  auto tube = makeTube();
  ASSERT_NE(tube, nullptr);
  const auto bent = elbowBent(90.0f);
  auto moved = tube->pose(bent, {}, 1);
  ASSERT_TRUE(moved.has_value());
  EXPECT_TRUE(*moved);
  Frame frame;
  EXPECT_TRUE(tube->tessellate(sideView(), kViewport, frame.mesh, frame.inverseRadius, 1));
  moved = tube->pose(bent, {}, 1);
  ASSERT_TRUE(moved.has_value());
  EXPECT_FALSE(*moved) << "the same pose leaves the cage where it was";
  EXPECT_FALSE(tube->tessellate(sideView(), kViewport, frame.mesh, frame.inverseRadius, 1));
  // A whole-body move changes no curvature but still moves the cage: tessellated again, since
  // the tessellator cannot tell a rigid move from a bend.
  const glm::mat4 shift = glm::translate(glm::mat4(1.0f), glm::vec3(0.001f, 0.0f, 0.0f));
  const std::array<glm::mat4, 2> shifted{shift * bent[0], shift * bent[1]};
  moved = tube->pose(shifted, {}, 1);
  ASSERT_TRUE(moved.has_value());
  EXPECT_TRUE(*moved);
  EXPECT_TRUE(tube->tessellate(sideView(), kViewport, frame.mesh, frame.inverseRadius, 1));
}

TEST(SkinnedCage, MorphTargetsMoveTheCageBeforeSkinning) {
  physics::SkinnedMeshData skin = tubeSkin(physics::SkinningMethod::LinearBlend);
  // A bulge: every vertex of the middle ring pushed 1 cm outwards.
  physics::MorphTarget bulge{.name = "bulge"};
  const subdiv::Cage cage = tubeCage();
  for (std::size_t v = 0; v < cage.positions.size(); ++v) {
    const bool middle = int(v) / kAround == kAlong / 2;
    bulge.positionDeltas.push_back(middle ? 0.2f * glm::vec3(cage.positions[v].x, 0.0f, cage.positions[v].z)
                                          : glm::vec3(0.0f));
  }
  skin.morphTargets.push_back(bulge);
  auto tube = SkinnedCage::create(cage, skin, {});
  ASSERT_TRUE(tube.has_value()) << tube.error().message;
  const auto rest = elbowBent(0.0f);
  const float weight = 1.0f;
  ASSERT_TRUE((*tube)->pose(rest, {&weight, 1}, 1).has_value());
  const glm::vec3 pushed = (*tube)->limit().cage().positions[std::size_t(kAlong / 2 * kAround)];
  EXPECT_NEAR(glm::length(glm::vec2(pushed.x, pushed.z)), 1.2f * kRadius, 1e-6f);
}

TEST(SkinnedCage, RejectsMismatchedOrBrokenInputWithAClearMessage) {
  physics::SkinnedMeshData skin = tubeSkin(physics::SkinningMethod::LinearBlend);
  skin.positions.assign(5, glm::vec3(0.0f));
  auto wrongCount = SkinnedCage::create(tubeCage(), skin, {});
  ASSERT_FALSE(wrongCount.has_value());
  EXPECT_EQ(wrongCount.error().message, "skinned cage: the skin has 5 bind positions; the cage has 104 vertices");

  skin = tubeSkin(physics::SkinningMethod::LinearBlend);
  skin.joints[7] = 2;
  auto badJoint = SkinnedCage::create(tubeCage(), skin, {});
  ASSERT_FALSE(badJoint.has_value());
  EXPECT_NE(badJoint.error().message.find("skinned cage: vertex 3 is bound to joint 2"), std::string::npos)
      << badJoint.error().message;

  subdiv::Cage broken = tubeCage();
  broken.faceVertices[0] = 999;
  auto badCage = SkinnedCage::create(broken, tubeSkin(physics::SkinningMethod::LinearBlend), {});
  ASSERT_FALSE(badCage.has_value());
  EXPECT_EQ(badCage.error().message.rfind("skinned cage: ", 0), 0u) << badCage.error().message;

  auto tube = makeTube();
  ASSERT_NE(tube, nullptr);
  const std::array<glm::mat4, 1> tooFew{glm::mat4(1.0f)};
  auto wrongJoints = tube->pose(tooFew, {}, 1);
  ASSERT_FALSE(wrongJoints.has_value());
  EXPECT_EQ(wrongJoints.error().message, "skinned cage: deforming a skinned mesh needs 2 joint matrices; got 1");
  const float weight = 0.5f;
  auto wrongWeights = tube->pose(elbowBent(0.0f), {&weight, 1}, 1);
  ASSERT_FALSE(wrongWeights.has_value());
  EXPECT_NE(wrongWeights.error().message.find("morph weights"), std::string::npos) << wrongWeights.error().message;
  auto notFinite = elbowBent(0.0f);
  notFinite[1][3][0] = std::nanf("");
  auto nan = tube->pose(notFinite, {}, 1);
  ASSERT_FALSE(nan.has_value());
  EXPECT_NE(nan.error().message.find("NaN"), std::string::npos) << nan.error().message;
}

}  // namespace
}  // namespace mane::scenes
