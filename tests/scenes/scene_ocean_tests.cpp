// The scene file's "ocean" and "ship" blocks, and a hull filled with cells.
//
// Oracles: the documented defaults and the errors' field paths; the volume a closed mesh holds,
// against its closed form (a procedural sphere, whose facets make it a little smaller than the
// sphere's 4/3 π r³).

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "scenes/procedural.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_ocean.hpp"

namespace mane::scenes {
namespace {

constexpr const char* kCamera = R"("camera": {"position": [0, 5, 20], "target": [0, 0, 0], "far": 30000})";

std::string sceneWith(const std::string& blocks) {
  return std::string(R"({"name": "sea", )") + kCamera +
         R"(, "meshes": [{"name": "boat", "source": "procedural:hull", "transform": {"scale": 10}}])" + blocks + "}";
}

std::string errorOf(const std::string& text) {
  auto scene = parseScene(text, "sea.json");
  return scene ? std::string() : scene.error().message;
}

TEST(SceneOcean, AnOceanAndAShipGetTheDocumentedDefaults) {
  auto scene = parseScene(sceneWith(R"(, "ocean": {}, "ship": {"mesh": "boat", "mass": 5000})"), "sea.json");
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_TRUE(scene->ocean && scene->ship);
  EXPECT_EQ(scene->ocean->waves.windSpeed, 10.0f);
  EXPECT_EQ(scene->ocean->waves.waveCount, 45);
  EXPECT_EQ(scene->ocean->grid, glm::ivec2(150, 150));
  EXPECT_EQ(scene->ocean->foamHalfLife, 3.0f);
  EXPECT_EQ(scene->ship->cells, glm::ivec3(24, 8, 8));
  EXPECT_EQ(scene->ship->drag, 0.5f);
  EXPECT_TRUE(scene->ship->spray);
  EXPECT_TRUE(scene->ship->rigging.empty());
  EXPECT_FALSE(scene->ship->cannon);
  EXPECT_FALSE(scene->ocean->debris);
}

TEST(SceneOcean, RiggingACannonAndDebrisAreReadAsWritten) {
  auto scene = parseScene(sceneWith(R"(, "ocean": {"debris": {"pieces": 5, "radius": 12, "size": 0.8}},
      "ship": {"mesh": "boat", "mass": 5000, "spray": false,
               "rigging": [{"from": [1, 10, 0], "to": [4, 1, 0], "width": 0.1}, {"from": [1, 10, 0], "to": [0, 1, 2]}],
               "cannon": {"muzzle": [0, 1, 2], "direction": [0, 0, 2], "first_seconds": 3, "interval_seconds": 5}})"),
                          "sea.json");
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_FALSE(scene->ship->spray);
  ASSERT_EQ(scene->ship->rigging.size(), 2u);
  EXPECT_EQ(scene->ship->rigging[0].to, glm::vec3(4.0f, 1.0f, 0.0f));
  EXPECT_EQ(scene->ship->rigging[0].width, 0.1f);
  EXPECT_EQ(scene->ship->rigging[1].width, 0.05f);
  ASSERT_TRUE(scene->ship->cannon);
  EXPECT_EQ(scene->ship->cannon->direction, glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(scene->ship->cannon->firstSeconds, 3.0f);
  EXPECT_EQ(scene->ship->cannon->intervalSeconds, 5.0f);
  ASSERT_TRUE(scene->ocean->debris);
  EXPECT_EQ(scene->ocean->debris->pieces, 5);
  EXPECT_EQ(scene->ocean->debris->radius, 12.0f);
  EXPECT_EQ(scene->ocean->debris->size, 0.8f);
}

TEST(SceneOcean, BadBlocksNameTheirField) {
  EXPECT_EQ(errorOf(sceneWith(R"(, "ship": {"mesh": "boat", "mass": 5000})")),
            "sea.json: ship: a ship floats on an ocean: the scene has none");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {}, "ship": {"mesh": "raft", "mass": 5000})")),
            "sea.json: ship.mesh: no mesh named \"raft\" in meshes");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {}, "ship": {"mesh": "boat", "mass": -1})")),
            "sea.json: ship.mass: expected kilograms > 0");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {}, "ship": {"mesh": "boat", "mass": 1, "cells": [4, 0.5, 4]})")),
            "sea.json: ship.cells: expected three whole numbers of cells, 1 to 64 each");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"choppiness": 2})")),
            "sea.json: ocean: Ocean settings: choppiness must be in [0, 1].");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"grid": 4})")),
            "sea.json: ocean.grid: expected 16 to 1024 cells, or [across, down] of 16 to 1024 each");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"grid": [100, 2000]})")),
            "sea.json: ocean.grid: expected 16 to 1024 cells, or [across, down] of 16 to 1024 each");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"grid": [100.5, 150]})")),
            "sea.json: ocean.grid: expected 16 to 1024 cells, or [across, down] of 16 to 1024 each");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"grid": [100]})")),
            "sea.json: ocean.grid: expected 16 to 1024 cells, or [across, down] of 16 to 1024 each");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"grid": [100, "x"]})")),
            "sea.json: ocean.grid[1]: expected a number, got a string");
  auto across = parseScene(sceneWith(R"(, "ocean": {"grid": [100, 150]})"), "sea.json");
  ASSERT_TRUE(across) << across.error().message;
  EXPECT_EQ(across->ocean->grid, glm::ivec2(100, 150));
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"foam": {"half_life": 0}})")),
            "sea.json: ocean.foam.half_life: expected seconds > 0");
  EXPECT_NE(errorOf(sceneWith(R"(, "ocean": {"swell": 1})")).find("ocean.swell: unknown field"), std::string::npos);
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {"debris": {"pieces": 0}})")),
            "sea.json: ocean.debris.pieces: expected 1 to 4096 pieces");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {}, "ship": {"mesh": "boat", "mass": 1,
                                 "rigging": [{"from": [0, 1, 0], "to": [0, 2, 0]}, {"from": [0, 1, 0], "to": [0, 1, 0]}]})")),
            "sea.json: ship.rigging[1].to: expected a point other than `from`");
  EXPECT_EQ(errorOf(sceneWith(R"(, "ocean": {}, "ship": {"mesh": "boat", "mass": 1,
                                 "cannon": {"muzzle": [0, 1, 0], "direction": [0, 0, 0]}})")),
            "sea.json: ship.cannon.direction: expected a direction, not zero");
  const std::string turned = std::string(R"({"name": "sea", )") + kCamera +
                             R"(, "meshes": [{"name": "boat", "source": "procedural:hull",
                                 "transform": {"rotation_degrees": [10, 0, 0]}}],
                                 "ocean": {}, "ship": {"mesh": "boat", "mass": 5000}})";
  EXPECT_EQ(errorOf(turned),
            "sea.json: ship.mesh: the ship's mesh may turn about +Y only (its rotation's x and z must be 0)");
}

