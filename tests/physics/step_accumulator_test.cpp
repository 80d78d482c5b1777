// The fixed-step accumulator: frames of any length become whole fixed steps; the remainder
// carries over; the substep limit drops time; and kinematic targets are interpolated at the
// true time of each step. References are hand-computed from the definitions in solver.hpp.

#include <gtest/gtest.h>

#include "physics/solver.hpp"

namespace mane::physics {
namespace {

TEST(StepAccumulator, SixtyHertzFramesGiveTwoStepsAt120Hz) {
  // 1/60 − 2·(1/120) is not exactly 0 in binary; the accumulator must still give exactly 2 steps
  // per frame forever (10,000 frames here) and never a 1/3 pattern.
  FixedStepAccumulator accumulator(1.0 / 120.0, 8);
  for (int frame = 0; frame < 10000; ++frame) {
    const StepPlan plan = accumulator.plan(1.0 / 60.0);
    ASSERT_EQ(plan.substeps, 2) << "frame " << frame;
    EXPECT_FLOAT_EQ(plan.fractionAt(1), 0.5f);
    EXPECT_FLOAT_EQ(plan.fractionAt(2), 1.0f);
  }
  EXPECT_EQ(accumulator.stepsTaken(), 20000u);
}

TEST(StepAccumulator, RemainderCarriesOverAndFractionsUseTheStepTime) {
  // Fixed step 1/120 s, frames of 1/100 s. Frame 1: one step, ending 1/120 s into a 1/100 s
  // frame → fraction 5/6; backlog 1/100 − 1/120 = 1/600 s. Frame 2: 1/600 + 1/100 = 7/600 s →
  // one step, ending 1/120 − 1/600 = 4/600 s into the frame → fraction 2/3; backlog 2/600 s.
  // Tolerance 1e-12 s on the backlog (double rounding of a few operations).
  FixedStepAccumulator accumulator(1.0 / 120.0, 8);
  StepPlan plan = accumulator.plan(1.0 / 100.0);
  EXPECT_EQ(plan.substeps, 1);
  EXPECT_FLOAT_EQ(plan.fractionAt(1), 5.0f / 6.0f);
  EXPECT_NEAR(accumulator.backlog(), 1.0 / 600.0, 1e-12);
  plan = accumulator.plan(1.0 / 100.0);
  EXPECT_EQ(plan.substeps, 1);
  EXPECT_FLOAT_EQ(plan.fractionAt(1), 2.0f / 3.0f);
  EXPECT_NEAR(accumulator.backlog(), 2.0 / 600.0, 1e-12);
}

TEST(StepAccumulator, ShortFramesRunNoStepUntilAWholeStepHasAccumulated) {
  FixedStepAccumulator accumulator(1.0 / 120.0, 8);
  EXPECT_EQ(accumulator.plan(1.0 / 480.0).substeps, 0);
  EXPECT_EQ(accumulator.plan(1.0 / 480.0).substeps, 0);
  EXPECT_EQ(accumulator.plan(1.0 / 480.0).substeps, 0);
  const StepPlan plan = accumulator.plan(1.0 / 480.0);
  EXPECT_EQ(plan.substeps, 1);
  // The step ends exactly at the end of this frame: 4/480 s = 1/120 s after the first began.
  EXPECT_FLOAT_EQ(plan.fractionAt(1), 1.0f);
}

TEST(StepAccumulator, LongFramesAreClampedAndTheExcessDropped) {
  // A 1 s hitch at 1/120 s steps would need 120 steps; the limit is 8 and the rest is dropped
  // (backlog 0), with the 8 steps spread evenly over the frame for interpolation.
  FixedStepAccumulator accumulator(1.0 / 120.0, 8);
  const StepPlan plan = accumulator.plan(1.0);
  EXPECT_EQ(plan.substeps, 8);
  EXPECT_TRUE(plan.clamped);
  EXPECT_EQ(accumulator.backlog(), 0.0);
  EXPECT_FLOAT_EQ(plan.fractionAt(4), 0.5f);
  EXPECT_FLOAT_EQ(plan.fractionAt(8), 1.0f);
}

TEST(SolverSettings, InvalidSettingsAreRejectedWithTheFieldNamed) {
  SolverSettings settings;
  settings.damping = 1.0f;
  auto result = validateSettings(settings);
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("damping"), std::string::npos) << result.error().message;

  settings = {};
  settings.fixedStep = 0.0;
  result = validateSettings(settings);
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("fixedStep"), std::string::npos);

  settings = {};
  settings.constraintIterations = 0;
  result = validateSettings(settings);
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("constraintIterations"), std::string::npos);

  settings = {};
  settings.maxSubstepsPerFrame = 0;
  EXPECT_FALSE(validateSettings(settings));

  EXPECT_TRUE(validateSettings(SolverSettings{}));
}

}  // namespace
}  // namespace mane::physics
