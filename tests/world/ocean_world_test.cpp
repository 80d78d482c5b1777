// clear_sailing.json's sea and ship through the World.
//
// Oracles: the constraints the demo sets (the ship keeps its place and heading), the drawn hull
// placed by the body's frame, the sea the renderer is given being the physics' waves; the
// rigging riding the hull; the cannon's puffs stopped by the air within their speed over its
// drag (beyond the wind's drift); spray leaving the hull's side at the sea; and one state hash
// for the ship, sails, spray, smoke and debris with 1, 2 and 4 threads.

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "scenes/world.hpp"

namespace mane::scenes {
namespace {

const std::filesystem::path kClearSailing = std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "clear_sailing.json";

// Whether `p` (the hull's frame, metres) lies within a cell of the waterplane's side, plus
// `slack` metres: procedural:hull is 30 m long, its half beam 4.2 m · √(1 − t²) forward and
// √(1 − t⁴) aft, t = x / 15 m; its cells are 1.25 m long and 1.05 m wide. A contact at a corner
// cell's corner reaches half a cell past the ends, where the outline narrows fastest, so the
// beam is taken half a cell nearer amidships.
bool nearHullSide(glm::vec3 p, float slack) {
  const float t = std::copysign(std::max(0.0f, std::abs(p.x) - 0.625f), p.x) / 15.0f;
  const float halfBeam = 4.2f * std::sqrt(std::max(0.0f, 1.0f - (t < 0.0f ? t * t * t * t : t * t)));
  const bool within = std::abs(p.x) < 15.0f + 1.3f + slack && std::abs(p.z) < halfBeam + 1.1f + slack;
  return within && (std::abs(p.x) > 15.0f - 2.6f - slack || std::abs(p.z) > halfBeam - 1.6f - slack);
}

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

TEST(OceanWorld, TheRiggingRidesTheHullAndTheDebrisFloatsRoundIt) {
  World world = loadClearSailing();
  const Scene& scene = world.scene();
  for (int frame = 0; frame < 60; ++frame) ASSERT_TRUE(world.advance(1.0 / 30.0, 1));
  const render::FrameInput input = world.frameInput();
  const render::MeshInstance& hull = input.instances.at(0);
  const float scale = scene.findMesh("ship")->transform.scale;
  ASSERT_EQ(input.effects.lines.size(), scene.ship->rigging.size());
  for (std::size_t i = 0; i < input.effects.lines.size(); ++i) {
    const glm::vec3 from = glm::vec3(hull.model * glm::vec4(scene.ship->rigging[i].from / scale, 1.0f));
    EXPECT_NEAR(glm::distance(input.effects.lines[i].from, from), 0.0f, 1e-3f);
    EXPECT_EQ(input.effects.lines[i].width, scene.ship->rigging[i].width);
  }
  // The sea foams where the hull's side meets it: each source's water lies at the hull's side.
  ASSERT_FALSE(input.ocean->foamSources.empty());
  ASSERT_LE(input.ocean->foamSources.size(), render::kMaxFoamSources);
  for (const glm::vec4& source : input.ocean->foamSources) {
    const physics::OceanSample water = world.ocean()->waves().sample({source.x, source.y}, world.time());
    const glm::vec3 inHull = glm::vec3(glm::inverse(hull.model) * glm::vec4(water.position, 1.0f)) * scale;
    EXPECT_TRUE(nearHullSide(inHull, 0.0f)) << inHull.x << ", " << inHull.z;
  }
  // The hull hides the sky in the water's reflection: the ellipsoid inscribed in its bounds,
  // placed where it floats.
  ASSERT_TRUE(input.ocean->reflector.has_value());
  const glm::mat4 hullFromSphere = glm::inverse(hull.model) * input.ocean->reflector->worldFromUnitSphere;
  const glm::vec3 middle(hullFromSphere * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const glm::vec3 bow(hullFromSphere * glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  EXPECT_NEAR(glm::distance(bow, middle) * scale, 15.0f, 0.05f);  // half the hull's 30 m
  EXPECT_NEAR(middle.x * scale, 0.0f, 0.05f);
  ASSERT_EQ(input.effects.triangles.size(), std::size_t(scene.ocean->debris->pieces));
  const physics::OceanWaves& sea = world.ocean()->waves();
  const glm::mat4 sphereFromWorld = glm::inverse(input.ocean->reflector->worldFromUnitSphere);
  for (const render::EffectTriangle& piece : input.effects.triangles) {
    const glm::vec3 centroid = (piece.corners[0] + piece.corners[1] + piece.corners[2]) / 3.0f;
    const float surface = sea.surfaceAt({centroid.x, centroid.z}, world.time()).position.y;
    EXPECT_LT(std::abs(centroid.y - surface), 0.3f);
    // Round it: outside the hull's ellipsoid.
    for (const glm::vec3& corner : piece.corners)
      EXPECT_GE(glm::length(glm::vec3(sphereFromWorld * glm::vec4(corner, 1.0f))), 1.0f - 1e-4f);
  }
}

TEST(OceanWorld, TheCannonsSmokeStopsWithinItsSpeedOverTheDragAndDriftsWithTheWind) {
  World world = loadClearSailing();
  const Cannon& cannon = *world.scene().ship->cannon;
  const physics::EffectParticles& smoke = *world.ocean()->smoke();
  // Until it fires by itself there is none; then a shot's puffs.
  while (world.time() + 1.0 / 60.0 < cannon.firstSeconds) {
    ASSERT_TRUE(world.advance(1.0 / 60.0, 1));
    ASSERT_TRUE(smoke.particles().empty()) << world.time();
  }
  ASSERT_TRUE(world.advance(2.0 / 60.0, 1));
  ASSERT_EQ(smoke.particles().size(), 60u);
  // Where they were fired from: the oldest puff's start, traced back through its closed form.
  const physics::EffectParticleSettings& air = smoke.settings();
  const glm::vec3 wind = world.ocean()->wind();
  const glm::vec3 terminal = wind + air.acceleration / air.dragPerSecond;
  const auto launchedFrom = [&](const physics::EffectParticle& p) {
    const float decay = std::exp(-air.dragPerSecond * p.age);
    const glm::vec3 v0 = terminal + (p.velocity - terminal) / decay;
    return p.position - terminal * p.age - (v0 - terminal) * (1.0f - decay) / air.dragPerSecond;
  };
  const glm::vec3 muzzle = launchedFrom(smoke.particles()[0]);
  ASSERT_TRUE(world.advance(3.0, 1));
  for (const physics::EffectParticle& puff : smoke.particles()) {
    // Beyond the drift of the wind (and the warm air's lift), at most 40 m/s over 2 per second.
    const glm::vec3 blown = puff.position - muzzle - terminal * puff.age;
    EXPECT_LT(glm::length(blown), 40.0f / air.dragPerSecond + 0.5f);
    EXPECT_NEAR(glm::distance(launchedFrom(puff), muzzle), 0.0f, 0.05f);
  }
}

TEST(OceanWorld, TheSailsPushTrimsTheShipByTheHead) {
  // The same sea with and without wind on the sails (the waves' wind unchanged). Square sails
  // across the ship take the wind mostly from astern: their push, handed to the hull through
  // the yards high over its centre of mass, would drive it ahead (it keeps its place) and turns
  // its bow down about the lateral axis. Means over 4 s after 2 s of settling, 30 frames a second.
  const auto meanPitchAndMoment = [](bool sailsInTheWind) {
    auto scene = loadScene(kClearSailing);
    EXPECT_TRUE(scene) << scene.error().message;
    if (!sailsInTheWind)
      for (Cloth& cloth : scene->cloths) cloth.wind = glm::vec3(0.0f);
    auto world = World::create(std::move(*scene), *AssetResolver::createDefault(), {.loadTextures = false});
    EXPECT_TRUE(world) << world.error().message;
    double pitch = 0.0;
    glm::dvec3 moment(0.0);  // about the lateral (pitch) axis, the long (roll) axis, the vertical
    for (int frame = 0; frame < 180; ++frame) {
      EXPECT_TRUE(world->advance(1.0 / 30.0, 1));
      if (frame < 60) continue;
      const physics::FloatingBody& ship = *world->ocean()->ship();
      pitch += ship.state().pitch / 120.0;
      const glm::mat4 body = ship.transform();
      glm::vec3 push(0.0f);
      for (const SceneCloth& sail : world->cloths()) push += sail.cloth().windPush(glm::vec3(body[3])).moment;
      moment += glm::dvec3(glm::dot(push, glm::normalize(glm::vec3(body[2]))),
                           glm::dot(push, glm::normalize(glm::vec3(body[0]))),
                           glm::dot(push, glm::normalize(glm::vec3(body[1])))) /
                120.0;
    }
    return std::pair(pitch, moment);
  };
  const auto [pitchInTheWind, moment] = meanPitchAndMoment(true);
  const auto [pitchBecalmed, still] = meanPitchAndMoment(false);
  RecordProperty("trim_degrees", std::to_string(glm::degrees(pitchInTheWind - pitchBecalmed)));
  RecordProperty("pitch_moment_kNm", std::to_string(moment.x / 1000.0));
  RecordProperty("roll_moment_kNm", std::to_string(moment.y / 1000.0));
  EXPECT_LT(glm::length(still), 1e-2 * glm::length(moment));  // the sails swinging through still air
  EXPECT_GT(std::abs(moment.x), 10.0 * std::abs(moment.y));
  // A positive pitch raises the bow: a turn about +z by the right hand, as the moment's.
  EXPECT_GT((pitchInTheWind - pitchBecalmed) * moment.x, 0.0);
}

TEST(OceanWorld, SprayLeavesTheHullsSideAtTheSea) {
  World world = loadClearSailing();
  std::size_t most = 0;
  int fresh = 0;
  for (int frame = 0; frame < 150; ++frame) {
    ASSERT_TRUE(world.advance(1.0 / 30.0, 1));
    const physics::EffectParticles& spray = *world.ocean()->spray();
    most = std::max(most, spray.particles().size());
    const glm::mat4 hullModel = world.frameInput().instances.at(0).model;
    const float scale = world.scene().findMesh("ship")->transform.scale;
    for (const physics::EffectParticle& drop : spray.particles()) {
      // Thrown in the last step: from the hull's side, half a metre along it, a step's flight away.
      if (drop.age <= 1.0f / 60.0f + 1e-6f) {
        const glm::vec3 inHull = glm::vec3(glm::inverse(hullModel) * glm::vec4(drop.position, 1.0f)) * scale;
        EXPECT_TRUE(nearHullSide(inHull, 0.8f)) << inHull.x << ", " << inHull.z;
        ++fresh;
      }
      if (drop.velocity.y >= 0.0f) continue;
      // A falling drop that reaches the sea is gone: none lies under it by more than a step's fall
      // (the frame's time may run ahead of the last step's).
      const float surface = world.ocean()->waves().sample({drop.position.x, drop.position.z}, world.time()).position.y;
      EXPECT_GE(drop.position.y, surface - 0.3f);
    }
  }
  EXPECT_GT(most, 20u);
  EXPECT_GT(fresh, 20);
}

TEST(OceanWorld, AStrongerWindGrowsTheSeaOfItsSpectrum) {
  World world = loadClearSailing();
  ASSERT_TRUE(world.advance(1.0 / 30.0, 1));
  ASSERT_TRUE(world.setWindSpeed(20.0f));
  // The waves the renderer is given now hold the energy of a 20 m/s sea: 4√(Σ A²/2) is its
  // significant height within the 1 % the bands leave out.
  const render::StaticScene drawn = world.staticScene();
  double energy = 0.0;
  for (const glm::vec4& wave : drawn.ocean->waves) energy += 0.5 * double(wave.w) * wave.w;
  EXPECT_NEAR(4.0 * std::sqrt(energy) / physics::piersonMoskowitzSignificantHeight(20.0), 1.0, 0.01);
  EXPECT_NEAR(glm::length(world.ocean()->wind()), 20.0f, 1e-4f);
  const glm::vec3 before = glm::normalize(world.ocean()->wind());
  EXPECT_NEAR(before.z / before.x, 0.4f, 1e-5f);  // the scene's direction, kept
  ASSERT_TRUE(world.advance(1.0 / 30.0, 1));
  EXPECT_EQ(world.frameInput().ocean->phases.size(), world.staticScene().ocean->waves.size());
  EXPECT_FALSE(world.setWindSpeed(-3.0f));
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
