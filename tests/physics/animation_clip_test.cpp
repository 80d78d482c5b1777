// Animation sampling against the glTF 2.0 formulas (Appendix C), at keys and between them, with
// hand-made channels; clamping outside the keys, looping, applying a clip to a pose, and bad
// channels rejected.

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/animation_clip.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;

constexpr float kPi = std::numbers::pi_v<float>;
// The formulas below are evaluated by hand to 6–7 digits; float rounding adds ~1e-7.
constexpr float kTolerance = 2e-6f;

AnimationChannel translation(Interpolation interpolation, std::vector<float> times, std::vector<float> values) {
  AnimationChannel channel;
  channel.node = 0;
  channel.property = AnimatedProperty::Translation;
  channel.interpolation = interpolation;
  channel.times = std::move(times);
  channel.values = std::move(values);
  channel.width = 3;
  return channel;
}

glm::vec3 sample3(const AnimationChannel& channel, float time) {
  float v[3];
  sampleChannel(channel, time, v);
  return {v[0], v[1], v[2]};
}

void expectVec3(const glm::vec3& actual, const glm::vec3& expected, const char* what) {
  EXPECT_NEAR(actual.x, expected.x, kTolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, kTolerance) << what;
  EXPECT_NEAR(actual.z, expected.z, kTolerance) << what;
}

// Keys at 0, 1 and 3 s: (0, 0, 0), (2, 4, 6), (−2, 0, 2).
const std::vector<float> kTimes = {0.0f, 1.0f, 3.0f};
const std::vector<float> kValues = {0.0f, 0.0f, 0.0f, 2.0f, 4.0f, 6.0f, -2.0f, 0.0f, 2.0f};

TEST(AnimationSampling, StepHoldsEachKeyUntilTheNext) {
  const auto channel = translation(Interpolation::Step, kTimes, kValues);
  EXPECT_EQ(sample3(channel, 0.0f), glm::vec3(0.0f));
  EXPECT_EQ(sample3(channel, 0.999f), glm::vec3(0.0f));
  EXPECT_EQ(sample3(channel, 1.0f), glm::vec3(2.0f, 4.0f, 6.0f));
  EXPECT_EQ(sample3(channel, 2.9f), glm::vec3(2.0f, 4.0f, 6.0f));
  EXPECT_EQ(sample3(channel, 3.0f), glm::vec3(-2.0f, 0.0f, 2.0f));
}

TEST(AnimationSampling, LinearIsExactAtKeysAndInterpolatesBetween) {
  const auto channel = translation(Interpolation::Linear, kTimes, kValues);
  // At a key u = 0, so (1 − u)·v_k + u·v_{k+1} is v_k bit for bit.
  EXPECT_EQ(sample3(channel, 0.0f), glm::vec3(0.0f));
  EXPECT_EQ(sample3(channel, 1.0f), glm::vec3(2.0f, 4.0f, 6.0f));
  EXPECT_EQ(sample3(channel, 3.0f), glm::vec3(-2.0f, 0.0f, 2.0f));
  // t = 0.5: u = 0.5 between keys 0 and 1 → (1, 2, 3).
  expectVec3(sample3(channel, 0.5f), {1.0f, 2.0f, 3.0f}, "t = 0.5");
  // t = 2.5: u = (2.5 − 1)/2 = 0.75 between keys 1 and 2 → 0.25·(2, 4, 6) + 0.75·(−2, 0, 2) = (−1, 1, 3).
  expectVec3(sample3(channel, 2.5f), {-1.0f, 1.0f, 3.0f}, "t = 2.5");
}

