// scenes/cape.json over ten seconds of its head shake: the cape hangs over the bust and the
// capsules that stand for the body below it without entering either, falls in folds, and does not
// pass through itself. CPU only.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <vector>

#include <glm/geometric.hpp>

#include "physics/sdf.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/world/body_frame.hpp"

namespace mane::scenes {
namespace {

const std::filesystem::path kCape = std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "cape.json";

using testing::transformPoint;
using testing::worldToBody;

float capsuleDistance(const physics::CapsuleCollider& capsule, const glm::vec3& p) {
  const glm::vec3 ab = capsule.b - capsule.a;
  const float s = std::clamp(glm::dot(p - capsule.a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::distance(p, capsule.a + s * ab) - capsule.radius;
}

/// Where segment pq crosses triangle abc (Möller & Trumbore 1997), in double precision: true
/// when it does, strictly between its ends.
bool segmentCrossesTriangle(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c) {
  const glm::dvec3 direction = q - p, e1 = b - a, e2 = c - a, h = glm::cross(direction, e2);
  const double det = glm::dot(e1, h);
  if (std::abs(det) < 1e-30) return false;
  const glm::dvec3 s = p - a;
  const double u = glm::dot(s, h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 r = glm::cross(s, e1);
  const double v = glm::dot(direction, r) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = glm::dot(e2, r) / det;
  return t > 0.0 && t < 1.0;
}

/// How many (edge, triangle) pairs of the mesh cross, leaving out the pairs that share a vertex:
/// a surface that passes through itself has at least two. Triangles are bucketed in a uniform
/// grid of cells `cell` wide, so each edge is tested against its neighbourhood only.
std::size_t selfCrossings(std::span<const glm::vec3> positions, std::span<const std::uint32_t> triangles, float cell) {
  using Cell = std::array<int, 3>;
  const auto cellOf = [&](const glm::vec3& p) {
    return Cell{int(std::floor(p.x / cell)), int(std::floor(p.y / cell)), int(std::floor(p.z / cell))};
  };
  std::map<Cell, std::vector<std::uint32_t>> buckets;
  for (std::uint32_t t = 0; t < triangles.size() / 3; ++t) {
    glm::vec3 low(std::numeric_limits<float>::infinity()), high(-std::numeric_limits<float>::infinity());
    for (int k = 0; k < 3; ++k) {
      low = glm::min(low, positions[triangles[3 * t + k]]);
      high = glm::max(high, positions[triangles[3 * t + k]]);
    }
    const Cell from = cellOf(low), to = cellOf(high);
    for (int x = from[0]; x <= to[0]; ++x)
      for (int y = from[1]; y <= to[1]; ++y)
        for (int z = from[2]; z <= to[2]; ++z) buckets[{x, y, z}].push_back(t);
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, bool> edges;
  for (std::size_t t = 0; t < triangles.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles[t + k], b = triangles[t + (k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}] = true;
    }
  std::size_t crossings = 0;
  for (const auto& [edge, unused] : edges) {
    const glm::vec3 p = positions[edge.first], q = positions[edge.second];
    const Cell from = cellOf(glm::min(p, q)), to = cellOf(glm::max(p, q));
    std::vector<std::uint32_t> nearby;
    for (int x = from[0]; x <= to[0]; ++x)
      for (int y = from[1]; y <= to[1]; ++y)
        for (int z = from[2]; z <= to[2]; ++z)
          if (auto found = buckets.find({x, y, z}); found != buckets.end())
            nearby.insert(nearby.end(), found->second.begin(), found->second.end());
    std::sort(nearby.begin(), nearby.end());
    nearby.erase(std::unique(nearby.begin(), nearby.end()), nearby.end());
    for (std::uint32_t t : nearby) {
      const std::uint32_t* corner = &triangles[3 * t];
      if (std::find(corner, corner + 3, edge.first) != corner + 3 ||
          std::find(corner, corner + 3, edge.second) != corner + 3)
        continue;
      crossings += segmentCrossesTriangle(p, q, positions[corner[0]], positions[corner[1]], positions[corner[2]]);
    }
  }
  return crossings;
}

TEST(SelfCrossings, FindsASheetThroughAnotherAndNoneInASheetAlone) {
  // Two triangles: one in z = 0, one standing through it.
  const std::vector<glm::vec3> positions = {{0, 0, 0},           {1, 0, 0},          {0, 1, 0},
                                            {0.2f, 0.2f, -0.5f}, {0.3f, 0.2f, 0.5f}, {0.25f, 0.3f, 0.5f}};
  EXPECT_EQ(selfCrossings(positions, std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}, 0.25f), 2u);
  EXPECT_EQ(selfCrossings(positions, std::vector<std::uint32_t>{0, 1, 2}, 0.25f), 0u);
}

/// The folds of the cape's hem: local maxima of its distance from the vertical through the collar's
/// centre, along the hem, that stand at least `prominence` above the minima on both sides.
int hemFolds(std::span<const glm::vec3> hem, const glm::vec3& axis, float prominence) {
  std::vector<float> radius;
  for (const glm::vec3& p : hem) radius.push_back(std::hypot(p.x - axis.x, p.z - axis.z));
  int folds = 0;
  float low = radius.front();
  bool rising = true;
  float peak = radius.front();
  for (float r : radius) {
    if (rising) {
      peak = std::max(peak, r);
      if (r < peak - prominence) {
        folds += peak - low >= prominence;
        rising = false;
        low = r;
      }
    } else {
      low = std::min(low, r);
      if (r > low + prominence) {
        rising = true;
        peak = r;
      }
    }
  }
  return folds;
}

// Every frame for ten seconds of the shake (30 frames a second), in the bust's body frame: every
// cape vertex outside the bust's field and outside both capsules (from the scene's own numbers)
// by the scene's collision thickness less 0.1 mm (float rounding of the body-frame transforms);
// that it touches them at all (else this would prove nothing); every fifth frame, no edge of the
// cape through one of its triangles; and at the end, the hem in folds.
TEST(CapeDrape, StaysOutsideTheBodyAndItselfOverTenSecondsOfTheShake) {
  auto scene = loadScene(kCape);
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const Scene copy = *scene;
  const MeshInstance& head = *copy.findMesh("head");
  const Colliders& colliders = copy.cloths[0].colliders;
  ASSERT_EQ(colliders.capsules.size(), 2u);
  auto world = World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world) << world.error().message;
  const SceneCloth& cape = world->cloths()[0];
  ASSERT_TRUE(cape.colliders().sdf) << "the bust's field";
  const physics::SignedDistanceField& field = *cape.colliders().sdf;

  float nearestField = std::numeric_limits<float>::infinity(), nearestCapsule = nearestField;
  std::size_t crossings = 0;
  int checks = 0;
  for (int frame = 1; frame <= 300; ++frame) {
    ASSERT_TRUE(world->advance(1.0 / 30.0, 2).has_value());
    const glm::mat4 toBody = worldToBody(copy, head, world->time());
    const auto positions = cape.cloth().particles().positions;
    for (std::size_t v = 0; v < positions.size(); ++v) {
      if (cape.cloth().particles().inverseMasses[v] == 0.0f) continue;  // the collar, sewn where the scene says
      const glm::vec3 body = transformPoint(toBody, positions[v]);
      nearestField = std::min(nearestField, field.sample(body));
      for (const physics::CapsuleCollider& capsule : colliders.capsules)
        nearestCapsule = std::min(nearestCapsule, capsuleDistance(capsule, body));
    }
    if (frame % 5 == 0) {
      crossings += selfCrossings(positions, cape.surface().indices, 0.01f);
      ++checks;
    }
  }
  const float thickness = colliders.thickness;
  EXPECT_GT(nearestField, thickness - 1e-4f) << "a vertex came " << nearestField * 1e3f << " mm from the bust";
  EXPECT_GT(nearestCapsule, thickness - 1e-4f) << "a vertex came " << nearestCapsule * 1e3f << " mm from a capsule";
  EXPECT_LT(nearestField, thickness + 0.001f) << "the cape never lay on the bust";
  EXPECT_LT(nearestCapsule, thickness + 0.001f) << "the cape never reached the body below the bust";
  EXPECT_EQ(crossings, 0u) << "edge-triangle crossings summed over " << checks << " frames";

  const CapeShape& shape = copy.cloths[0].cape;
  const auto positions = cape.cloth().particles().positions;
  const glm::mat4 toBody = worldToBody(copy, head, world->time());
  std::vector<glm::vec3> hem;
  for (int column = 0; column < shape.columns; ++column)
    hem.push_back(transformPoint(toBody, positions[std::size_t((shape.rows - 1) * shape.columns + column)]));
  const int folds = hemFolds(hem, copy.cloths[0].transform.translation, 0.005f);
  EXPECT_GE(folds, 4) << "the hem hangs in too few folds";

  RecordProperty("nearest_to_bust_mm", std::to_string(nearestField * 1e3f));
  RecordProperty("nearest_to_capsule_mm", std::to_string(nearestCapsule * 1e3f));
  RecordProperty("self_crossings", std::to_string(crossings));
  RecordProperty("hem_folds", std::to_string(folds));
}

// The same cape at the coarser steps the scene once used (1/120 s, 12 sweeps), where the shake
// does fold it through itself: counted every tenth frame over ten seconds, there are crossings
// without self collision and none with it at 3 mm. Vertices alone are not enough there (long
// hem edges cross short triangles in the deepest folds), so this holds the edge pass too.
TEST(CapeDrape, AtCoarseStepsSelfCollisionKeepsItOffItself) {
  auto scene = loadScene(kCape);
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const auto crossingsWith = [&](float selfCollision) {
    Scene coarse = *scene;
    coarse.simulation.stepSeconds = 1.0f / 120.0f;
    coarse.simulation.maxStepsPerFrame = 8;
    coarse.cloths[0].iterations = 12;
    coarse.cloths[0].selfCollision = selfCollision;
    auto world = World::create(std::move(coarse), testing::sharedResolver(), {.loadTextures = false});
    EXPECT_TRUE(world) << world.error().message;
    std::size_t crossings = 0;
    if (!world) return crossings;
    for (int frame = 1; frame <= 300; ++frame) {
      EXPECT_TRUE(world->advance(1.0 / 30.0, 2).has_value());
      if (frame % 10 == 0)
        crossings += selfCrossings(world->cloths()[0].cloth().particles().positions,
                                   world->cloths()[0].surface().indices, 0.01f);
    }
    return crossings;
  };
  const std::size_t loose = crossingsWith(0.0f), guarded = crossingsWith(0.003f);
  EXPECT_GT(loose, 0u) << "at these steps the shake should fold the cape through itself";
  EXPECT_EQ(guarded, 0u) << "edge-triangle crossings summed over 30 frames";
  RecordProperty("crossings_without_self_collision", std::to_string(loose));
  RecordProperty("crossings_with_self_collision", std::to_string(guarded));
}

}  // namespace
}  // namespace mane::scenes
