// Embedding mane_physics in a host engine that animates and skins its characters itself.
//
// The host here owns a furry arm: a tube mesh, a two-bone skeleton (shoulder, elbow) and its own
// linear blend skinning, written below in plain GLM. The physics never sees the skeleton. Each
// frame the host hands it what it needs, in world space or in the frame of one bone:
//   - the hair's root targets: where each strand's root is on the skinned skin, and the skin's
//     normal there (SurfaceBinding::evaluate on the host's deformed vertices);
//   - the hair's "head" transform: the upper arm bone, which carries the colliders;
//   - the colliders: one capsule per bone, re-expressed in the upper arm's frame;
//   - a cloth flag hanging from the arm: its pinned top row follows points bound to the skin, its
//     colliders are the same capsules.
// Two seconds at 60 frames per second on two threads; prints checks and the state hashes.
// Uses nothing but mane_physics (GLM and the standard library). All motion is built from exact
// arithmetic and square roots (no libm sin/cos), so the hashes are the same on every platform.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "physics/cloth.hpp"
#include "physics/colliders.hpp"
#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/surface_binding.hpp"

namespace {

using namespace mane;
using namespace mane::physics;

// ---- The host's side: its own mesh, skeleton and skinning. Nothing here is mane's. ----------

constexpr float kBoneLength = 0.3f;  // upper arm and forearm, metres, along +x in the bind pose
constexpr float kArmRadius = 0.04f;  // metres
constexpr int kRings = 25;           // vertex rings along the arm
constexpr int kSides = 12;           // vertices per ring, 30° apart

// The arm in its bind pose (the shoulder at the origin, the arm along +x), with per-vertex
// weights: the forearm bone's share (the upper arm bone has the rest).
struct HostArm {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices;  // counter-clockwise seen from outside
  std::vector<float> forearmWeight;
};

HostArm makeArm() {
  // Cosines of 0°, 30°, …, 330°; the sines are the same list three places on.
  const float h = std::sqrt(3.0f) / 2.0f;
  const float cosine[kSides] = {1.0f, h, 0.5f, 0.0f, -0.5f, -h, -1.0f, -h, -0.5f, 0.0f, 0.5f, h};
  HostArm arm;
  for (int r = 0; r < kRings; ++r) {
    const float x = 2.0f * kBoneLength * static_cast<float>(r) / static_cast<float>(kRings - 1);
    for (int k = 0; k < kSides; ++k) {
      const glm::vec3 around(0.0f, cosine[k], cosine[(k + 9) % kSides]);  // (cos, sin) in y, z
      arm.positions.push_back(glm::vec3(x, 0.0f, 0.0f) + kArmRadius * around);
      arm.normals.push_back(around);
      // The elbow's 10 cm either side of the joint blends the two bones.
      arm.forearmWeight.push_back(std::clamp((x - kBoneLength + 0.05f) / 0.1f, 0.0f, 1.0f));
    }
  }
  for (std::uint32_t r = 0; r + 1 < kRings; ++r)
    for (std::uint32_t k = 0; k < kSides; ++k) {
      const std::uint32_t a = r * kSides + k, b = r * kSides + (k + 1) % kSides, c = a + kSides, d = b + kSides;
      arm.indices.insert(arm.indices.end(), {a, c, b, b, c, d});
    }
  return arm;
}

// A rotation about z whose half-angle has tangent `t` (rational form: no sin or cos needed).
glm::mat4 rotationZ(float t) {
  const float c = (1.0f - t * t) / (1.0f + t * t), s = 2.0f * t / (1.0f + t * t);
  glm::mat4 m(1.0f);
  m[0][0] = c, m[0][1] = s, m[1][0] = -s, m[1][1] = c;
  return m;
}

// The skeleton at frame `frame`: per bone, its skinning matrix (bind pose → world).
struct ArmPose {
  glm::mat4 upperArm;
  glm::mat4 forearm;
};

ArmPose poseAt(int frame) {
  // A triangle wave 0 → 1 → 0 over 120 frames: the arm lifts and the elbow bends, then back.
  const float wave = static_cast<float>(frame % 120 < 60 ? frame % 120 : 120 - frame % 120) / 60.0f;
  ArmPose pose;
  pose.upperArm = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.4f, 0.0f)) * rotationZ(0.3f * wave);
  const glm::vec3 elbow(kBoneLength, 0.0f, 0.0f);
  pose.forearm = pose.upperArm * glm::translate(glm::mat4(1.0f), elbow) * rotationZ(0.5f * wave) *
                 glm::translate(glm::mat4(1.0f), -elbow);
  return pose;
}

