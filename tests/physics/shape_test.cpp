// Local shape (bending) constraints and the velocity clamp (SolverSettings::shapeStiffness,
// ::maxSpeed): a curly groom keeps its rest shape under gravity the more the stiffer, the shape
// is kept in the head's frame when the head turns, and no particle carries more than the maximum
// speed into the next step.

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/solver.hpp"
#include "tests/support/particle_solver.hpp"

namespace mane::physics {
namespace {

using mane::testing::ParticleSolver;

using ::testing::HasSubstr;

float norm(const glm::vec3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

std::vector<std::vector<glm::vec3>> curlyGroom() {
  GroomSettings groom;
  groom.seed = 4;
  groom.strandCount = 40;
  groom.particlesPerStrand = 24;
  groom.strandLength = 0.3f;
  groom.curlRadius = 0.012f;
  groom.curlAnglePerSegment = 0.8f;
  return *generateGroom(groom);
}

// Root-mean-square distance of the non-root particles from their rest positions in the head's
// frame, metres.
float rmsShapeError(const HairSystem& hair, const std::vector<std::vector<glm::vec3>>& rest, const glm::mat4& head) {
  const glm::mat4 toLocal = glm::inverse(head);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t s = 0; s < rest.size(); ++s) {
    const auto x = hair.strandPositions(s);
    for (std::size_t i = 1; i < x.size(); ++i) {
      const float e = norm(glm::vec3(toLocal * glm::vec4(x[i], 1.0f)) - rest[s][i]);
      sum += static_cast<double>(e) * e;
      ++count;
    }
  }
  return static_cast<float>(std::sqrt(sum / static_cast<double>(count)));
}

TEST(ShapeConstraint, CurlyGroomKeepsItsRestShapeUnderGravityMonotoneInStiffness) {
  // Reference: the groom's rest shape. Measured after 2 s of gravity on a still head: the RMS
  // distance from rest must fall strictly as the stiffness rises, be under a tenth of the
  // shapeless value at 0.5, and under 1 mm at stiffness 1: each particle is then put exactly where
  // its parent's frame says, so the groom is rigid in the head's frame. (Stiffness below 0.4 is
  // not used: the constraint is not conservative there; see SolverSettings::shapeStiffness.)
  const auto rest = curlyGroom();
  std::vector<float> errors;
  for (float stiffness : {0.0f, 0.5f, 0.75f, 1.0f}) {
    SolverSettings settings;
    settings.shapeStiffness = stiffness;
    auto hair = HairSystem::create(rest, settings);
    ASSERT_TRUE(hair);
    for (int frame = 0; frame < 120; ++frame) ASSERT_TRUE(hair->advance(1.0 / 60.0, 2));
    errors.push_back(rmsShapeError(*hair, rest, glm::mat4(1.0f)));
    std::printf("shape stiffness %.2f: RMS distance from rest %.5f m\n", static_cast<double>(stiffness),
                static_cast<double>(errors.back()));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_LT(errors[k], errors[k - 1]) << "stiffness step " << k;
  EXPECT_LT(errors[1], 0.1f * errors.front());
  EXPECT_LT(errors.back(), 1e-3f);
}

TEST(ShapeConstraint, ShapeIsKeptInTheHeadsFrameWhenTheHeadTurns) {
  // Without gravity nothing but the shape constraint restores a strand's shape. The head turns a
  // quarter turn about Z in 0.5 s and then holds still for 1.5 s. Reference: the rest shape in
  // head-local space. With stiffness 0.5 the groom returns to it (RMS under 1 mm); without, the
  // strands stay bent by their inertia (RMS over 1 cm).
  const auto rest = curlyGroom();
  const auto run = [&](float stiffness) {
    SolverSettings settings;
    settings.gravity = glm::vec3(0.0f);
    settings.shapeStiffness = stiffness;
    auto hair = HairSystem::create(rest, settings);
    EXPECT_TRUE(hair);
    glm::mat4 head(1.0f);
    for (int frame = 1; frame <= 120; ++frame) {
      const float turn = 1.5707963f * std::min(1.0f, static_cast<float>(frame) / 30.0f);
      head = glm::rotate(glm::mat4(1.0f), turn, glm::vec3(0.0f, 0.0f, 1.0f));
      EXPECT_TRUE(hair->setHeadTransform(head));
      EXPECT_TRUE(hair->advance(1.0 / 60.0, 1));
    }
    return rmsShapeError(*hair, rest, head);
  };
  const float kept = run(0.5f), loose = run(0.0f);
  std::printf("head turn: RMS from rest with shape %.5f m, without %.5f m\n", static_cast<double>(kept),
              static_cast<double>(loose));
  EXPECT_LT(kept, 1e-3f);
  EXPECT_GT(loose, 1e-2f);
}

TEST(VelocityClamp, NoParticleCarriesMoreThanTheMaximumSpeedIntoTheNextStep) {
  // The head jerks 0.3 m sideways within one 1/120 s step (36 m/s) and back, twice. Reference:
  // the clamp's definition, |x − x_prev| ≤ maxSpeed·h after every step, for every non-root
  // particle; tolerance 1e-5 relative (float rounding of the rescale). Control: without the
  // clamp the same motion gives particles more than 3× that speed.
  GroomSettings groom;
  groom.strandCount = 50;
  auto strands = generateGroom(groom);
  ASSERT_TRUE(strands);
  const auto fastest = [&](float maxSpeed) {
    SolverSettings settings;
    settings.maxSpeed = maxSpeed;
    auto hair = HairSystem::create(*strands, settings);
    EXPECT_TRUE(hair);
    float top = 0.0f;
    for (int k = 0; k < 120; ++k) {
      const float offset = (k / 15) % 2 == 1 ? 0.3f : 0.0f;
      EXPECT_TRUE(hair->setHeadTransform(glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0.0f, 0.0f))));
      EXPECT_TRUE(hair->advance(settings.fixedStep, 2));
      const Particles& p = hair->particles();
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p.inverseMasses[i] > 0.0f)
          top = std::max(top, norm(p.positions[i] - p.previousPositions[i]) / static_cast<float>(settings.fixedStep));
    }
    return top;
  };
  constexpr float kMaxSpeed = 2.0f;
  const float clamped = fastest(kMaxSpeed);
  const float free = fastest(std::numeric_limits<float>::infinity());
  std::printf("velocity clamp: fastest %.4f m/s with a %.1f m/s clamp, %.2f m/s without\n",
              static_cast<double>(clamped), static_cast<double>(kMaxSpeed), static_cast<double>(free));
  EXPECT_LE(clamped, kMaxSpeed * (1.0f + 1e-5f));
  EXPECT_GT(clamped, 0.9f * kMaxSpeed);
  EXPECT_GT(free, 3.0f * kMaxSpeed);
}

