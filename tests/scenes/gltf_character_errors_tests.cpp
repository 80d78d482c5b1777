// loadCharacter on small hand-written glTF files (JSON with the buffer as a base64 data URI,
// written to a scratch directory): a valid two-joint rig loads and rests where its bind pose
// says; each kind of bad input gives an error that names the file and the element, and no
// character.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenes/gltf_character.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t chunk = (std::uint32_t(bytes[i]) << 16) |
                                (i + 1 < bytes.size() ? std::uint32_t(bytes[i + 1]) << 8 : 0u) |
                                (i + 2 < bytes.size() ? std::uint32_t(bytes[i + 2]) : 0u);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

/// A skinned, morphing, animated rig whose parts the tests break one at a time.
///   nodes: 0 Root → 1 Upper (joint 0) → 2 Lower (joint 1, 1 m up); 3 Body (mesh 0, skin 0)
///   mesh 0 'Body': a triangle bound to both joints, one morph target 'Smile'
///   animation 0 'Wave': LINEAR rotation of node 2 at 0, 1, 2 s
struct Rig {
  std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 2, 0};
  std::vector<std::uint8_t> joints = {0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0};
  std::vector<float> weights = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0, 1, 0, 0};
  std::vector<float> smileDeltas = {0, 0.1f, 0, 0, 0.1f, 0, 0, 0, 0};
  // Joint 0 binds at the origin (identity); joint 1 one metre up (inverse: 1 m down).
  std::vector<float> inverseBind = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  std::vector<float> times = {0, 1, 2};
  std::vector<float> rotations = {0, 0, 0, 1, 0, 0, 0.7071068f, 0.7071068f, 0, 0, 1, 0};

  /// The file's JSON; tests edit it further before writing.
  [[nodiscard]] nlohmann::json json() const {
    std::vector<std::uint8_t> bin;
    nlohmann::json views = nlohmann::json::array();
    nlohmann::json accessors = nlohmann::json::array();
    const auto add = [&](const void* data, std::size_t bytes, int componentType, std::size_t count, const char* type) {
      while (bin.size() % 4 != 0) bin.push_back(0);
      views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
      const auto* p = static_cast<const std::uint8_t*>(data);
      bin.insert(bin.end(), p, p + bytes);
      accessors.push_back(
          {{"bufferView", views.size() - 1}, {"componentType", componentType}, {"count", count}, {"type", type}});
    };
    add(positions.data(), positions.size() * 4, 5126, positions.size() / 3, "VEC3");         // 0
    add(joints.data(), joints.size(), 5121, joints.size() / 4, "VEC4");                      // 1
    add(weights.data(), weights.size() * 4, 5126, weights.size() / 4, "VEC4");               // 2
    add(smileDeltas.data(), smileDeltas.size() * 4, 5126, smileDeltas.size() / 3, "VEC3");   // 3
    add(inverseBind.data(), inverseBind.size() * 4, 5126, inverseBind.size() / 16, "MAT4");  // 4
    add(times.data(), times.size() * 4, 5126, times.size(), "SCALAR");                       // 5
    add(rotations.data(), rotations.size() * 4, 5126, rotations.size() / 4, "VEC4");         // 6
    return {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 3}}}}},
        {"nodes",
         {{{"name", "Root"}, {"children", {1}}},
          {{"name", "Upper"}, {"children", {2}}},
          {{"name", "Lower"}, {"translation", {0, 1, 0}}},
          {{"name", "Body"}, {"mesh", 0}, {"skin", 0}}}},
        {"skins", {{{"joints", {1, 2}}, {"inverseBindMatrices", 4}}}},
        {"meshes",
         {{{"name", "Body"},
           {"primitives",
            {{{"attributes", {{"POSITION", 0}, {"JOINTS_0", 1}, {"WEIGHTS_0", 2}}}, {"targets", {{{"POSITION", 3}}}}}}},
           {"weights", {0.0}},
           {"extras", {{"targetNames", {"Smile"}}}}}}},
        {"animations",
         {{{"name", "Wave"},
           {"samplers", {{{"input", 5}, {"output", 6}, {"interpolation", "LINEAR"}}}},
           {"channels", {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}}}}}},
        {"accessors", accessors},
        {"bufferViews", views},
        {"buffers", {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}}},
    };
  }
};

