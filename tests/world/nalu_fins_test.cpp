// nalu.json's fins over one loop of the head's turns and shakes, in the head's body frame: they
// stay out of the head, stay open (their rays held where the body holds them), and their
// membrane moves between the rays. CPU only.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "physics/sdf.hpp"
#include "scenes/fin_cloth.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/world/body_frame.hpp"

namespace mane::scenes {
namespace {

const std::filesystem::path kNalu = std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json";

using testing::transformPoint;
using testing::worldToBody;

/// The angle between a fin's first and last ray, each from its base row to its tip.
double openingDegrees(std::span<const glm::vec3> body, const FinShape& shape, int columns) {
  const auto ray = [&](int column) {
    return glm::normalize(glm::dvec3(body[(shape.rows - 1) * columns + column]) - glm::dvec3(body[columns + column]));
  };
  return glm::degrees(std::acos(std::clamp(glm::dot(ray(0), ray(columns - 1)), -1.0, 1.0)));
}

TEST(NaluFins, StayOutOfTheHeadStayOpenAndRippleBetweenTheirRays) {
  auto scene = loadScene(kNalu);
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  scene->grooms.clear();  // the fins do not touch the hair; without it the loop runs in a second
  const Scene copy = *scene;
  const MeshInstance& head = *copy.findMesh("head");
  auto world = World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world) << world.error().message;
  ASSERT_EQ(world->cloths().size(), 2u);

  struct Track {
    const SceneCloth* cloth = nullptr;
    FinShape shape;
    int columns = 0;
    std::vector<glm::vec3> rest;                 // body frame, at the start
    std::vector<std::vector<glm::vec3>> frames;  // body frame, each frame of the loop
  };
  std::vector<Track> fins;
  for (std::size_t c = 0; c < 2; ++c) {
    ASSERT_EQ(copy.cloths[c].source, "procedural:fin");
    Track track{
        .cloth = &world->cloths()[c], .shape = copy.cloths[c].fin, .columns = makeFin(copy.cloths[c].fin).columns};
    const glm::mat4 toBody = worldToBody(copy, head, world->time());
    for (const glm::vec3& p : track.cloth->cloth().particles().positions)
      track.rest.push_back(transformPoint(toBody, p));
    fins.push_back(std::move(track));
  }
  const double restOpening = openingDegrees(fins[0].rest, fins[0].shape, fins[0].columns);

  // One second to settle, then the six-second loop of turns and shakes at 30 frames a second.
  for (int frame = 0; frame < 30; ++frame) ASSERT_TRUE(world->advance(1.0 / 30.0, 2).has_value());
  float nearest = std::numeric_limits<float>::infinity();
  double narrowest = 180.0, farthestTip = 0.0;
  for (int frame = 0; frame < 180; ++frame) {
    ASSERT_TRUE(world->advance(1.0 / 30.0, 2).has_value());
    const glm::mat4 toBody = worldToBody(copy, head, world->time());
    for (Track& fin : fins) {
      const physics::SignedDistanceField& field = *fin.cloth->colliders().sdf;
      const auto& particles = fin.cloth->cloth().particles();
      std::vector<glm::vec3> body;
      for (std::size_t v = 0; v < particles.size(); ++v) {
        body.push_back(transformPoint(toBody, particles.positions[v]));
        if (particles.inverseMasses[v] > 0.0f) nearest = std::min(nearest, field.sample(body.back()));
      }
      narrowest = std::min(narrowest, openingDegrees(body, fin.shape, fin.columns));
      for (int ray = 0; ray < fin.shape.rays; ++ray) {
        const std::size_t tip = std::size_t((fin.shape.rows - 1) * fin.columns + ray * kFinColumnsPerGap);
        farthestTip = std::max(farthestTip, double(glm::distance(body[tip], fin.rest[tip])));
      }
      fin.frames.push_back(std::move(body));
    }
  }

  // The membrane midway between two rays, in the fin's outer half, against the midpoint of the two
  // rays beside it: how far that offset strays from its mean over the loop (root mean square).
  // Rays held at full stiffness leave 0.2 mm; rays held at a twentieth let the fin fold to 12
  // degrees.
  double membraneSquares = 0.0;
  int samples = 0;
  for (const Track& fin : fins)
    for (int row = fin.shape.rows / 2; row < fin.shape.rows; ++row)
      for (int gap = 0; gap + 1 < fin.shape.rays; ++gap) {
        const std::size_t left = std::size_t(row * fin.columns + gap * kFinColumnsPerGap);
        const std::size_t middle = left + kFinColumnsPerGap / 2, right = left + kFinColumnsPerGap;
        std::vector<glm::dvec3> offsets;
        glm::dvec3 mean(0.0);
        for (const auto& body : fin.frames) {
          offsets.push_back(glm::dvec3(body[middle]) - 0.5 * (glm::dvec3(body[left]) + glm::dvec3(body[right])));
          mean += offsets.back() / double(fin.frames.size());
        }
        for (const glm::dvec3& offset : offsets) membraneSquares += glm::dot(offset - mean, offset - mean);
        samples += int(offsets.size());
      }
  const double ripple = std::sqrt(membraneSquares / samples);

  const float thickness = copy.cloths[0].colliders.thickness;
  EXPECT_GT(nearest, thickness - 1e-4f) << "a fin vertex came " << nearest * 1e3f << " mm from the head";
  EXPECT_GT(narrowest, 0.7 * restOpening) << "a fin closed from " << restOpening << " to " << narrowest << " degrees";
  EXPECT_LT(farthestTip, 0.5 * copy.cloths[0].fin.length) << "a ray's tip strayed " << farthestTip * 1e3 << " mm";
  EXPECT_GT(ripple, 0.0003) << "the membrane hardly moves between the rays: " << ripple * 1e3 << " mm";
  RecordProperty("nearest_to_head_mm", std::to_string(nearest * 1e3f));
  RecordProperty("opening_degrees_rest", std::to_string(restOpening));
  RecordProperty("opening_degrees_narrowest", std::to_string(narrowest));
  RecordProperty("farthest_tip_mm", std::to_string(farthestTip * 1e3));
  RecordProperty("membrane_ripple_mm", std::to_string(ripple * 1e3));
}

}  // namespace
}  // namespace mane::scenes