TEST(SceneOcean, AMeshRidesOnAnotherThatIsNotItselfAttached) {
  const auto scene = [](const std::string& meshes) {
    return std::string(R"({"name": "sea", )") + kCamera +
           R"(, "meshes": [{"name": "boat", "source": "procedural:hull"})" + meshes + "]}";
  };
  auto good =
      parseScene(scene(R"(, {"name": "mast", "source": "procedural:spar", "attached_mesh": "boat"})"), "sea.json");
  ASSERT_TRUE(good) << good.error().message;
  EXPECT_EQ(good->meshes[1].attachedMesh, "boat");
  EXPECT_EQ(errorOf(scene(R"(, {"name": "mast", "source": "procedural:spar", "attached_mesh": "raft"})")),
            "sea.json: meshes[1].attached_mesh: no other mesh named \"raft\" in meshes");
  EXPECT_EQ(errorOf(scene(R"(, {"name": "mast", "source": "procedural:spar", "attached_mesh": "mast"})")),
            "sea.json: meshes[1].attached_mesh: no other mesh named \"mast\" in meshes");
  EXPECT_EQ(errorOf(scene(R"(, {"name": "mast", "source": "procedural:spar", "attached_mesh": "boat"},
                              {"name": "flag", "source": "procedural:plane", "attached_mesh": "mast"})")),
            "sea.json: meshes[2].attached_mesh: \"mast\" rides on another mesh itself: attach to the one it rides on");
}

TEST(HullCells, ASphereHoldsItsVolume) {
  const Mesh sphere = makeSphere(64, 128, 1.0f);
  const auto cells = hullCells(sphere, 2.0f, {40, 40, 40});
  ASSERT_TRUE(cells) << cells.error().message;
  double volume = 0.0;
  glm::dvec3 centre(0.0);
  for (const physics::HullCell& cell : *cells) {
    const double v = double(cell.size.x) * cell.size.y * cell.size.z;
    volume += v;
    centre += glm::dvec3(cell.centre) * v;
  }
  // Radius 2 after the scale: 4/3 π 8 = 33.51 m³; the cells' staircase is within a percent.
  EXPECT_NEAR(volume / (4.0 / 3.0 * std::numbers::pi * 8.0), 1.0, 0.01);
  EXPECT_LT(glm::length(centre / volume), 0.01);
}

TEST(HullCells, TheProceduralHullIsClosed) {
  const Mesh hull = makeHull(64, 24);
  const auto cells = hullCells(hull, 1.0f, {48, 16, 16});
  ASSERT_TRUE(cells) << cells.error().message;
  // Every cell lies within the hull's bounds.
  const Bounds bounds = hull.bounds();
  for (const physics::HullCell& cell : *cells) {
    EXPECT_GE(cell.centre.x, bounds.min.x);
    EXPECT_LE(cell.centre.x, bounds.max.x);
    EXPECT_GE(cell.centre.y, bounds.min.y);
    EXPECT_LE(cell.centre.y, bounds.max.y);
  }
  double volume = 0.0;
  for (const physics::HullCell& cell : *cells) volume += double(cell.size.x) * cell.size.y * cell.size.z;
  // A closed hull of length 1, beam 0.28 and depth 0.16 amidships holds a share of its box
  // between a diamond's (1/3) and the box's own: an open one would hold nothing or its box.
  const double box = 1.0 * 0.28 * 0.16;
  EXPECT_GT(volume, 0.4 * box);
  EXPECT_LT(volume, 0.9 * box);
}

TEST(HullCells, ASparHoldsItsCylinder) {
  // 16 sides: the polygon's area is (16/2π)·sin(2π/16) = 0.9745 of the circle's.
  const Mesh spar = makeSpar(0.015f, 16);
  const auto cells = hullCells(spar, 10.0f, {24, 4, 24});
  ASSERT_TRUE(cells) << cells.error().message;
  double volume = 0.0;
  for (const physics::HullCell& cell : *cells) volume += double(cell.size.x) * cell.size.y * cell.size.z;
  const double polygon = 0.5 * 16.0 * std::sin(2.0 * std::numbers::pi / 16.0) * 0.15 * 0.15 * 10.0;
  EXPECT_NEAR(volume / polygon, 1.0, 0.03);
}

TEST(HullCells, AnOpenSheetHoldsNothing) {
  const Mesh plane = makePlane(1.0f);
  const auto cells = hullCells(plane, 1.0f, {4, 4, 4});
  ASSERT_FALSE(cells);
  EXPECT_NE(cells.error().message.find("is it closed?"), std::string::npos);
}

}  // namespace
}  // namespace mane::scenes