class CharacterErrors : public ::testing::Test {
protected:
  /// Loads `json` from rig.gltf in the scratch directory.
  Result<Character> load(const nlohmann::json& json) {
    file_ = scratch_.write("rig.gltf", json.dump());
    return loadCharacter(file_);
  }

  /// Loads `json`, expects a failure whose message starts with the file and holds every part.
  void expectError(const nlohmann::json& json, const std::vector<std::string>& parts) {
    auto character = load(json);
    ASSERT_FALSE(character) << "loaded although it should not";
    const std::string& message = character.error().message;
    EXPECT_EQ(message.rfind(file_.string() + ": ", 0), 0u) << message;
    for (const std::string& part : parts) EXPECT_THAT(message, HasSubstr(part));
  }

  ScratchDir scratch_;
  std::filesystem::path file_;
};

TEST_F(CharacterErrors, TheValidRigLoadsAndRestsInItsBindPose) {
  auto character = load(Rig{}.json());
  ASSERT_TRUE(character) << character.error().message;
  ASSERT_EQ(character->meshes.size(), 1u);
  EXPECT_EQ(character->meshes[0].skin, 0);
  EXPECT_EQ(character->skins[0].joints, (std::vector<int>{1, 2}));
  auto clip = character->findClip("Wave");
  ASSERT_TRUE(clip) << clip.error().message;
  EXPECT_EQ((*clip)->duration(), 2.0f);
  // The inverse bind matrices undo the joints' rest transforms: every joint matrix is the
  // identity, so the rest pose gives the file's positions.
  const physics::Pose rest = character->skeleton.restPose();
  auto world = character->skeleton.worldMatrices(rest);
  ASSERT_TRUE(world);
  auto joints = character->jointMatrices(0, *world);
  ASSERT_TRUE(joints);
  physics::DeformedSurface out;
  ASSERT_TRUE(character->meshes[0].surface.deform(*joints, rest.morphWeights[3], out));
  EXPECT_EQ(out.positions[2], glm::vec3(0.0f, 2.0f, 0.0f));
}

TEST_F(CharacterErrors, WithoutInverseBindMatricesEveryJointUsesTheIdentity) {
  nlohmann::json json = Rig{}.json();
  json["skins"][0].erase("inverseBindMatrices");
  auto character = load(json);
  ASSERT_TRUE(character) << character.error().message;
  for (const glm::mat4& m : character->skins[0].inverseBindMatrices) EXPECT_EQ(m, glm::mat4(1.0f));
}

TEST_F(CharacterErrors, WeightsSummingToZeroNameTheMeshPrimitiveAndVertex) {
  Rig rig;
  std::fill(rig.weights.begin() + 4, rig.weights.begin() + 8, 0.0f);
  expectError(rig.json(), {"mesh 0 ('Body') primitive 0 vertex 1", "sum to 0"});
}

TEST_F(CharacterErrors, AJointIndexPastTheSkinsJointsIsNamed) {
  Rig rig;
  rig.joints[8] = 5;
  expectError(rig.json(), {"mesh 0 ('Body') primitive 0 vertex 2", "joint 5", "skin 0 has 2 joints"});
}

TEST_F(CharacterErrors, AnInverseBindAccessorThatIsNotInTheFileIsNamed) {
  nlohmann::json json = Rig{}.json();
  json["skins"][0]["inverseBindMatrices"] = 42;
  expectError(json, {"skin 0 inverseBindMatrices", "accessor 42"});
}

