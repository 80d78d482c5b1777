#pragma once
// Keyframed animation of a node hierarchy, sampled exactly as glTF 2.0 defines it (§3.11 and
// Appendix C, "Animation Sampler Interpolation Modes"):
//   STEP         the value of the last key at or before t;
//   LINEAR       (1 − u)·v_k + u·v_{k+1} with u = (t − t_k)/(t_{k+1} − t_k); rotations use
//                spherical linear interpolation along the shorter arc;
//   CUBICSPLINE  the cubic Hermite spline through v_k and v_{k+1} whose tangents are the stored
//                out-tangent b_k and in-tangent a_{k+1} scaled by the key interval t_{k+1} − t_k.
// Rotations are normalised after interpolation. Before the first key a channel holds the first
// key's value, after the last key the last key's value; looping is the caller's choice
// (`loopedTime`).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "physics/skeleton.hpp"

namespace mane::physics {

enum class Interpolation { Step, Linear, CubicSpline };

/// Which property of a node a channel drives.
enum class AnimatedProperty { Translation, Rotation, Scale, MorphWeights };

/// One animated property of one node with its keyframes (a glTF channel with its sampler).
struct AnimationChannel {
  /// Index of the node in the skeleton the clip animates.
  int node = -1;
  AnimatedProperty property = AnimatedProperty::Translation;
  Interpolation interpolation = Interpolation::Linear;
  /// Key times in seconds, strictly increasing; at least one key (two for CubicSpline).
  std::vector<float> times;
  /// `width` floats per element. Step and Linear: one element per key. CubicSpline: three per
  /// key, in glTF's order (in-tangent a_k, value v_k, out-tangent b_k); tangents are in units per
  /// second. Translations in metres; rotations as quaternions in glTF's order x, y, z, w.
  std::vector<float> values;
  /// Floats per element: 3 for translation and scale, 4 for rotation, the mesh's morph-target
  /// count for weights.
  std::size_t width = 0;
};

/// Checks what `AnimationChannel` documents: a node index ≥ 0, the width the property needs,
/// finite and strictly increasing times, finite values of the right count, no zero rotation key.
/// The message names the problem; callers prefix the file and the channel.
[[nodiscard]] Result<void> validateChannel(const AnimationChannel& channel);

/// The value of a valid channel (one that passes `validateChannel`) at `time` seconds, written
/// to `out`, which must hold `channel.width` floats. Rotations come out as unit quaternions in
/// x, y, z, w order.
void sampleChannel(const AnimationChannel& channel, float time, std::span<float> out);

/// A named set of channels played together (a glTF animation).
class AnimationClip {
public:
  /// Validates every channel (the message names the clip and the channel).
  [[nodiscard]] static Result<AnimationClip> create(std::string name, std::vector<AnimationChannel> channels);

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] std::span<const AnimationChannel> channels() const { return channels_; }

  /// The last key time over all channels, seconds (0 for a clip without channels). Clips are
  /// timed from 0, as glTF's are, so this is also the length of one loop.
  [[nodiscard]] float duration() const { return duration_; }

  /// Overwrites the properties the clip animates in `pose` with their values at `time` seconds;
  /// the rest of the pose is left as it is. Where two channels drive the same property the later
  /// one wins. Fails, naming the channel, when a channel's node is not in the pose or its morph
  /// weights do not have the channel's width; the pose is then left unchanged.
  [[nodiscard]] Result<void> apply(float time, Pose& pose) const;

private:
  std::string name_;
  std::vector<AnimationChannel> channels_;
  float duration_ = 0.0f;
};

/// `time` wrapped into [0, duration) for a looping clip, computed in double so that hours of
/// play keep sub-microsecond resolution. A duration ≤ 0 gives 0.
[[nodiscard]] float loopedTime(double time, float duration);

}  // namespace mane::physics
