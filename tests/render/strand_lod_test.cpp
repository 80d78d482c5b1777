// The strand level of detail's arithmetic (render/strand_lod.hpp): the share of strands kept,
// and the pixels per metre it is measured with, against a pinhole camera's closed form.

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "render/frame.hpp"
#include "render/strand_lod.hpp"

namespace mane::render {
namespace {

TEST(StrandLevelOfDetail, KeepsTheShareOfItsWidthThatTheStrandsSpan) {
  EXPECT_EQ(keptStrandShare(0.5f, 1.0f), 0.5f);
  EXPECT_EQ(keptStrandShare(0.25f, 2.0f), 0.125f);
  EXPECT_EQ(keptStrandShare(1.0f, 1.0f), 1.0f) << "strands as wide as the level-of-detail width";
  EXPECT_EQ(keptStrandShare(3.0f, 1.0f), 1.0f) << "wider strands";
  EXPECT_EQ(keptStrandShare(0.001f, 1.0f), kLeastKeptStrands) << "never fewer than the least share";
  EXPECT_EQ(keptStrandShare(0.5f, 0.0f), 1.0f) << "0 turns the level of detail off";
  EXPECT_EQ(keptStrandShare(0.0f, 1.0f), kLeastKeptStrands) << "a point-sized groom";
}

// A pinhole camera of vertical field of view θ over H pixels spans H / (2 d tan(θ/2)) pixels per
// metre at distance d along its axis, in any direction across it.
TEST(StrandLevelOfDetail, PixelsPerMetreFollowThePinholeCamera) {
  Camera camera{.position = {0.3f, 0.2f, 1.5f}, .target = {0.0f, 0.0f, 0.0f}, .verticalFovRadians = 0.5f};
  const glm::vec2 viewport(1280.0f, 720.0f);
  const glm::mat4 viewProjection = camera.projection(viewport.x / viewport.y) * camera.view();
  const glm::vec3 axis = glm::normalize(camera.target - camera.position);
  for (const float distance : {0.2f, 1.0f, 4.0f, 30.0f}) {
    const float expected = viewport.y / (2.0f * distance * std::tan(0.5f * camera.verticalFovRadians));
    EXPECT_NEAR(pixelsPerMetreAt(viewProjection, viewport, camera.position + axis * distance), expected,
                1e-3f * expected)
        << "at " << distance << " m";
  }
  EXPECT_EQ(pixelsPerMetreAt(viewProjection, viewport, camera.position - axis), 0.0f) << "behind the eye";
}

}  // namespace
}  // namespace mane::render
