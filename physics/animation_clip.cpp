#include "physics/animation_clip.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mane::physics {
namespace {

// Below this angle between two keys (cos θ > 0.9995, θ < 1.8°) sin θ is too small to divide by
// accurately; the normalised linear blend differs from the arc by under 1e-7 there.
constexpr float kSlerpLinearThreshold = 0.9995f;

std::string propertyName(AnimatedProperty property) {
  switch (property) {
    case AnimatedProperty::Translation: return "translation";
    case AnimatedProperty::Rotation: return "rotation";
    case AnimatedProperty::Scale: return "scale";
    case AnimatedProperty::MorphWeights: return "weights";
  }
  return "unknown";
}

/// Scales the quaternion at `q` (x, y, z, w) to unit length; false when it has none.
bool normaliseQuaternion(float* q) {
  const float lengthSquared = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  if (!(lengthSquared > 0.0f) || !std::isfinite(lengthSquared)) return false;
  const float inverse = 1.0f / std::sqrt(lengthSquared);
  for (int i = 0; i < 4; ++i) q[i] *= inverse;
  return true;
}

/// Spherical linear interpolation from `from` to `to` (unit, x y z w) along the shorter arc:
/// q and −q are the same rotation, so `to` is negated when the two are more than 90° apart in
/// quaternion space.
void slerp(const float* from, const float* to, float u, float* out) {
  float cosTheta = from[0] * to[0] + from[1] * to[1] + from[2] * to[2] + from[3] * to[3];
  float sign = 1.0f;
  if (cosTheta < 0.0f) {
    cosTheta = -cosTheta;
    sign = -1.0f;
  }
  float weightFrom = 1.0f - u;
  float weightTo = u;
  if (cosTheta < kSlerpLinearThreshold) {
    const float theta = std::acos(cosTheta);
    const float sinTheta = std::sin(theta);
    weightFrom = std::sin((1.0f - u) * theta) / sinTheta;
    weightTo = std::sin(u * theta) / sinTheta;
  }
  for (int i = 0; i < 4; ++i) out[i] = weightFrom * from[i] + sign * weightTo * to[i];
}

/// The channel's value at `time` before the rotation clean-up; returns the key whose value
/// stands in when a rotation comes out degenerate.
std::size_t interpolate(const AnimationChannel& channel, float time, float* out) {
  const std::size_t width = channel.width;
  const std::size_t keys = channel.times.size();
  const bool cubic = channel.interpolation == Interpolation::CubicSpline;
  const std::size_t stride = cubic ? 3 * width : width;
  const std::size_t valueOffset = cubic ? width : 0;  // the spline vertex sits between its tangents
  const auto value = [&](std::size_t key) { return channel.values.data() + key * stride + valueOffset; };

  // `!(time > first)` also catches a NaN time, which no key bracket could hold.
  std::size_t clampedKey = keys;
  if (keys == 1 || !(time > channel.times.front())) clampedKey = 0;
  if (clampedKey == keys && time >= channel.times.back()) clampedKey = keys - 1;
  if (clampedKey != keys) {
    std::copy_n(value(clampedKey), width, out);
    return clampedKey;
  }

  // times[k] ≤ time < times[k + 1].
  const auto upper = std::upper_bound(channel.times.begin(), channel.times.end(), time);
  const auto k = static_cast<std::size_t>(upper - channel.times.begin()) - 1;
  const float t0 = channel.times[k];
  const float keyInterval = channel.times[k + 1] - t0;
  const float u = (time - t0) / keyInterval;
  const float* v0 = value(k);
  const float* v1 = value(k + 1);

  switch (channel.interpolation) {
    case Interpolation::Step: std::copy_n(v0, width, out); break;
    case Interpolation::Linear:
      if (channel.property == AnimatedProperty::Rotation) {
        float from[4];
        float to[4];
        std::copy_n(v0, 4, from);
        std::copy_n(v1, 4, to);
        if (normaliseQuaternion(from) && normaliseQuaternion(to)) {
          slerp(from, to, u, out);
        } else {
          std::copy_n(v0, 4, out);
        }
      } else {
        for (std::size_t i = 0; i < width; ++i) out[i] = (1.0f - u) * v0[i] + u * v1[i];
      }
      break;
    case Interpolation::CubicSpline: {
      // Hermite basis (glTF 2.0 Appendix C); tangents b_k (out) and a_{k+1} (in) times t_d.
      const float* outTangent0 = channel.values.data() + k * stride + 2 * width;
      const float* inTangent1 = channel.values.data() + (k + 1) * stride;
      const float u2 = u * u;
      const float u3 = u2 * u;
      const float h00 = 2.0f * u3 - 3.0f * u2 + 1.0f;
      const float h10 = u3 - 2.0f * u2 + u;
      const float h01 = -2.0f * u3 + 3.0f * u2;
      const float h11 = u3 - u2;
      for (std::size_t i = 0; i < width; ++i) {
        out[i] = h00 * v0[i] + h10 * keyInterval * outTangent0[i] + h01 * v1[i] + h11 * keyInterval * inTangent1[i];
      }
      break;
    }
  }
  return k;
}

}  // namespace