TEST_F(CharacterErrors, TooFewOrMistypedInverseBindMatricesAreNamed) {
  nlohmann::json json = Rig{}.json();
  json["accessors"][4]["count"] = 1;
  expectError(json, {"skin 0 inverseBindMatrices (accessor 4) holds 1 matrices for 2 joints"});
  json = Rig{}.json();
  json["accessors"][4]["type"] = "VEC4";
  json["accessors"][4]["count"] = 8;
  expectError(json, {"skin 0 inverseBindMatrices (accessor 4)", "expected 16"});
}

TEST_F(CharacterErrors, NonFiniteKeyframesAreNamed) {
  Rig rig;
  rig.rotations[5] = std::numeric_limits<float>::quiet_NaN();
  expectError(rig.json(), {"animation 0 ('Wave') channel 0 (sampler 0)", "NaN or infinite value at keyframe 1"});
  rig = Rig{};
  rig.times[2] = std::numeric_limits<float>::infinity();
  expectError(rig.json(), {"animation 0 ('Wave') channel 0", "NaN or infinite time at keyframe 2"});
}

TEST_F(CharacterErrors, KeyTimesThatDoNotIncreaseAreNamed) {
  Rig rig;
  rig.times = {0.0f, 1.0f, 0.5f};
  expectError(rig.json(), {"animation 0 ('Wave') channel 0", "do not increase: keyframe 2"});
}

TEST_F(CharacterErrors, AnOutputCountThatDoesNotMatchTheKeysIsNamed) {
  nlohmann::json json = Rig{}.json();
  json["accessors"][6]["count"] = 2;
  expectError(json, {"animation 0 ('Wave') channel 0", "8 floats for 3 keyframes; expected 12"});
}

TEST_F(CharacterErrors, ClipAndMorphTargetNamesThatAreNotThereAreNamed) {
  auto character = load(Rig{}.json());
  ASSERT_TRUE(character) << character.error().message;
  auto clip = character->findClip("Run");
  ASSERT_FALSE(clip);
  EXPECT_THAT(clip.error().message, HasSubstr(file_.string() + ": no animation named 'Run'; the file has 'Wave'"));
  auto target = character->findMorphTarget(0, "Frown");
  ASSERT_FALSE(target);
  EXPECT_THAT(target.error().message,
              HasSubstr(file_.string() + ": mesh 'Body' has no morph target named 'Frown'; it has 'Smile'"));
  auto smile = character->findMorphTarget(0, "Smile");
  ASSERT_TRUE(smile);
  EXPECT_EQ(*smile, 0u);
}

TEST_F(CharacterErrors, OtherBrokenStructureIsNamed) {
  nlohmann::json json = Rig{}.json();
  json["nodes"][2]["children"] = {1};  // Upper → Lower → Upper
  expectError(json, {"node 1", "two parents"});

  json = Rig{}.json();
  json["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0");
  expectError(json, {"mesh 0 ('Body') primitive 0 has JOINTS_0 without WEIGHTS_0"});

  json = Rig{}.json();
  json["animations"][0]["channels"][0]["target"] = {{"node", 1}, {"path", "weights"}};
  expectError(json, {"animation 0 ('Wave') channel 0 animates the morph weights of node 1"});

  json = Rig{}.json();
  json["meshes"][0]["extras"]["targetNames"] = {"Smile", "Frown"};
  expectError(json, {"mesh 0 ('Body') extras.targetNames must be an array of 1 names"});

  json = Rig{}.json();
  json["meshes"][0]["weights"] = {0.0, 1.0};
  expectError(json, {"mesh 0 ('Body') has 2 morph weights for 1 morph targets"});

  json = Rig{}.json();
  json["animations"][0]["samplers"][0]["interpolation"] = "BEZIER";
  expectError(json, {"sampler 0) has interpolation 'BEZIER'"});
}

}  // namespace
}  // namespace mane::scenes
