// The limit surface where the World uses it (hair roots, and tessellations refreshed when the
// camera moves): a procedural groom on a subdivided mesh grows from the limit surface itself,
// and the World tessellates its subdivided meshes again as the camera moves.
//
// Oracles: the limit surface evaluated here, from the scene's cage, with OpenSubdiv (a root's
// distance to it found by Gauss-Newton projection, its normal ∂u × ∂v there); Archimedes'
// hat-box theorem for "uniform by area" on a sphere-like cap (area is proportional to height);
// a fresh tessellation of the same view for the re-tessellated one; closedness by matching
// every directed edge with its reverse.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "scenes/limit_scalp.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_meshes.hpp"
#include "scenes/subdivided_mesh.hpp"
#include "scenes/world.hpp"
#include "subdiv/limit.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/scenes/subdivision_test_shapes.hpp"

namespace mane::scenes {
namespace {

using testing::quadSphereObj;
using testing::unmatchedEdges;

/// The closest point of a limit surface to a point near it: the nearest samples of a grid over
/// every ptex face start Gauss-Newton iterations on |S(u, v) − p|², each kept inside its face.
class LimitProjector {
public:
  explicit LimitProjector(const subdiv::LimitSurface& surface) : surface_(surface) {
    for (std::uint32_t f = 0; f < surface.ptexFaceCount(); ++f)
      for (int j = 0; j <= kGrid; ++j)
        for (int i = 0; i <= kGrid; ++i)
          samples_.push_back({f, glm::dvec2(double(i) / kGrid, double(j) / kGrid),
                              surface.evaluatePosition(f, double(i) / kGrid, double(j) / kGrid)});
  }

  struct Hit {
    double distance = std::numeric_limits<double>::max();
    std::uint32_t face = 0;
    glm::dvec2 uv{0.0};
  };

  Hit project(const glm::dvec3& p) const {
    std::vector<const Sample*> nearest;
    for (const Sample& sample : samples_) nearest.push_back(&sample);
    const std::size_t starts = std::min<std::size_t>(16, nearest.size());
    std::partial_sort(nearest.begin(), nearest.begin() + std::ptrdiff_t(starts), nearest.end(),
                      [&](const Sample* a, const Sample* b) {
                        return glm::distance(a->position, p) < glm::distance(b->position, p);
                      });
    Hit best;
    for (std::size_t s = 0; s < starts; ++s) {
      const std::uint32_t face = nearest[s]->face;
      glm::dvec2 uv = nearest[s]->uv;
      double distance = glm::distance(surface_.evaluatePosition(face, uv.x, uv.y), p);
      for (int iteration = 0; iteration < 100 && distance > 1e-12; ++iteration) {
        const subdiv::LimitSample at = surface_.evaluate(face, uv.x, uv.y);
        const glm::dvec3 du(at.du), dv(at.dv);
        const glm::dvec3 r = p - surface_.evaluatePosition(face, uv.x, uv.y);
        const double a = glm::dot(du, du), b = glm::dot(du, dv), c = glm::dot(dv, dv);
        const double ru = glm::dot(du, r), rv = glm::dot(dv, r);
        const double det = a * c - b * b;
        if (!(det > 0.0)) break;
        // A Gauss-Newton step, halved until it brings the point closer (damped: near the
        // extraordinary poles the parametrisation bends fast).
        glm::dvec2 step = glm::dvec2(c * ru - b * rv, a * rv - b * ru) / det;
        bool closer = false;
        for (int halving = 0; halving < 30 && !closer; ++halving, step *= 0.5) {
          const glm::dvec2 next = glm::clamp(uv + step, 0.0, 1.0);
          const double d = glm::distance(surface_.evaluatePosition(face, next.x, next.y), p);
          if (d < distance) {
            uv = next;
            distance = d;
            closer = true;
          }
        }
        if (!closer) break;
      }
      if (distance < best.distance) best = {distance, face, uv};
    }
    return best;
  }

private:
  static constexpr int kGrid = 8;
  struct Sample {
    std::uint32_t face;
    glm::dvec2 uv;
    glm::dvec3 position;
  };
  const subdiv::LimitSurface& surface_;
  std::vector<Sample> samples_;
};

/// A unit-sphere quad cage drawn subdivided at scale 0.1 m, seen from 0.4 m; `extra` adds
/// top-level fields (grooms, animation).
struct SphereScene {
  testing::ScratchDir dir;
  std::filesystem::path file;

