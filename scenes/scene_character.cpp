#include "scenes/scene_character.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

namespace mane::scenes {
namespace {

// "'a', 'b', 'c'" for messages.
std::string quoted(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "'" : ", '") + name + "'";
  return list.empty() ? "none" : list;
}

// `b` blended over `a` by `w` ∈ [0, 1]: translations, scales and morph weights linearly,
// rotations along the shorter arc (a cross-fade between two clips).
void blendInto(const physics::Pose& a, physics::Pose& b, float w) {
  for (std::size_t n = 0; n < b.local.size(); ++n) {
    physics::NodeTransform& to = b.local[n];
    const physics::NodeTransform& from = a.local[n];
    to.translation = glm::mix(from.translation, to.translation, w);
    to.scale = glm::mix(from.scale, to.scale, w);
    to.rotation = glm::normalize(glm::slerp(from.rotation, to.rotation, w));
    for (std::size_t k = 0; k < b.morphWeights[n].size(); ++k)
      b.morphWeights[n][k] = glm::mix(a.morphWeights[n][k], b.morphWeights[n][k], w);
  }
}

// The joint whose weights move most of the mesh (the lowest such node on a tie), or the node it
// rides when it has no skin.
int dominantNode(const Character& character, const CharacterMesh& mesh) {
  if (mesh.skin < 0) return mesh.node;
  const CharacterSkin& skin = character.skins[static_cast<std::size_t>(mesh.skin)];
  const physics::SkinnedMeshData& data = mesh.surface.data();
  std::vector<double> total(skin.joints.size(), 0.0);
  for (std::size_t i = 0; i < data.weights.size(); ++i) total[data.joints[i]] += data.weights[i];
  const auto most = std::max_element(total.begin(), total.end());
  return skin.joints[static_cast<std::size_t>(most - total.begin())];
}

}  // namespace

glm::mat4 rigidPart(const glm::mat4& placement) {
  const glm::vec3 x = glm::normalize(glm::vec3(placement[0]));
  const glm::vec3 yRaw = glm::vec3(placement[1]);
  const glm::vec3 y = glm::normalize(yRaw - glm::dot(yRaw, x) * x);
  const glm::vec3 z = glm::cross(x, y);
  glm::mat4 rigid(1.0f);
  rigid[0] = glm::vec4(x, 0.0f);
  rigid[1] = glm::vec4(y, 0.0f);
  rigid[2] = glm::vec4(z, 0.0f);
  rigid[3] = placement[3];
  return rigid;
}

Transform transformOf(const glm::mat4& frame) {
  Transform transform;
  transform.translation = glm::vec3(frame[3]);
  const float sinY = std::clamp(-frame[0][2], -1.0f, 1.0f);
  glm::vec3 radians(0.0f, std::asin(sinY), 0.0f);
  if (std::abs(sinY) < 0.99999f) {
    radians.x = std::atan2(frame[1][2], frame[2][2]);
    radians.z = std::atan2(frame[0][1], frame[0][0]);
  } else {  // gimbal lock: the x and z turns share an axis; all of it goes to z
    radians.z = std::atan2(-frame[1][0], frame[1][1]);
  }
  transform.rotationDegrees = glm::degrees(radians);
  return transform;
}