// Linear blend skinning: blended matrix per vertex; normals by its linear part (the bones are
// rigid, so no inverse transpose is needed), renormalised.
void skin(const HostArm& arm, const ArmPose& pose, std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  positions.resize(arm.positions.size());
  normals.resize(arm.positions.size());
  for (std::size_t v = 0; v < arm.positions.size(); ++v) {
    const float w = arm.forearmWeight[v];
    const glm::mat4 m = pose.upperArm * (1.0f - w) + pose.forearm * w;
    positions[v] = glm::vec3(m * glm::vec4(arm.positions[v], 1.0f));
    normals[v] = glm::normalize(glm::mat3(m) * arm.normals[v]);
  }
}

// ---- The physics side. ------------------------------------------------------------------------

// One capsule per bone in the bind pose, slightly inside the skin so roots and pins sit outside.
const CapsuleCollider kUpperArmCapsule{{0.0f, 0.0f, 0.0f}, {kBoneLength, 0.0f, 0.0f}, 0.035f};
const CapsuleCollider kForearmCapsule{{kBoneLength, 0.0f, 0.0f}, {2.0f * kBoneLength, 0.0f, 0.0f}, 0.035f};

// The capsules in the upper arm's frame (the hair's head frame, the cloth's body frame): the
// upper arm's own is fixed there; the forearm's moves by upperArm⁻¹ · forearm.
ColliderSet armColliders(const ArmPose& pose) {
  const glm::mat4 relative = glm::inverse(pose.upperArm) * pose.forearm;
  auto place = [&](const glm::vec3& p) { return glm::vec3(relative * glm::vec4(p, 1.0f)); };
  ColliderSet set;
  set.capsules = {kUpperArmCapsule, {place(kForearmCapsule.a), place(kForearmCapsule.b), kForearmCapsule.radius}};
  set.friction = 0.2f;
  set.thickness = 0.002f;
  return set;
}

bool check(const Result<void>& result, const char* what) {
  if (!result) std::fprintf(stderr, "%s: %s\n", what, result.error().message.c_str());
  return result.has_value();
}

}  // namespace