  explicit SphereScene(const std::string& extra, int segments = 16, int rings = 8) {
    dir.write("sphere.obj", quadSphereObj(segments, rings));
    file = dir.write("scene.json", R"({"name": "ball", "output": {"width": 640, "height": 480},
        "camera": {"position": [0, 0, 0.8], "target": [0, 0, 0], "near": 0.01, "far": 10},
        "simulation": {"settle_seconds": 0},
        "meshes": [{"name": "ball", "source": "sphere.obj", "transform": {"scale": 0.1},
                    "subdivision": {"isolation": 3}}])" +
                                       extra + "}");
  }

  Result<World> world() const {
    auto scene = loadScene(file);
    if (!scene) return std::unexpected(scene.error());
    return World::create(std::move(*scene), testing::sharedResolver(), {.loadTextures = false});
  }

  /// The limit surface of the scene's cage, built here (model units: the unit sphere's).
  subdiv::LimitSurface limit() const {
    auto scene = loadScene(file);
    EXPECT_TRUE(scene.has_value());
    auto loaded = loadSceneMesh(scene->meshes[0], testing::sharedResolver(), file.parent_path());
    EXPECT_TRUE(loaded.has_value() && loaded->cage.has_value());
    auto surface = subdiv::LimitSurface::create(*loaded->cage, {.maxIsolationLevel = 3});
    EXPECT_TRUE(surface.has_value());
    return std::move(*surface);
  }
};

/// The scene's camera (as the renderer gets it) moved to `distance` metres in front of the ball.
render::Camera cameraAt(const World& world, float distance) {
  render::Camera camera = world.frameInput().camera;
  camera.position = {0.0f, 0.0f, distance};
  return camera;
}

// --- Hair roots on the limit surface -------------------------------------------------------------

// Each root, taken back to model units (÷ the mesh's scale), must lie on the limit surface:
// its distance from the closest limit point is float rounding of a unit-sphere-sized position
// (the root is a float, evaluated in double), so at most 1e-6. Its strand grows along the limit
// normal there (the strand's first rest segment, normalised: within 1e-5 of it, float rounding
// of a 1 cm segment). And it lies in the groom's scalp region, tested per point: normal y ≥ 0.2
// and height in the top quarter of the surface (y ≥ top − 0.25·height, the limit's top being
// within 1 % of the cage's 1).
TEST(ScalpOnTheLimitSurface, ProceduralRootsLieOnTheLimitSurfaceAlongItsNormal) {
  const SphereScene scene(R"(, "grooms": [{"name": "hair", "source": "procedural", "attached_mesh": "ball",
                                          "strands": 300, "length": 0.05}])");
  auto world = scene.world();
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const subdiv::LimitSurface limit = scene.limit();
  const LimitProjector projector(limit);
  const physics::HairSystem& hair = world->simulatedGroom(0);
  ASSERT_EQ(hair.strandCount(), 300u);
  double worstDistance = 0.0, worstNormal = 0.0, lowest = 1.0;
  for (std::size_t s = 0; s < hair.strandCount(); ++s) {
    const glm::dvec3 root = glm::dvec3(hair.strands()[s].rootLocal) / 0.1;
    const LimitProjector::Hit hit = projector.project(root);
    worstDistance = std::max(worstDistance, hit.distance);
    const subdiv::LimitSample at = limit.evaluate(hit.face, hit.uv.x, hit.uv.y);
    worstNormal = std::max(worstNormal, 1.0 - double(glm::dot(hair.rootRestNormals()[s], at.normal)));
    EXPECT_GE(at.normal.y, 0.2f) << "strand " << s;
    lowest = std::min(lowest, root.y);
  }
  EXPECT_LT(worstDistance, 1e-6);
  EXPECT_LT(worstNormal, 1e-5);
  EXPECT_GT(lowest, 0.49) << "the top quarter of a sphere of radius ~1 starts at y ~ 0.5";
}

