#pragma once
// A scene's character entry brought to life: its glTF file loaded (scenes/gltf_character.hpp),
// posed at any time from the scene's clip timeline (clips, speeds, loops, cross-fades) and morph
// tracks, and its meshes deformed on the CPU for whatever follows them (hair roots, cloth pins).
//
// Joint frames. Every node has a rigid frame that moves with it: its placement with the scale
// divided out, turned so that in the rest pose its axes are the character's own (as placed by the
// scene: y up, z front for a glTF character), whatever axes the file's bones have. Shapes carried
// by a joint are given in that frame, so "0.1 m above the head joint" reads as it sounds.
//
// Each mesh of the character is a *part*, whose frame is the frame of the joint that moves most
// of it (for a mesh that rides one node: that node). What follows a part in the physics lives in
// that frame: a groom's head transform, its colliders and its collider field, a cloth's body
// transform.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <span>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

#include "common/error.hpp"
#include "physics/skinning.hpp"
#include "scenes/gltf_character.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {

/// The rotation and translation of an affine matrix whose linear part is a rotation times a
/// positive scale (a joint placement): the columns made orthonormal (Gram–Schmidt, x first).
[[nodiscard]] glm::mat4 rigidPart(const glm::mat4& placement);

/// The Transform whose matrix is the rigid `frame` (rotation and translation): Euler angles for
/// T · Rz · Ry · Rx, the order Transform composes.
[[nodiscard]] Transform transformOf(const glm::mat4& frame);

class SceneCharacter {
public:
  /// Loads `file` for `instance` (errors name the file and what is wrong): every clip of the
  /// timeline must be in the file, every morph track must name a target of one of its meshes.
  /// Posed at time 0.
  [[nodiscard]] static Result<SceneCharacter> create(const CharacterInstance& instance,
                                                     const std::filesystem::path& file);

  [[nodiscard]] const CharacterInstance& instance() const { return instance_; }
  [[nodiscard]] const Character& character() const { return character_; }

  /// Poses the character at scene time `time` (seconds ≥ 0): the clip that has started last
  /// (blended with the one before while its cross-fade lasts), then the morph tracks.
  void poseAt(double time);

  /// Plays clip `clip` (an index into character().clips) from scene time `start` on, looping at
  /// its own speed, blended in over `crossFadeSeconds` from what plays then; what the timeline
  /// had after `start` is dropped. For interactive viewers; poses already taken stay as they are.
  void play(std::size_t clip, double start, float crossFadeSeconds);
  /// The clip (index into character().clips) that has started last at the current pose; none
  /// while the timeline is empty.
  [[nodiscard]] std::optional<std::size_t> clipPlaying() const;
  /// Blends morph target `name` from its weight at the current pose to `weight` over `seconds`
  /// from scene time `start`, replacing what the scene keyed for it. The error lists the targets.
  [[nodiscard]] Result<void> blendMorph(std::string_view name, float weight, double start, float seconds);
  /// The weight of morph target `name` at the current pose (0 when no mesh has it).
  [[nodiscard]] float morphWeight(std::string_view name) const;
  /// Every morph target name of the character's meshes, each once, in file order.
  [[nodiscard]] std::vector<std::string> morphTargetNames() const;

  [[nodiscard]] std::size_t partCount() const { return character_.meshes.size(); }
  /// The part whose glTF mesh is named `name`; the error lists the parts.
  [[nodiscard]] Result<std::size_t> findPart(std::string_view name) const;
  /// The part's rigid frame in the world at the current pose (see the file comment).
  [[nodiscard]] glm::mat4 partFrame(std::size_t part) const;

  /// The node named `name`; the error names the file and lists the nodes.
  [[nodiscard]] Result<int> findJoint(std::string_view name) const;
  /// Node `node`'s rigid frame in the world at the current pose (see the file comment).
  [[nodiscard]] glm::mat4 jointFrame(int node) const;

  /// The joint matrices that deform `part` into the world at the current pose, one per joint of
  /// its skin (or one for a mesh riding its node), and its morph weights.
  [[nodiscard]] std::vector<glm::mat4> jointMatrices(std::size_t part) const;
  /// `jointMatrices` into the part's frame instead of the world: what deforms the part for a
  /// renderer that places it with partFrame().
  [[nodiscard]] std::vector<glm::mat4> jointMatricesInPartFrame(std::size_t part) const;
  [[nodiscard]] std::span<const float> morphWeights(std::size_t part) const;

  /// The part deformed at the current pose, world space (metres): morphs, then skinning, on the
  /// CPU. Computed once per pose. `threads` ≥ 1; the result does not depend on it.
  [[nodiscard]] Result<const physics::DeformedSurface*> deformed(std::size_t part, unsigned threads = 1);

private:
  struct ClipTrack {
    std::size_t clip = 0;  ///< index into character_.clips
    ClipPlay play;
  };
  struct MorphBinding {
    std::size_t track = 0;   ///< index into instance_.morphs
    std::size_t part = 0;
    std::size_t target = 0;  ///< index into the part's targets and its node's morph weights
  };

  SceneCharacter() = default;
  /// Binds track `track` of instance_.morphs to every mesh target of its name; false if none.
  bool bindMorphTrack(std::size_t track);
  /// The rest pose with entry `entry` of the timeline applied at scene time `time`.
  physics::Pose clipPose(std::size_t entry, double time) const;

  CharacterInstance instance_;
  Character character_;
  std::vector<ClipTrack> timeline_;
  std::vector<MorphBinding> morphBindings_;
  std::vector<int> frameNodes_;  ///< per part
  /// Per node: the turn from its rigid placement's axes to the character's in the rest pose.
  std::vector<glm::mat4> frameTurns_;
  glm::mat4 placement_{1.0f};    ///< the instance's transform
  double time_ = 0.0;
  bool posed_ = false;  ///< pose_ is of time_ and of the timeline and tracks as they are
  physics::Pose pose_;
  std::vector<glm::mat4> world_;  ///< per node, at the current pose, placement included
  std::vector<physics::DeformedSurface> deformed_;  ///< per part
  std::vector<bool> deformedValid_;                  ///< per part: deformed_ is of the current pose
};

}  // namespace mane::scenes