TEST(AnimationSampling, OutsideTheKeysTheFirstAndLastValuesHold) {
  for (Interpolation interpolation : {Interpolation::Step, Interpolation::Linear}) {
    const auto channel = translation(interpolation, {0.5f, 1.0f}, {1.0f, 1.0f, 1.0f, 3.0f, 3.0f, 3.0f});
    EXPECT_EQ(sample3(channel, 0.0f), glm::vec3(1.0f));
    EXPECT_EQ(sample3(channel, -5.0f), glm::vec3(1.0f));
    EXPECT_EQ(sample3(channel, 7.0f), glm::vec3(3.0f));
    EXPECT_EQ(sample3(channel, std::numeric_limits<float>::quiet_NaN()), glm::vec3(1.0f));
  }
}

TEST(AnimationSampling, CubicSplineFollowsTheHermiteFormulaWithTangentsScaledByTheKeyInterval) {
  // Two keys 2 s apart, each stored as (in-tangent a_k, value v_k, out-tangent b_k):
  //   key 0: a0 = (9, 9, 9) (unused), v0 = (0, 0, 0),  b0 = (1, 0, −1)
  //   key 1: a1 = (3, 1, 0),          v1 = (4, 2, 0),  b1 = (9, 9, 9) (unused)
  // v(u) = (2u³ − 3u² + 1)·v0 + t_d·(u³ − 2u² + u)·b0 + (−2u³ + 3u²)·v1 + t_d·(u³ − u²)·a1, t_d = 2.
  const auto channel = translation(Interpolation::CubicSpline, {0.0f, 2.0f},
                                   {9, 9, 9, 0, 0, 0, 1, 0, -1,  //
                                    3, 1, 0, 4, 2, 0, 9, 9, 9});
  EXPECT_EQ(sample3(channel, 0.0f), glm::vec3(0.0f));
  EXPECT_EQ(sample3(channel, 2.0f), glm::vec3(4.0f, 2.0f, 0.0f));
  // u = 0.5: basis 0.5, 0.125, 0.5, −0.125 →
  //   x = 0.125·2·1 + 0.5·4 − 0.125·2·3 = 1.5;  y = 0.5·2 − 0.125·2·1 = 0.75;  z = 0.125·2·(−1) = −0.25.
  expectVec3(sample3(channel, 1.0f), {1.5f, 0.75f, -0.25f}, "u = 0.5");
  // u = 0.25: basis 0.84375, 0.140625, 0.15625, −0.046875 →
  //   x = 0.28125 + 0.625 − 0.28125 = 0.625;  y = 0.3125 − 0.09375 = 0.21875;  z = −0.28125.
  expectVec3(sample3(channel, 0.5f), {0.625f, 0.21875f, -0.28125f}, "u = 0.25");
  // The same keys 4 s apart: t_d = 4 doubles the tangent terms. u = 0.5 →
  //   x = 0.125·4·1 + 2 − 0.125·4·3 = 1.0;  y = 1 − 0.5 = 0.5;  z = −0.5.
  const auto slower = translation(Interpolation::CubicSpline, {0.0f, 4.0f}, channel.values);
  expectVec3(sample3(slower, 2.0f), {1.0f, 0.5f, -0.5f}, "u = 0.5, t_d = 4");
}

glm::quat sampleRotation(const AnimationChannel& channel, float time) {
  float v[4];
  sampleChannel(channel, time, v);
  return {v[3], v[0], v[1], v[2]};
}

AnimationChannel rotation(Interpolation interpolation, const glm::quat& from, const glm::quat& to,
                          bool zeroTangents = false) {
  AnimationChannel channel;
  channel.node = 0;
  channel.property = AnimatedProperty::Rotation;
  channel.interpolation = interpolation;
  channel.times = {0.0f, 1.0f};
  channel.width = 4;
  const auto xyzw = [](const glm::quat& q) { return std::vector<float>{q.x, q.y, q.z, q.w}; };
  const std::vector<float> zeros(4, 0.0f);
  for (const glm::quat& q : {from, to}) {
    if (zeroTangents) channel.values.insert(channel.values.end(), zeros.begin(), zeros.end());
    const auto v = xyzw(q);
    channel.values.insert(channel.values.end(), v.begin(), v.end());
    if (zeroTangents) channel.values.insert(channel.values.end(), zeros.begin(), zeros.end());
  }
  return channel;
}