/// The area of `surface` above each of `heights` (sorted), from a 16 × 16 grid of limit points
/// on every ptex face cut into triangles, each counted at its centroid's height.
std::vector<double> areaAbove(const subdiv::LimitSurface& surface, const std::vector<double>& heights) {
  constexpr int n = 16;
  std::vector<std::pair<double, double>> pieces;  // (height, area)
  std::vector<glm::dvec3> grid((n + 1) * (n + 1));
  for (std::uint32_t f = 0; f < surface.ptexFaceCount(); ++f) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) grid[j * (n + 1) + i] = surface.evaluatePosition(f, double(i) / n, double(j) / n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 a = grid[j * (n + 1) + i], b = grid[j * (n + 1) + i + 1], c = grid[(j + 1) * (n + 1) + i + 1],
                         d = grid[(j + 1) * (n + 1) + i];
        pieces.emplace_back((a.y + b.y + c.y) / 3.0, 0.5 * glm::length(glm::cross(b - a, c - a)));
        pieces.emplace_back((a.y + c.y + d.y) / 3.0, 0.5 * glm::length(glm::cross(c - a, d - a)));
      }
  }
  std::vector<double> above;
  for (const double h : heights) {
    double sum = 0.0;
    for (const auto& [y, area] : pieces) sum += y > h ? area : 0.0;
    above.push_back(sum);
  }
  return above;
}

// Uniform by area: the share of roots above a height must be the share of the region's area
// above it. The area comes from a fine grid of limit points cut into triangles (not from the
// Jacobians the sampler weighs by). Kolmogorov-Smirnov on 4,000 roots at 9 heights: the
// largest difference must stay below 1.63/√n ≈ 0.026 (the 1 % critical value) plus 0.005 for
// the grid's area error. On a sphere this is Archimedes' hat-box theorem (heights uniform); the
// limit of a lat-long cage is close to one, its pole patches (valence 32, Gregory end caps)
// somewhat flatter.
TEST(ScalpOnTheLimitSurface, RootsAreSpreadUniformlyByArea) {
  const SphereScene scene("", 32, 16);
  const subdiv::LimitSurface limit = scene.limit();
  auto roots = sampleScalpOnLimitSurface(limit, ScalpRegion{}, 4000, 7);
  ASSERT_TRUE(roots.has_value()) << roots.error().message;
  ASSERT_EQ(roots->size(), 4000u);
  std::vector<double> rootHeights;
  for (const LimitRoot& root : *roots) {
    // What the root says about itself is the limit surface's own evaluation, bit for bit.
    const subdiv::LimitSample at = limit.evaluate(root.ptexFace, root.uv.x, root.uv.y);
    ASSERT_EQ(root.position, at.position);
    ASSERT_EQ(root.normal, at.normal);
    rootHeights.push_back(root.position.y);
  }
  const double south = limit.evaluatePosition(0, 0.0, 0.0).y;  // face 0's first corner: the south pole
  const double north = -south;                                 // a symmetric cage
  const double bottom = north - 0.25 * (north - south);
  std::vector<double> heights;
  for (int k = 0; k <= 9; ++k) heights.push_back(bottom + (north - bottom) * k / 10.0);
  const std::vector<double> area = areaAbove(limit, heights);
  double ks = 0.0;
  for (std::size_t k = 1; k < heights.size(); ++k) {
    const double share =
        double(std::count_if(rootHeights.begin(), rootHeights.end(), [&](double y) { return y > heights[k]; })) /
        double(rootHeights.size());
    ks = std::max(ks, std::abs(share - area[k] / area[0]));
    RecordProperty("share_above_" + std::to_string(k),
                   std::to_string(share) + " vs " + std::to_string(area[k] / area[0]));
  }
  EXPECT_LT(ks, 1.63 / std::sqrt(4000.0) + 0.005);
  // Reproducible: the same seed gives the same roots.
  auto again = sampleScalpOnLimitSurface(limit, ScalpRegion{}, 4000, 7);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ((*again)[1234].position, (*roots)[1234].position);
}