TEST(VelocityClamp, FreeFallReachesTheMaximumSpeedAndStaysThere) {
  // A particle falls from rest. Reference: free fall v = g·t until the clamp, then exactly
  // maxSpeed (Verlet: the displacement per step grows by g·h² until it is cut to maxSpeed·h).
  // Tolerance 1e-5 relative.
  SolverSettings settings;
  settings.damping = 0.0f;
  settings.maxSpeed = 3.0f;
  auto solver = ParticleSolver::create(settings);
  ASSERT_TRUE(solver);
  solver->particles.add({0.0f, 0.0f, 0.0f}, 1.0f);
  const float h = static_cast<float>(settings.fixedStep);
  for (int k = 1; k <= 120; ++k) {
    solver->step();
    const float speed = norm(solver->particles.positions[0] - solver->particles.previousPositions[0]) / h;
    const float freeFall = 9.81f * h * static_cast<float>(k);
    EXPECT_NEAR(speed, std::min(freeFall, 3.0f), 1e-5f * 3.0f + 1e-6f) << "step " << k;
  }
}

TEST(ShapeAndClampSettings, OutOfRangeValuesAreRejectedByName) {
  for (float bad : {-0.1f, 1.5f, std::nanf("")}) {
    SolverSettings settings;
    settings.shapeStiffness = bad;
    auto valid = validateSettings(settings);
    ASSERT_FALSE(valid) << bad;
    EXPECT_THAT(valid.error().message, HasSubstr("shapeStiffness"));
  }
  for (float bad : {0.0f, -1.0f, std::nanf("")}) {
    SolverSettings settings;
    settings.maxSpeed = bad;
    auto valid = validateSettings(settings);
    ASSERT_FALSE(valid) << bad;
    EXPECT_THAT(valid.error().message, HasSubstr("maxSpeed"));
  }
}

}  // namespace
}  // namespace mane::physics