TEST(AnimationSampling, LinearRotationsSlerpAlongTheShorterArc) {
  const glm::vec3 z(0.0f, 0.0f, 1.0f);
  const glm::quat identity(1.0f, 0.0f, 0.0f, 0.0f);
  // 0° → 90° about z: halfway is 45°, turning (1, 0, 0) to (cos 45°, sin 45°, 0).
  const auto quarter = rotation(Interpolation::Linear, identity, glm::angleAxis(0.5f * kPi, z));
  expectVec3(sampleRotation(quarter, 0.5f) * glm::vec3(1.0f, 0.0f, 0.0f), {0.7071068f, 0.7071068f, 0.0f}, "45°");
  // A quarter of the way: 22.5° (slerp is uniform in angle).
  expectVec3(sampleRotation(quarter, 0.25f) * glm::vec3(1.0f, 0.0f, 0.0f),
             {std::cos(0.125f * kPi), std::sin(0.125f * kPi), 0.0f}, "22.5°");
  // The same end rotation stored as −q: still the 90° arc, not the 270° one.
  const auto negated = rotation(Interpolation::Linear, identity, -glm::angleAxis(0.5f * kPi, z));
  expectVec3(sampleRotation(negated, 0.5f) * glm::vec3(1.0f, 0.0f, 0.0f), {0.7071068f, 0.7071068f, 0.0f}, "−q");
  // 0° → 270° about z is −90° the short way: halfway is −45°.
  const auto longWay = rotation(Interpolation::Linear, identity, glm::angleAxis(1.5f * kPi, z));
  expectVec3(sampleRotation(longWay, 0.5f) * glm::vec3(1.0f, 0.0f, 0.0f), {0.7071068f, -0.7071068f, 0.0f}, "−45°");
}

TEST(AnimationSampling, CubicSplineRotationsAreNormalised) {
  // Zero tangents, u = 0.5: the spline gives ½·q0 + ½·q1 = (0, 0, 0.353553, 0.853553), of
  // length 0.92388 = cos 22.5°; normalised it is exactly the 45° rotation.
  const glm::quat identity(1.0f, 0.0f, 0.0f, 0.0f);
  const auto channel =
      rotation(Interpolation::CubicSpline, identity, glm::angleAxis(0.5f * kPi, glm::vec3(0.0f, 0.0f, 1.0f)), true);
  const glm::quat q = sampleRotation(channel, 0.5f);
  EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
  EXPECT_NEAR(q.z, std::sin(0.125f * kPi), kTolerance);
  EXPECT_NEAR(q.w, std::cos(0.125f * kPi), kTolerance);
}

TEST(AnimationSampling, MorphWeightChannelsInterpolateEveryTarget) {
  AnimationChannel channel;
  channel.node = 0;
  channel.property = AnimatedProperty::MorphWeights;
  channel.interpolation = Interpolation::Linear;
  channel.times = {0.0f, 2.0f};
  channel.values = {0.0f, 1.0f, 1.0f, 0.0f};  // two targets per key
  channel.width = 2;
  float w[2];
  sampleChannel(channel, 0.5f, w);  // u = 0.25
  EXPECT_FLOAT_EQ(w[0], 0.25f);
  EXPECT_FLOAT_EQ(w[1], 0.75f);
}