Result<void> validateChannel(const AnimationChannel& channel) {
  const std::string what = propertyName(channel.property) + " channel of node " + std::to_string(channel.node);
  if (channel.node < 0) return fail("a " + what + ": the node index must be >= 0");
  std::size_t expectedWidth = 0;
  switch (channel.property) {
    case AnimatedProperty::Translation:
    case AnimatedProperty::Scale: expectedWidth = 3; break;
    case AnimatedProperty::Rotation: expectedWidth = 4; break;
    case AnimatedProperty::MorphWeights: expectedWidth = channel.width; break;
  }
  if (channel.width == 0 || channel.width != expectedWidth) {
    return fail("the " + what + " has " + std::to_string(channel.width) + " components per value; expected " +
                (channel.property == AnimatedProperty::MorphWeights ? std::string("at least 1")
                                                                    : std::to_string(expectedWidth)));
  }
  const std::size_t keys = channel.times.size();
  const bool cubic = channel.interpolation == Interpolation::CubicSpline;
  if (keys == 0) return fail("the " + what + " has no keyframes");
  if (cubic && keys < 2) return fail("the " + what + " is a cubic spline with one keyframe; it needs at least two");
  for (std::size_t k = 0; k < keys; ++k) {
    if (!std::isfinite(channel.times[k])) {
      return fail("the " + what + " has a NaN or infinite time at keyframe " + std::to_string(k));
    }
    if (k > 0 && !(channel.times[k] > channel.times[k - 1])) {
      return fail("the " + what + " has key times that do not increase: keyframe " + std::to_string(k) + " is at " +
                  std::to_string(channel.times[k]) + " s after " + std::to_string(channel.times[k - 1]) + " s");
    }
  }
  const std::size_t perKey = (cubic ? 3 : 1) * channel.width;
  if (channel.values.size() / perKey != keys || channel.values.size() % perKey != 0) {
    return fail("the " + what + " has " + std::to_string(channel.values.size()) + " floats for " +
                std::to_string(keys) + " keyframes; expected " + std::to_string(keys * perKey) + " (" +
                (cubic ? "in-tangent, value and out-tangent of " : "") + std::to_string(channel.width) +
                " components per keyframe)");
  }
  for (std::size_t i = 0; i < channel.values.size(); ++i) {
    if (!std::isfinite(channel.values[i])) {
      return fail("the " + what + " has a NaN or infinite value at keyframe " + std::to_string(i / perKey));
    }
  }
  if (channel.property == AnimatedProperty::Rotation) {
    for (std::size_t k = 0; k < keys; ++k) {
      const float* q = channel.values.data() + k * perKey + (cubic ? 4 : 0);
      if (q[0] == 0.0f && q[1] == 0.0f && q[2] == 0.0f && q[3] == 0.0f) {
        return fail("the " + what + " has a zero quaternion at keyframe " + std::to_string(k) +
                    "; rotations must be unit quaternions");
      }
    }
  }
  return {};
}

void sampleChannel(const AnimationChannel& channel, float time, std::span<float> out) {
  const std::size_t key = interpolate(channel, time, out.data());
  if (channel.property != AnimatedProperty::Rotation) return;
  if (normaliseQuaternion(out.data())) return;
  // A spline between valid keys can pass through zero in hostile data; hold the key instead.
  const std::size_t stride = channel.interpolation == Interpolation::CubicSpline ? 12 : 4;
  const std::size_t offset = channel.interpolation == Interpolation::CubicSpline ? 4 : 0;
  std::copy_n(channel.values.data() + key * stride + offset, 4, out.data());
  normaliseQuaternion(out.data());
}

Result<AnimationClip> AnimationClip::create(std::string name, std::vector<AnimationChannel> channels) {
  AnimationClip clip;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (auto ok = validateChannel(channels[c]); !ok) {
      return fail("animation '" + name + "' channel " + std::to_string(c) + ": " + ok.error().message);
    }
    clip.duration_ = std::max(clip.duration_, channels[c].times.back());
  }
  clip.name_ = std::move(name);
  clip.channels_ = std::move(channels);
  return clip;
}

Result<void> AnimationClip::apply(float time, Pose& pose) const {
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const AnimationChannel& channel = channels_[c];
    const auto node = static_cast<std::size_t>(channel.node);
    if (node >= pose.local.size() || node >= pose.morphWeights.size()) {
      return fail("animation '" + name_ + "' channel " + std::to_string(c) + " drives node " +
                  std::to_string(channel.node) + ", but the pose has " + std::to_string(pose.local.size()) + " nodes");
    }
    if (channel.property == AnimatedProperty::MorphWeights && pose.morphWeights[node].size() != channel.width) {
      return fail("animation '" + name_ + "' channel " + std::to_string(c) + " drives " +
                  std::to_string(channel.width) + " morph weights of node " + std::to_string(channel.node) +
                  ", but the pose holds " + std::to_string(pose.morphWeights[node].size()) + " for it");
    }
  }
  for (const AnimationChannel& channel : channels_) {
    const auto node = static_cast<std::size_t>(channel.node);
    float v[4];
    switch (channel.property) {
      case AnimatedProperty::Translation:
        sampleChannel(channel, time, v);
        pose.local[node].translation = glm::vec3(v[0], v[1], v[2]);
        break;
      case AnimatedProperty::Rotation:
        sampleChannel(channel, time, v);
        pose.local[node].rotation = glm::quat(v[3], v[0], v[1], v[2]);
        break;
      case AnimatedProperty::Scale:
        sampleChannel(channel, time, v);
        pose.local[node].scale = glm::vec3(v[0], v[1], v[2]);
        break;
      case AnimatedProperty::MorphWeights: sampleChannel(channel, time, pose.morphWeights[node]); break;
    }
  }
  return {};
}

float loopedTime(double time, float duration) {
  if (!(duration > 0.0f) || !std::isfinite(time)) return 0.0f;
  double wrapped = std::fmod(time, static_cast<double>(duration));
  if (wrapped < 0.0) wrapped += duration;
  const auto result = static_cast<float>(wrapped);
  // Rounding to float can land exactly on the duration; that instant is the next loop's start.
  return result < duration ? result : 0.0f;
}

}  // namespace mane::physics
