// A skinned, morphing, animated character in the running World (scenes/README.md,
// "Characters"): hair roots, cloth pins and joint-borne colliders follow the body over whole
// clips and a cross-fade, the simulation is deterministic, and bad references are clear errors.
// The references are computed here from the character's file on its own: the surface points
// from the triangles deformed by physics::SkinnedMesh, the joints from the skeleton's pose.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"

namespace mane::scenes {
namespace {

// The RobotExpressive character walking, then dancing after a 0.3 s cross-fade, the Surprised
// expression keyed in and out; a crest of hair on its head with a field and joint capsules, a
// cape pinned across its back colliding with capsules along its limbs.
std::string robotScene(const std::string& clip = "Dance", const std::string& target = "Surprised",
                       const std::string& part = "robot/Head", const std::string& joint = "Neck") {
  return R"({
  "name": "robot test",
  "camera": { "position": [2.4, 1.5, 4.3], "target": [0.0, 0.92, 0.0] },
  "lights": [ { "kind": "directional", "direction": [0, -1, 0] } ],
  "materials": [ { "name": "main", "kind": "lambert" } ],
  "characters": [ {
    "name": "robot",
    "source": "characters/RobotExpressive/RobotExpressive.glb",
    "transform": { "scale": 0.45 },
    "material": "main",
    "skinning": "dual_quaternion",
    "clips": [ { "clip": "Walking", "start": 0.0 }, { "clip": ")" + clip + R"(", "start": 0.6, "cross_fade": 0.3 } ],
    "morphs": [ { "target": ")" + target + R"(", "keys": [ { "time": 0.2, "weight": 0 }, { "time": 0.8, "weight": 1 } ] } ]
  } ],
  "grooms": [ {
    "name": "crest", "source": "procedural", "attached_mesh": ")" + part + R"(", "strands": 200, "length": 0.2,
    "scalp": { "top_fraction": 0.2, "min_up": 0.5 },
    "colliders": { "sdf": { "mesh": "robot/Head", "resolution": 24 },
                   "capsules": [ { "joint": ")" + joint + R"(", "to_joint": "Head", "radius": 0.09 },
                                 { "joint": "Head", "a": [0, 0, 0], "b": [0, 0.1, 0], "radius": 0.05 } ],
                   "thickness": 0.003 }
  } ],
  "cloths": [ {
    "name": "cape", "source": "procedural:grid", "attached_mesh": "robot/Torso",
    "transform": { "translation": [0.0, 1.12, -0.2], "scale": 0.7 },
    "colliders": { "capsules": [ { "joint": "Hips", "to_joint": "Neck", "radius": 0.2 } ], "thickness": 0.01 }
  } ]
})";
}

Result<World> robotWorld(const std::string& text) {
  auto scene = parseScene(text, std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "robot_test.json");
  if (!scene) return std::unexpected(scene.error());
  return World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
}

glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

TEST(CharacterWorld, RootsPinsAndCollidersFollowTheBodyOverWholeClips) {
  auto world = robotWorld(robotScene());
  ASSERT_TRUE(world) << world.error().message;
  ASSERT_EQ(world->simulatedGroomCount(), 1u);
  ASSERT_EQ(world->characters().size(), 1u);
  const SceneCharacter& robot = world->characters()[0];
  auto neck = robot.findJoint("Neck");
  auto head = robot.findJoint("Head");
  ASSERT_TRUE(neck && head);

  float rootError = 0.0f, pinError = 0.0f, capsuleError = 0.0f, rootTravel = 0.0f;
  auto rest = world->boundRoots(0);
  ASSERT_TRUE(rest) << rest.error().message;
  // Walking's 0.96 s loop once and more, the cross-fade and the dance after it, in frames of
  // exactly two fixed steps (the step is a float), so the simulation ends each frame at the
  // frame's time: roots and pins must then be on their targets.
  const double frameDt = 2.0 * static_cast<double>(world->scene().simulation.stepSeconds);
  for (int frame = 0; frame < 84; ++frame) {
    ASSERT_TRUE(world->advance(frameDt, 2));
    const physics::HairSystem& hair = world->simulatedGroom(0);
    auto roots = world->boundRoots(0);
    ASSERT_TRUE(roots) << roots.error().message;
    for (std::size_t s = 0; s < hair.strandCount(); ++s) {
      rootError = std::max(rootError, glm::distance(hair.strandPositions(s).front(), (*roots)[s]));
      rootTravel = std::max(rootTravel, glm::distance((*roots)[s], (*rest)[s]));
      for (const glm::vec3& p : hair.strandPositions(s)) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
    }
    auto pins = world->boundPins(0);
    ASSERT_TRUE(pins) << pins.error().message;
    const physics::Cloth& cape = world->cloths()[0].cloth();
    for (std::size_t i = 0; i < cape.pinnedVertices().size(); ++i)
      pinError = std::max(pinError, glm::distance(cape.particles().positions[cape.pinnedVertices()[i]], (*pins)[i]));
    // The joint capsule runs from the neck's origin to the head's, in the world.
    const glm::mat4 headFrame = robot.partFrame(*robot.findPart("Head"));
    const physics::CapsuleCollider& capsule = hair.colliders().capsules.at(0);
    capsuleError = std::max({capsuleError,
                             glm::distance(transformPoint(headFrame, capsule.a), glm::vec3(robot.jointFrame(*neck)[3])),
                             glm::distance(transformPoint(headFrame, capsule.b), glm::vec3(robot.jointFrame(*head)[3]))});
  }
  std::printf("largest distance from target: roots %.3g m, pins %.3g m, capsule ends %.3g m; roots travelled %.3g m\n",
              double(rootError), double(pinError), double(capsuleError), double(rootTravel));
  EXPECT_LE(rootError, 1e-5f);
  EXPECT_LE(pinError, 1e-5f);
  EXPECT_LE(capsuleError, 1e-5f);
  // The body did move: the roots went far, so following it is not trivially met.
  EXPECT_GT(rootTravel, 0.05f);
}

TEST(CharacterWorld, SameStateForAnyThreadCountAndRun) {
  std::vector<std::uint64_t> hashes;
  for (unsigned threads : {1u, 2u, 4u, 1u}) {
    auto world = robotWorld(robotScene());
    ASSERT_TRUE(world) << world.error().message;
    for (int frame = 0; frame < 48; ++frame) ASSERT_TRUE(world->advance(1.0 / 60.0, threads));
    hashes.push_back(world->stateHash());
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
  EXPECT_EQ(hashes[0], hashes[3]);
}

void expectError(const std::string& text, std::initializer_list<const char*> parts) {
  auto world = robotWorld(text);
  ASSERT_FALSE(world);
  for (const char* part : parts) EXPECT_NE(world.error().message.find(part), std::string::npos) << world.error().message;
}

TEST(CharacterWorld, BadReferencesAreClearErrors) {
  expectError(robotScene("Moonwalk"), {"RobotExpressive.glb", "Moonwalk", "'Dance'"});
  expectError(robotScene("Dance", "Bored"), {"RobotExpressive.glb", "Bored", "'Surprised'"});
  expectError(robotScene("Dance", "Surprised", "robot/Hat"), {"groom crest", "robot/Hat", "'robot/Head'"});
  // A drawn primitive is not a part: roots and pins bind to whole parts.
  expectError(robotScene("Dance", "Surprised", "robot/Head#1"), {"groom crest", "robot/Head#1", "'robot/Head'"});
  expectError(robotScene("Dance", "Surprised", "robot/Head", "Nek"), {"groom crest", "Nek", "'Neck'"});
}

}  // namespace
}  // namespace mane::scenes