Result<SceneCharacter> SceneCharacter::create(const CharacterInstance& instance, const std::filesystem::path& file) {
  auto loaded = loadCharacter(file);
  if (!loaded) return std::unexpected(loaded.error());
  SceneCharacter result;
  result.instance_ = instance;
  result.character_ = std::move(*loaded);
  result.placement_ = instance.transform.matrix();
  const std::string where = file.string() + ": character '" + instance.name + "'";
  for (CharacterMesh& mesh : result.character_.meshes) mesh.surface.setMethod(instance.skinning);
  for (const ClipPlay& play : instance.clips) {
    auto clip = result.character_.findClip(play.clip);
    if (!clip) return fail("character '" + instance.name + "': " + clip.error().message);
    result.timeline_.push_back({static_cast<std::size_t>(*clip - result.character_.clips.data()), play});
  }
  for (std::size_t t = 0; t < instance.morphs.size(); ++t)
    if (!result.bindMorphTrack(t))
      return fail(where + ": no morph target named '" + instance.morphs[t].target + "'; the file's targets are " +
                  quoted(result.morphTargetNames()));
  for (const CharacterMesh& mesh : result.character_.meshes)
    result.frameNodes_.push_back(dominantNode(result.character_, mesh));
  const glm::mat4 characterAxes = glm::mat4(glm::mat3(rigidPart(result.placement_)));
  auto rest = result.character_.skeleton.worldMatrices(result.character_.skeleton.restPose());
  for (const glm::mat4& node : *rest) {
    const glm::mat4 nodeAxes = glm::mat4(glm::mat3(rigidPart(result.placement_ * node)));
    result.frameTurns_.push_back(glm::transpose(nodeAxes) * characterAxes);
  }
  result.deformed_.resize(result.character_.meshes.size());
  result.deformedValid_.assign(result.character_.meshes.size(), false);
  result.poseAt(0.0);
  return result;
}

bool SceneCharacter::bindMorphTrack(std::size_t track) {
  bool bound = false;
  for (std::size_t part = 0; part < character_.meshes.size(); ++part) {
    const std::vector<std::string>& names = character_.meshes[part].morphTargetNames;
    for (std::size_t k = 0; k < names.size(); ++k)
      if (names[k] == instance_.morphs[track].target) {
        morphBindings_.push_back({track, part, k});
        bound = true;
      }
  }
  return bound;
}