TEST(AnimationClip, AppliesItsChannelsToAPoseAndReportsItsDuration) {
  AnimationChannel weights;
  weights.node = 1;
  weights.property = AnimatedProperty::MorphWeights;
  weights.times = {0.0f, 4.0f};
  weights.values = {0.0f, 1.0f};
  weights.width = 1;
  auto clip = AnimationClip::create("Walk", {translation(Interpolation::Linear, kTimes, kValues), weights});
  ASSERT_TRUE(clip) << clip.error().message;
  EXPECT_EQ(clip->name(), "Walk");
  EXPECT_EQ(clip->duration(), 4.0f);
  Pose pose;
  pose.local.resize(2);
  pose.local[1].scale = glm::vec3(2.0f);
  pose.morphWeights = {{}, {0.3f}};
  ASSERT_TRUE(clip->apply(0.5f, pose));
  expectVec3(pose.local[0].translation, {1.0f, 2.0f, 3.0f}, "node 0");
  EXPECT_EQ(pose.local[1].scale, glm::vec3(2.0f));  // not animated: untouched
  EXPECT_FLOAT_EQ(pose.morphWeights[1][0], 0.125f);

  Pose tooSmall;
  tooSmall.local.resize(1);
  tooSmall.morphWeights.resize(1);
  auto failed = clip->apply(0.5f, tooSmall);
  ASSERT_FALSE(failed);
  EXPECT_THAT(failed.error().message, HasSubstr("node 1"));
  EXPECT_EQ(tooSmall.local[0].translation, glm::vec3(0.0f));  // nothing written on failure
}

TEST(AnimationClip, LoopedTimeWrapsIntoOneLoop) {
  EXPECT_FLOAT_EQ(loopedTime(5.0, 2.0f), 1.0f);
  EXPECT_FLOAT_EQ(loopedTime(-0.5, 2.0f), 1.5f);
  EXPECT_EQ(loopedTime(4.0, 2.0f), 0.0f);
  EXPECT_EQ(loopedTime(3.0, 0.0f), 0.0f);
  // An hour in, 1/60 s steps stay distinguishable: double keeps the wrap exact to ~1e-12 s.
  EXPECT_NEAR(loopedTime(3600.0 + 1.0 / 60.0, 0.9583333f), std::fmod(3600.0 + 1.0 / 60.0, 0.9583333f), 1e-6);
}

TEST(AnimationClip, BadChannelsAreRejectedNamingTheProblem) {
  const auto rejected = [](AnimationChannel channel) {
    auto clip = AnimationClip::create("Bad", {std::move(channel)});
    EXPECT_FALSE(clip);
    return clip ? std::string() : clip.error().message;
  };
  EXPECT_THAT(rejected(translation(Interpolation::Linear, {0.0f, 1.0f, 1.0f}, std::vector<float>(9, 0.0f))),
              HasSubstr("do not increase"));
  EXPECT_THAT(rejected(translation(Interpolation::Linear, {0.0f, 1.0f}, std::vector<float>(5, 0.0f))),
              HasSubstr("expected 6"));
  EXPECT_THAT(rejected(translation(Interpolation::CubicSpline, {0.0f, 1.0f}, std::vector<float>(6, 0.0f))),
              HasSubstr("expected 18"));
  EXPECT_THAT(rejected(translation(Interpolation::CubicSpline, {0.0f}, std::vector<float>(9, 0.0f))),
              HasSubstr("at least two"));
  auto nan = translation(Interpolation::Linear, {0.0f, 1.0f}, std::vector<float>(6, 0.0f));
  nan.values[4] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(rejected(nan), HasSubstr("NaN or infinite value at keyframe 1"));
  auto infiniteTime = translation(Interpolation::Linear, {0.0f, 1.0f}, std::vector<float>(6, 0.0f));
  infiniteTime.times[1] = std::numeric_limits<float>::infinity();
  EXPECT_THAT(rejected(infiniteTime), HasSubstr("NaN or infinite time"));
  auto zeroQuaternion = rotation(Interpolation::Linear, glm::quat(1.0f, 0.0f, 0.0f, 0.0f), glm::quat(1.0f, 0, 0, 0));
  zeroQuaternion.values[7] = 0.0f;
  EXPECT_THAT(rejected(zeroQuaternion), HasSubstr("zero quaternion"));
  EXPECT_THAT(rejected(translation(Interpolation::Linear, {}, {})), HasSubstr("no keyframes"));
}

}  // namespace
}  // namespace mane::physics
