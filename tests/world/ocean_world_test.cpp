// clear_sailing.json's sea and ship through the World.
//
// Oracles: the constraints the demo sets (the ship keeps its place and heading), the drawn hull
// placed by the body's frame, the sea the renderer is given being the physics' waves, and one
// state hash for 1, 2 and 4 threads.

#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "scenes/world.hpp"

namespace mane::scenes {
namespace {

const std::filesystem::path kClearSailing = std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "clear_sailing.json";

World loadClearSailing() {
  auto scene = loadScene(kClearSailing);
  EXPECT_TRUE(scene) << scene.error().message;
  auto world = World::create(std::move(*scene), *AssetResolver::createDefault(), {.loadTextures = false});
  EXPECT_TRUE(world) << world.error().message;
  return std::move(*world);
}

TEST(OceanWorld, TheShipRidesTheSeaInItsPlaceAndTheHullIsDrawnWhereItFloats) {
  World world = loadClearSailing();
  const MeshInstance& ship = *world.scene().findMesh("ship");
  const float heading = glm::radians(ship.transform.rotationDegrees.y);
  float lowest = 1e9f, highest = -1e9f;
  for (int frame = 0; frame < 150; ++frame) {
    ASSERT_TRUE(world.advance(1.0 / 30.0, 1));
    const render::FrameInput input = world.frameInput();
    const render::MeshInstance& hull = input.instances.at(0);
    // The model's bow (+x) keeps the heading in the horizontal plane; the hull is 30 m long.
    const glm::vec3 bow = glm::vec3(hull.model[0]);
    EXPECT_NEAR(glm::length(bow), ship.transform.scale, 1e-3f);
    const glm::vec2 level = glm::normalize(glm::vec2(bow.x, bow.z));
    ASSERT_NEAR(level.x, std::cos(heading), 1e-5f);
    ASSERT_NEAR(level.y, -std::sin(heading), 1e-5f);
    lowest = std::min(lowest, hull.model[3].y);
    highest = std::max(highest, hull.model[3].y);
    // The masts ride on the hull: the foremast's foot stays where the scene puts it in the hull's frame.
    const render::MeshInstance& mast = input.instances.at(1);
    const glm::vec3 foot = glm::vec3(glm::inverse(hull.model) * mast.model * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const glm::vec3 placed = world.scene().findMesh("foremast")->transform.translation / ship.transform.scale;
    ASSERT_NEAR(glm::distance(foot, placed), 0.0f, 1e-4f);
    // The sea drawn is the sea simulated: one phase per wave.
    ASSERT_TRUE(input.ocean.has_value());
    ASSERT_EQ(input.ocean->phases.size(), world.staticScene().ocean->waves.size());
  }
  // It heaves on waves of 4 m significant height (a 14 m/s wind), and stays afloat.
  EXPECT_GT(highest - lowest, 0.3f);
  EXPECT_LT(highest - lowest, 8.0f);
}

TEST(OceanWorld, TheShipsStateIsTheSameForOneTwoAndFourThreads) {
  std::uint64_t hashes[3] = {};
  const unsigned threads[3] = {1, 2, 4};
  for (int i = 0; i < 3; ++i) {
    World world = loadClearSailing();
    for (int frame = 0; frame < 45; ++frame) ASSERT_TRUE(world.advance(1.0 / 30.0, threads[i]));
    hashes[i] = world.stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

}  // namespace
}  // namespace mane::scenes