// A denser hairline: on the back half of a ball (normal z <= 0) with roots four times as dense
// at its edge, falling linearly to the common density 0.2 behind it (in the normal's z), the
// band z in [-0.2, 0] holds 2.5 x 0.2 / (2.5 x 0.2 + 0.8) = 5/13 of the roots, where it holds 0.2
// of the area (Archimedes: a sphere's area between parallel planes is in proportion to their
// distance). 4,000 roots: within 4 binomial standard deviations plus 0.01 for the cage's
// flattening.
TEST(ScalpOnTheLimitSurface, AHairlineGrowsItsRootsAsDenselyAsAsked) {
  const SphereScene scene("", 32, 16);
  const subdiv::LimitSurface limit = scene.limit();
  const auto bandShare = [&](float density) {
    const ScalpRegion region{.topFraction = 1.0f, .minUp = -1.0f, .maxForward = 0.0f, .hairlineDensity = density};
    auto roots = sampleScalpOnLimitSurface(limit, region, 4000, 11);
    EXPECT_TRUE(roots.has_value()) << roots.error().message;
    if (!roots) return 0.0;
    const auto inBand =
        std::count_if(roots->begin(), roots->end(), [](const LimitRoot& root) { return root.normal.z >= -0.2f; });
    return double(inBand) / double(roots->size());
  };
  const auto tolerance = [](double p) { return 4.0 * std::sqrt(p * (1.0 - p) / 4000.0) + 0.01; };
  EXPECT_NEAR(bandShare(1.0f), 0.2, tolerance(0.2));
  EXPECT_NEAR(bandShare(4.0f), 5.0 / 13.0, tolerance(5.0 / 13.0));
}

TEST(ScalpOnTheLimitSurface, ARegionNothingReachesIsAnError) {
  const SphereScene scene("");
  const subdiv::LimitSurface limit = scene.limit();
  auto roots =
      sampleScalpOnLimitSurface(limit, ScalpRegion{.topFraction = 0.25f, .minUp = 0.2f, .maxForward = -2.0f}, 10, 1);
  ASSERT_FALSE(roots.has_value());
  EXPECT_NE(roots.error().message.find("no point of the surface is in the scalp region"), std::string::npos)
      << roots.error().message;
}

// --- Tessellated again as the camera moves ---------------------------------------------------

// Closer, the same screen error needs more triangles; farther, fewer; every mesh is closed,
// and is the one a fresh tessellation of the same cage for the same view gives (the kept
// tessellator is reused, not stale). The same view again changes nothing.
TEST(RefineForCamera, MovingCloserAddsTrianglesAndFartherRemovesThemWatertightEachTime) {
  const SphereScene scene("");
  auto world = scene.world();
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const std::size_t atLoad = world->meshData(0).indices.size() / 3;
  EXPECT_EQ(unmatchedEdges(world->meshData(0)), 0u);

  auto loaded = loadSceneMesh(world->scene().meshes[0], testing::sharedResolver(), scene.file.parent_path());
  ASSERT_TRUE(loaded.has_value());
  const Subdivision subdivision = *world->scene().meshes[0].subdivision;
  std::size_t previous = atLoad;
  for (const float distance : {0.3f, 3.2f, 0.8f}) {
    const render::Camera camera = cameraAt(*world, distance);
    auto changed = world->refineForCamera(camera, {640, 480}, 2);
    ASSERT_TRUE(changed.has_value()) << changed.error().message;
    ASSERT_EQ(*changed, std::vector<std::size_t>{0}) << "at " << distance << " m";
    const render::MeshData mesh = world->meshData(0);
    const std::size_t triangles = mesh.indices.size() / 3;
    if (distance == 0.3f) {
      EXPECT_GT(triangles, 2 * previous) << "nearer, more pixels per metre: more triangles";
    } else if (distance == 3.2f) {
      EXPECT_LT(triangles * 2, previous) << "farther, fewer";
    } else {
      EXPECT_EQ(triangles, atLoad) << "back at the scene's camera";
    }
    EXPECT_EQ(unmatchedEdges(mesh), 0u) << "at " << distance << " m";
    EXPECT_EQ(mesh.curvatures.size(), 0u) << "no skin material: no curvature";
    auto fresh = tessellateForCamera(*loaded->cage, subdivision,
                                     camera.projection(640.0f / 480.0f) * camera.view() *
                                         animatedMatrix(world->scene(), world->scene().meshes[0], 0.0f),
                                     {640.0f, 480.0f});
    ASSERT_TRUE(fresh.has_value());
    EXPECT_EQ(fresh->mesh.indices, std::vector<std::uint32_t>(mesh.indices.begin(), mesh.indices.end()));
    EXPECT_EQ(fresh->mesh.positions, std::vector<glm::vec3>(mesh.positions.begin(), mesh.positions.end()));
    previous = triangles;
  }
  auto again = world->refineForCamera(cameraAt(*world, 0.8f), {640, 480}, 1);
  ASSERT_TRUE(again.has_value());
  EXPECT_TRUE(again->empty()) << "the same view: nothing to upload";
}