int main() {
  constexpr unsigned kThreads = 2;
  constexpr int kFrames = 120;
  constexpr double kFrameDt = 1.0 / 60.0;
  const HostArm arm = makeArm();

  // Load time: choose roots on the top of the arm (a point inside every upward-facing triangle
  // but the ends'), bind them to the bind-pose mesh, grow strands along the skin's normal.
  std::vector<glm::vec3> roots;
  for (std::size_t t = 0; t < arm.indices.size() / 3; t += 2) {
    const glm::vec3 a = arm.positions[arm.indices[3 * t]], b = arm.positions[arm.indices[3 * t + 1]],
                    c = arm.positions[arm.indices[3 * t + 2]];
    const glm::vec3 centre = (a + b + c) / 3.0f;
    if (centre.y > 0.02f && centre.x > 0.03f && centre.x < 2.0f * kBoneLength - 0.03f) roots.push_back(centre);
  }
  auto rootBinding = SurfaceBinding::create(arm.positions, arm.indices, roots);
  if (!rootBinding) return std::fprintf(stderr, "roots: %s\n", rootBinding.error().message.c_str()), EXIT_FAILURE;
  std::vector<glm::vec3> rootTargets(roots.size()), rootNormals(roots.size());
  // The rest normals come from the same evaluation the frames use, on the bind pose.
  if (!check(rootBinding->evaluate(arm.positions, arm.normals, rootTargets, rootNormals, {}), "rest normals"))
    return EXIT_FAILURE;
  GroomSettings groom;
  groom.seed = 5;
  groom.particlesPerStrand = 10;
  groom.strandLength = 0.12f;  // metres
  auto strands = generateGroomFromRoots(groom, roots, rootNormals);
  if (!strands) return std::fprintf(stderr, "groom: %s\n", strands.error().message.c_str()), EXIT_FAILURE;

  // Hair and cloth are created in the bind pose's space placed by the upper arm at frame 0.
  ArmPose pose = poseAt(0);
  // The host's workers could run the parallel loops (a TaskRunner over its job system); here the
  // built-in pool does.
  const TaskRunner tasks = builtInTaskRunner(kThreads);
  HairSettings hairSettings;  // solver: 1/120 s steps, gravity −9.81 m/s² along y
  hairSettings.strands = std::move(*strands);
  hairSettings.solver.shapeStiffness = 0.3f;
  hairSettings.headTransform = pose.upperArm;
  hairSettings.rootRestNormals = rootNormals;
  hairSettings.tasks = tasks;
  auto hair = HairSystem::create(hairSettings);
  if (!hair) return std::fprintf(stderr, "hair: %s\n", hair.error().message.c_str()), EXIT_FAILURE;

  // A 0.5 m × 0.2 m flag under the arm, its top row pinned to the skin's bottom line.
  constexpr int kFlagColumns = 11, kFlagRows = 6;
  std::vector<glm::vec3> flag;
  std::vector<std::uint32_t> flagTriangles, flagPins;
  for (int j = 0; j < kFlagRows; ++j)
    for (int i = 0; i < kFlagColumns; ++i)
      flag.push_back({0.05f + 0.05f * static_cast<float>(i), -kArmRadius - 0.04f * static_cast<float>(j), 0.0f});
  for (std::uint32_t j = 0; j + 1 < kFlagRows; ++j)
    for (std::uint32_t i = 0; i + 1 < kFlagColumns; ++i) {
      const std::uint32_t a = j * kFlagColumns + i, b = a + 1, c = a + kFlagColumns, d = c + 1;
      flagTriangles.insert(flagTriangles.end(), {a, c, b, b, c, d});
    }
  for (std::uint32_t i = 0; i < kFlagColumns; ++i) flagPins.push_back(i);
  ClothSettings clothSettings;
  clothSettings.solver.constraintIterations = 8;
  clothSettings.positions = flag;
  clothSettings.triangles = flagTriangles;
  clothSettings.pinnedVertices = flagPins;
  clothSettings.bodyTransform = pose.upperArm;
  clothSettings.tasks = tasks;
  auto cloth = Cloth::create(clothSettings);
  if (!cloth) return std::fprintf(stderr, "cloth: %s\n", cloth.error().message.c_str()), EXIT_FAILURE;
  // The pins bound to the arm's skin like the roots (pinnedVertices() gives their order).
  std::vector<glm::vec3> pinRest;
  for (std::uint32_t v : cloth->pinnedVertices()) pinRest.push_back(flag[v]);
  auto pinBinding = SurfaceBinding::create(arm.positions, arm.indices, pinRest);
  if (!pinBinding) return std::fprintf(stderr, "pins: %s\n", pinBinding.error().message.c_str()), EXIT_FAILURE;
  std::vector<glm::vec3> pinTargets(pinRest.size());

  // Frames: the host animates and skins, then hands the physics its targets and transforms.
  std::vector<glm::vec3> skinPositions, skinNormals;
  float worstRoot = 0.0f, worstPin = 0.0f;
  for (int frame = 1; frame <= kFrames; ++frame) {
    pose = poseAt(frame);
    skin(arm, pose, skinPositions, skinNormals);
    const ColliderSet colliders = armColliders(pose);
    if (!check(rootBinding->evaluate(skinPositions, skinNormals, rootTargets, rootNormals, {}), "roots") ||
        !check(hair->setHeadTransform(pose.upperArm), "head") || !check(hair->setColliders(colliders), "colliders") ||
        !check(hair->setRootTargets(rootTargets, rootNormals), "root targets") ||
        !check(pinBinding->evaluate(skinPositions, {}, pinTargets, {}, {}), "pins") ||
        !check(cloth->setBodyTransform(pose.upperArm), "body") || !check(cloth->setColliders(colliders), "colliders") ||
        !check(cloth->setPinTargets(pinTargets), "pin targets") || !check(hair->advance(kFrameDt), "hair") ||
        !check(cloth->advance(kFrameDt), "cloth"))
      return EXIT_FAILURE;
    for (std::size_t s = 0; s < hair->strandCount(); ++s)
      worstRoot = std::max(worstRoot, glm::distance(hair->strandPositions(s)[0], rootTargets[s]));
    for (std::size_t p = 0; p < pinTargets.size(); ++p)
      worstPin =
          std::max(worstPin, glm::distance(cloth->particles().positions[cloth->pinnedVertices()[p]], pinTargets[p]));
  }

  std::printf("%zu strands, %zu cloth pins, %d frames on %u threads\n", hair->strandCount(), pinTargets.size(), kFrames,
              kThreads);
  std::printf("largest root-to-target distance after a frame: %.3g m\n", static_cast<double>(worstRoot));
  std::printf("largest pin-to-target distance after a frame: %.3g m\n", static_cast<double>(worstPin));
  std::printf("hair state hash: %016llx\n", static_cast<unsigned long long>(hair->stateHash()));
  std::printf("cloth state hash: %016llx\n", static_cast<unsigned long long>(cloth->stateHash()));
  // Roots land on their targets up to a rounding step; pins exactly (Cloth::setPinTargets).
  return worstRoot <= 1e-6f && worstPin == 0.0f ? EXIT_SUCCESS : EXIT_FAILURE;
}