std::vector<std::string> SceneCharacter::morphTargetNames() const {
  std::vector<std::string> names;
  for (const CharacterMesh& mesh : character_.meshes)
    for (const std::string& name : mesh.morphTargetNames)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

void SceneCharacter::play(std::size_t clip, double start, float crossFadeSeconds) {
  while (!timeline_.empty() && timeline_.back().play.startSeconds >= start) timeline_.pop_back();
  // A fade needs a clip to come from; with none the new clip simply starts.
  const float fade = timeline_.empty() ? 0.0f : crossFadeSeconds;
  // Stored in float like the scene's starts, rounded down so that the clip has started at `start`.
  float startSeconds = static_cast<float>(start);
  if (static_cast<double>(startSeconds) > start)
    startSeconds = std::nextafter(startSeconds, -std::numeric_limits<float>::infinity());
  timeline_.push_back({clip, ClipPlay{.clip = character_.clips.at(clip).name(),
                                      .startSeconds = startSeconds,
                                      .crossFadeSeconds = fade}});
  posed_ = false;
}

std::optional<std::size_t> SceneCharacter::clipPlaying() const {
  std::optional<std::size_t> playing;
  for (const ClipTrack& track : timeline_)
    if (!playing || track.play.startSeconds <= time_) playing = track.clip;
  return playing;
}

float SceneCharacter::morphWeight(std::string_view name) const {
  for (std::size_t part = 0; part < character_.meshes.size(); ++part) {
    const std::vector<std::string>& names = character_.meshes[part].morphTargetNames;
    for (std::size_t k = 0; k < names.size(); ++k)
      if (names[k] == name) return morphWeights(part)[k];
  }
  return 0.0f;
}

Result<void> SceneCharacter::blendMorph(std::string_view name, float weight, double start, float seconds) {
  const float from = morphWeight(name);
  const auto at = static_cast<float>(start);
  MorphTrack track{.target = std::string(name),
                   .keys = {{at, from}, {at + std::max(seconds, 1e-3f), weight}}};
  const auto existing = std::find_if(instance_.morphs.begin(), instance_.morphs.end(),
                                     [&](const MorphTrack& m) { return m.target == name; });
  if (existing != instance_.morphs.end()) {
    *existing = std::move(track);
  } else {
    instance_.morphs.push_back(std::move(track));
    if (!bindMorphTrack(instance_.morphs.size() - 1)) {
      instance_.morphs.pop_back();
      return fail("character '" + instance_.name + "': no morph target named '" + std::string(name) +
                  "'; its targets are " + quoted(morphTargetNames()));
    }
  }
  posed_ = false;
  return {};
}

physics::Pose SceneCharacter::clipPose(std::size_t entry, double time) const {
  physics::Pose pose = character_.skeleton.restPose();
  const ClipTrack& track = timeline_[entry];
  const physics::AnimationClip& clip = character_.clips[track.clip];
  const double local = std::max(0.0, time - track.play.startSeconds) * track.play.speed;
  const float clipTime = track.play.loop ? physics::loopedTime(local, clip.duration())
                                         : static_cast<float>(std::min(local, static_cast<double>(clip.duration())));
  // The clip was checked against this skeleton when the file was read, so it applies.
  (void)clip.apply(clipTime, pose);
  return pose;
}

void SceneCharacter::poseAt(double time) {
  if (posed_ && time == time_) return;
  posed_ = true;
  time_ = time;
  if (timeline_.empty()) {
    pose_ = character_.skeleton.restPose();
  } else {
    std::size_t entry = 0;
    while (entry + 1 < timeline_.size() && timeline_[entry + 1].play.startSeconds <= time) ++entry;
    pose_ = clipPose(entry, time);
    const ClipPlay& play = timeline_[entry].play;
    const double into = time - play.startSeconds;
    if (entry > 0 && play.crossFadeSeconds > 0.0f && into >= 0.0 && into < play.crossFadeSeconds)
      blendInto(clipPose(entry - 1, time), pose_, static_cast<float>(into / play.crossFadeSeconds));
  }
  for (const MorphBinding& binding : morphBindings_) {
    const int node = character_.meshes[binding.part].node;
    pose_.morphWeights[static_cast<std::size_t>(node)][binding.target] =
        instance_.morphs[binding.track].weightAt(static_cast<float>(time));
  }
  // The pose comes from the skeleton itself, so its sizes match.
  auto world = character_.skeleton.worldMatrices(pose_);
  world_ = std::move(*world);
  for (glm::mat4& matrix : world_) matrix = placement_ * matrix;
  std::fill(deformedValid_.begin(), deformedValid_.end(), false);
}

Result<std::size_t> SceneCharacter::findPart(std::string_view name) const {
  auto found = character_.findMesh(name);
  if (!found) return fail("character '" + instance_.name + "': " + found.error().message);
  return found;
}

glm::mat4 SceneCharacter::partFrame(std::size_t part) const { return jointFrame(frameNodes_.at(part)); }

Result<int> SceneCharacter::findJoint(std::string_view name) const {
  std::vector<std::string> names;
  for (const physics::SkeletonNode& node : character_.skeleton.nodes()) {
    if (node.name == name) return static_cast<int>(names.size());
    names.push_back(node.name);
  }
  return fail(character_.file + ": character '" + instance_.name + "': no joint (node) named '" + std::string(name) +
              "'; the nodes are " + quoted(names));
}

glm::mat4 SceneCharacter::jointFrame(int node) const {
  const auto index = static_cast<std::size_t>(node);
  return rigidPart(world_.at(index)) * frameTurns_[index];
}

std::vector<glm::mat4> SceneCharacter::jointMatrices(std::size_t part) const {
  // The part index and the world matrices come from this character: the call cannot fail.
  return *character_.jointMatrices(part, world_);
}

std::vector<glm::mat4> SceneCharacter::jointMatricesInPartFrame(std::size_t part) const {
  std::vector<glm::mat4> joints = jointMatrices(part);
  const glm::mat4 worldToPart = glm::inverse(partFrame(part));
  for (glm::mat4& joint : joints) joint = worldToPart * joint;
  return joints;
}

std::span<const float> SceneCharacter::morphWeights(std::size_t part) const {
  return pose_.morphWeights.at(static_cast<std::size_t>(character_.meshes.at(part).node));
}

Result<const physics::DeformedSurface*> SceneCharacter::deformed(std::size_t part, unsigned threads) {
  if (!deformedValid_.at(part)) {
    const std::vector<glm::mat4> joints = jointMatrices(part);
    if (auto done = character_.meshes[part].surface.deform(joints, morphWeights(part), deformed_[part], threads);
        !done)
      return fail("character '" + instance_.name + "', mesh '" + character_.meshes[part].name +
                  "': " + done.error().message);
    deformedValid_[part] = true;
  }
  return &deformed_[part];
}

}  // namespace mane::scenes