// The head turns (a scene animation): the same camera sees it from another side, so the mesh
// is tessellated again; the skin's curvature follows the new vertices.
// A turning head keeps its triangles (the error does not depend on which way the surface
// faces); a camera come nearer has them made again, with the limit surface's curvature.
TEST(RefineForCamera, ATurningHeadKeepsItsTrianglesUntilTheCameraComesNearer) {
  const SphereScene scene(R"(, "materials": [{"name": "skin", "kind": "skin"}],
      "animation": {"head": {"mesh": "ball", "motion": "turn", "amplitude_degrees": 20, "frequency_hz": 0.25}})");
  std::string text = testing::readFile(scene.file);
  text.replace(text.find(R"("transform")"), 0, R"("material": "skin", )");
  scene.dir.write("scene.json", text);
  auto world = scene.world();
  ASSERT_TRUE(world.has_value()) << world.error().message;
  ASSERT_TRUE(world->refineForCamera(cameraAt(*world, 0.8f), {640, 480}).has_value());
  const std::vector<std::uint32_t> before(world->meshData(0).indices.begin(), world->meshData(0).indices.end());
  ASSERT_TRUE(world->advance(0.5, 1).has_value());
  auto turned = world->refineForCamera(cameraAt(*world, 0.8f), {640, 480});
  ASSERT_TRUE(turned.has_value()) << turned.error().message;
  EXPECT_TRUE(turned->empty());
  auto nearer = world->refineForCamera(cameraAt(*world, 0.6f), {640, 480});
  ASSERT_TRUE(nearer.has_value()) << nearer.error().message;
  EXPECT_EQ(*nearer, std::vector<std::size_t>{0});
  const render::MeshData mesh = world->meshData(0);
  EXPECT_GT(mesh.indices.size(), before.size());
  ASSERT_EQ(mesh.curvatures.size(), mesh.positions.size());
  EXPECT_EQ(unmatchedEdges(mesh), 0u);
  // The limit of this coarse cage is a sphere within ~2 %: 1/r about 1 per unit.
  for (std::size_t v = 0; v < mesh.positions.size(); v += 97)
    if (std::abs(mesh.positions[v].y) < 0.7f) {
      EXPECT_NEAR(mesh.curvatures[v], 1.0f, 0.1f) << "vertex " << v;
    }
  EXPECT_EQ(world->staticScene().meshes[0].indices.size(), mesh.indices.size());
}

TEST(RefineForCamera, ThreadsDoNotChangeTheTriangles) {
  const SphereScene scene("");
  auto one = scene.world();
  auto four = scene.world();
  ASSERT_TRUE(one.has_value() && four.has_value());
  ASSERT_TRUE(one->refineForCamera(cameraAt(*one, 0.25f), {1280, 720}, 1).has_value());
  ASSERT_TRUE(four->refineForCamera(cameraAt(*four, 0.25f), {1280, 720}, 4).has_value());
  const render::MeshData a = one->meshData(0), b = four->meshData(0);
  EXPECT_TRUE(std::equal(a.indices.begin(), a.indices.end(), b.indices.begin(), b.indices.end()));
  EXPECT_TRUE(std::equal(a.positions.begin(), a.positions.end(), b.positions.begin(), b.positions.end()));
}

TEST(RefineForCamera, AnEmptyImageOrABrokenCameraIsAnError) {
  const SphereScene scene("");
  auto world = scene.world();
  ASSERT_TRUE(world.has_value()) << world.error().message;
  auto empty = world->refineForCamera(cameraAt(*world, 0.8f), {0, 480});
  ASSERT_FALSE(empty.has_value());
  EXPECT_NE(empty.error().message.find("at least 1x1 pixels"), std::string::npos) << empty.error().message;
  render::Camera broken = cameraAt(*world, 0.8f);
  broken.target = broken.position;  // no view direction
  auto failed = world->refineForCamera(broken, {640, 480});
  ASSERT_FALSE(failed.has_value());
  EXPECT_NE(failed.error().message.find("no projection"), std::string::npos) << failed.error().message;
}

}  // namespace
}  // namespace mane::scenes
