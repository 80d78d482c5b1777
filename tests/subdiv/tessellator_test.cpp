// View-dependent tessellation of the limit surface.
//
// Oracles: (1) topology: on a closed cage every edge of a crack-free mesh without
// T-junctions has exactly two triangles, and a closed genus-0 surface has V − E + F = 2;
// (2) the screen-space error, measured independently here: for points sampled along every
// output edge, the pixel distance between the straight edge and the limit surface at the same
// ptex parameter (a point of the surface, so an upper bound of the distance to it).

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <set>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "subdiv/cage_obj.hpp"
#include "subdiv/tessellator.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/subdiv/test_cages.hpp"

namespace mane::subdiv {
namespace {

constexpr glm::vec2 kViewport{1280.0f, 720.0f};

/// A camera on the +z side of `centre` at `distance`, looking at it (40° vertical field).
ScreenView viewFrom(glm::vec3 centre, float distance) {
  const glm::mat4 projection = glm::perspective(glm::radians(40.0f), kViewport.x / kViewport.y, 0.01f, 100.0f);
  const glm::vec3 eye = centre + glm::normalize(glm::vec3(0.3f, 0.5f, 1.0f)) * distance;
  return {projection * glm::lookAt(eye, centre, glm::vec3(0, 1, 0)), kViewport};
}

struct EdgeCounts {
  std::size_t edges = 0, vertices = 0, notTwo = 0;
};

/// Undirected edges of the welded mesh (UV seams joined) and how many lack two triangles.
EdgeCounts countEdges(const TessellatedMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  std::set<std::uint32_t> used;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.weldedVertex[mesh.indices[t + k]];
      const std::uint32_t b = mesh.weldedVertex[mesh.indices[t + (k + 1) % 3]];
      ++uses[std::minmax(a, b)];
      used.insert(a);
    }
  EdgeCounts counts{uses.size(), used.size(), 0};
  for (const auto& [edge, count] : uses) counts.notTwo += count != 2 ? 1 : 0;
  return counts;
}

bool isClosed(const Cage& cage) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  std::uint32_t offset = 0;
  for (std::uint32_t size : cage.faceSizes) {
    for (std::uint32_t k = 0; k < size; ++k)
      ++uses[std::minmax(cage.faceVertices[offset + k], cage.faceVertices[offset + (k + 1) % size])];
    offset += size;
  }
  return std::all_of(uses.begin(), uses.end(), [](const auto& entry) { return entry.second == 2; });
}

glm::dvec2 toPixels(const ScreenView& view, const glm::dvec3& p) {
  const glm::dvec4 clip = glm::dmat4(view.viewProjection) * glm::dvec4(p, 1.0);
  return (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(view.viewportSize);
}

/// The largest pixel distance between output edges and the surface, 8 samples per edge.
double worstEdgeError(const LimitSurface& surface, const TessellatedMesh& mesh, const ScreenView& view) {
  double worst = 0.0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = 3 * t + std::size_t(k), b = 3 * t + std::size_t(k + 1) % 3;
      const glm::dvec3 pa(mesh.positions[mesh.indices[a]]), pb(mesh.positions[mesh.indices[b]]);
      const glm::dvec2 ua(mesh.cornerPtexCoordinates[a]), ub(mesh.cornerPtexCoordinates[b]);
      for (int s = 1; s < 8; ++s) {
        const double f = s / 8.0;
        const glm::dvec2 uv = glm::mix(ua, ub, f);
        const glm::dvec3 onSurface = surface.evaluatePosition(mesh.trianglePtexFaces[t], uv.x, uv.y);
        worst = std::max(worst, glm::length(toPixels(view, glm::mix(pa, pb, f)) - toPixels(view, onSurface)));
      }
    }
  return worst;
}

/// A surface and its tessellator, which points at the surface: the surface lives on the
/// heap so that the pair can move.
struct Tessellated {
  std::unique_ptr<LimitSurface> surfaceStorage;
  AdaptiveTessellator tessellator;
  LimitSurface& surface;
};

Tessellated prepare(const Cage& cage, TessellationSettings settings = {}) {
  auto surface = LimitSurface::create(cage);
  if (!surface) throw std::runtime_error(surface.error().message);
  auto stored = std::make_unique<LimitSurface>(std::move(*surface));
  auto tessellator = AdaptiveTessellator::create(*stored, settings);
  if (!tessellator) throw std::runtime_error(tessellator.error().message);
  LimitSurface& reference = *stored;
  return {std::move(stored), std::move(*tessellator), reference};
}

TEST(AdaptiveTessellation, ClosedCagesAreWatertightAtEveryDistance) {
  const Cage cages[] = {testing::unitCube(), testing::uvSphere(12, 6, 1.0f)};
  for (const Cage& cage : cages) {
    auto surface = LimitSurface::create(cage);
    ASSERT_TRUE(surface.has_value());
    auto tessellator = AdaptiveTessellator::create(*surface);
    ASSERT_TRUE(tessellator.has_value());
    std::size_t previousTriangles = 0;
    for (float distance : {40.0f, 8.0f, 2.5f}) {  // far, mid, near (the near view clips the surface)
      TessellatedMesh mesh;
      tessellator->tessellate(viewFrom(glm::vec3(0.0f), distance), mesh);
      const EdgeCounts counts = countEdges(mesh);
      EXPECT_EQ(counts.notTwo, 0u) << "distance " << distance;
      // Euler characteristic of a sphere: V − E + F = 2.
      EXPECT_EQ(std::int64_t(counts.vertices) - std::int64_t(counts.edges) + std::int64_t(mesh.triangleCount()), 2)
          << "distance " << distance;
      EXPECT_GT(mesh.triangleCount(), previousTriangles) << "nearer needs more triangles";
      previousTriangles = mesh.triangleCount();
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) ASSERT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-5f);
    }
  }
}

TEST(AdaptiveTessellation, EdgesStayWithinTheTargetOnScreen) {
  TessellationSettings settings;
  settings.keepPtexCoordinates = true;
  const Cage cages[] = {testing::unitCube(), testing::uvSphere(12, 6, 1.0f)};
  for (const Cage& cage : cages)
    for (float target : {1.0f, 4.0f}) {
      settings.maxPixelError = target;
      Tessellated t = prepare(cage, settings);
      for (float distance : {30.0f, 6.0f}) {  // the whole object in view
        const ScreenView view = viewFrom(glm::vec3(0.0f), distance);
        TessellatedMesh mesh;
        t.tessellator.tessellate(view, mesh);
        EXPECT_LE(worstEdgeError(t.surface, mesh, view), 1.1 * target)
            << "target " << target << " distance " << distance << ", " << mesh.triangleCount() << " triangles";
      }
    }
}

TEST(AdaptiveTessellation, IsDeterministicAndFollowsADeformingCage) {
  const Cage cage = testing::uvSphere(10, 6, 1.0f);
  Tessellated t = prepare(cage);
  const ScreenView view = viewFrom(glm::vec3(0.0f), 5.0f);
  TessellatedMesh first, second;
  t.tessellator.tessellate(view, first);
  t.tessellator.tessellate(view, second);
  EXPECT_EQ(first.indices, second.indices);
  EXPECT_EQ(first.positions, second.positions);

  // Stretch the cage along x: the next frame's vertices lie on the stretched surface.
  std::vector<glm::vec3> stretched = cage.positions;
  for (glm::vec3& p : stretched) p.x *= 1.5f;
  ASSERT_TRUE(t.surface.updatePositions(stretched).has_value());
  TessellatedMesh moved;
  t.tessellator.tessellate(view, moved);
  ASSERT_FALSE(moved.positions.empty());
  // Affine invariance: same topology of the surface, x scaled.
  float widthBefore = 0.0f, widthAfter = 0.0f;
  for (const glm::vec3& p : first.positions) widthBefore = std::max(widthBefore, std::abs(p.x));
  for (const glm::vec3& p : moved.positions) widthAfter = std::max(widthAfter, std::abs(p.x));
  EXPECT_NEAR(widthAfter / widthBefore, 1.5f, 0.02f);
  EXPECT_EQ(countEdges(moved).notTwo, 0u);
}

// A deforming cage seen from a still camera keeps its triangles: updateVertices moves each
// vertex to the new surface at its own ptex point, and moving the cage back restores the mesh.
TEST(AdaptiveTessellation, UpdatingVerticesKeepsTheTrianglesOnTheMovedSurface) {
  const Cage cage = testing::uvSphere(10, 6, 1.0f);
  Tessellated t = prepare(cage, {.keepPtexCoordinates = true});
  TessellatedMesh none;
  EXPECT_FALSE(t.tessellator.updateVertices(none).has_value()) << "nothing tessellated yet";
  const ScreenView view = viewFrom(glm::vec3(0.0f), 5.0f);
  TessellatedMesh rest;
  t.tessellator.tessellate(view, rest);
  TessellatedMesh mesh = rest;

  std::vector<glm::vec3> stretched = cage.positions;
  for (glm::vec3& p : stretched) p.x *= 1.5f;
  ASSERT_TRUE(t.surface.updatePositions(stretched).has_value());
  ASSERT_TRUE(t.tessellator.updateVertices(mesh).has_value());
  EXPECT_EQ(mesh.indices, rest.indices);
  float largest = 0.0f;
  for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
    const std::uint32_t v = mesh.indices[corner];
    const glm::vec2 uv = mesh.cornerPtexCoordinates[corner];
    const LimitSample sample = t.surface.evaluate(mesh.trianglePtexFaces[corner / 3], uv.x, uv.y);
    largest = std::max(largest, glm::length(mesh.positions[v] - sample.position));
    EXPECT_NEAR(glm::dot(mesh.normals[v], sample.normal), 1.0f, 1e-5f);
    EXPECT_EQ(mesh.meanCurvature[v], mesh.meanCurvature[mesh.weldedVertex[v]]);
  }
  EXPECT_LT(largest, 1e-6f);
  float widthBefore = 0.0f, widthAfter = 0.0f;
  for (const glm::vec3& p : rest.positions) widthBefore = std::max(widthBefore, std::abs(p.x));
  for (const glm::vec3& p : mesh.positions) widthAfter = std::max(widthAfter, std::abs(p.x));
  EXPECT_NEAR(widthAfter / widthBefore, 1.5f, 0.02f);

  ASSERT_TRUE(t.surface.updatePositions(cage.positions).has_value());
  ASSERT_TRUE(t.tessellator.updateVertices(mesh, 2).has_value());
  EXPECT_EQ(mesh.positions, rest.positions);
  EXPECT_EQ(mesh.normals, rest.normals);
  EXPECT_EQ(mesh.meanCurvature, rest.meanCurvature);
  EXPECT_EQ(mesh.uvs, rest.uvs);

  // A small deformation, as an animated head's from one frame to the next (the lower half of the
  // sphere turned by up to 3° about x, blended in over its height): the kept triangles stay
  // within the target on screen, as a fresh tessellation does.
  std::vector<glm::vec3> jaw = cage.positions;
  for (glm::vec3& p : jaw) {
    const float angle = glm::radians(3.0f) * std::clamp(-p.y, 0.0f, 1.0f);
    p = glm::vec3(p.x, p.y * std::cos(angle) - p.z * std::sin(angle), p.y * std::sin(angle) + p.z * std::cos(angle));
  }
  ASSERT_TRUE(t.surface.updatePositions(jaw).has_value());
  ASSERT_TRUE(t.tessellator.updateVertices(mesh).has_value());
  EXPECT_LE(worstEdgeError(t.surface, mesh, view), 1.1 * t.tessellator.settings().maxPixelError);
  ASSERT_TRUE(t.surface.updatePositions(cage.positions).has_value());
  ASSERT_TRUE(t.tessellator.updateVertices(mesh).has_value());

  TessellatedMesh other;  // not this tessellation's output
  other.positions.resize(3);
  const auto refused = t.tessellator.updateVertices(other);
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("3 vertices"), std::string::npos) << refused.error().message;
}

// A cage moved in one place re-evaluates only the vertices whose surface changed, and the mesh
// is what evaluating every vertex gives: the support LimitSurface::changedAt assumes (the faces
// sharing a vertex with a face) is wide enough. (Within float rounding: a vertex on a face
// boundary is evaluated through one of its faces, the check through each triangle's; a
// vertex left stale would be off by up to the move, 0.1–0.2 units.)
TEST(AdaptiveTessellation, UpdatingAfterALocalMoveEvaluatesOnlyWhatMoved) {
  const Cage cage = testing::uvSphere(12, 6, 1.0f);
  Tessellated t = prepare(cage, {.keepPtexCoordinates = true});
  TessellatedMesh mesh;
  t.tessellator.tessellate(viewFrom(glm::vec3(0.0f), 5.0f), mesh);
  const std::size_t all = t.tessellator.statistics().limitPoints;
  EXPECT_EQ(t.tessellator.statistics().pointsEvaluated, all);
  std::vector<glm::vec3> moved = cage.positions;
  for (std::size_t step = 1; step <= 2; ++step) {  // twice, so the second starts from a moved mesh
    moved[20] *= 1.0f + 0.1f * float(step);
    ASSERT_TRUE(t.surface.updatePositions(moved).has_value());
    ASSERT_TRUE(t.tessellator.updateVertices(mesh).has_value());
    EXPECT_GT(t.tessellator.statistics().pointsEvaluated, 0u);
    EXPECT_LT(t.tessellator.statistics().pointsEvaluated, all / 2) << "one vertex of 62 moved";
    for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
      const std::uint32_t v = mesh.indices[corner];
      const glm::vec2 uv = mesh.cornerPtexCoordinates[corner];
      const LimitSample sample = t.surface.evaluate(mesh.trianglePtexFaces[corner / 3], uv.x, uv.y);
      ASSERT_LT(glm::length(mesh.positions[v] - sample.position), 1e-6f) << "vertex " << v << ", step " << step;
      ASSERT_GT(glm::dot(mesh.normals[v], sample.normal), 1.0f - 1e-6f) << "vertex " << v << ", step " << step;
    }
  }
  // Two moves between updates: the points either one changed are evaluated.
  moved[3] += glm::vec3(0.1f);
  ASSERT_TRUE(t.surface.updatePositions(moved).has_value());
  ASSERT_TRUE(t.surface.updatePositions(moved).has_value());  // no vertex moved this time
  ASSERT_TRUE(t.tessellator.updateVertices(mesh).has_value());
  EXPECT_GT(t.tessellator.statistics().pointsEvaluated, 0u);
  for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
    const glm::vec2 uv = mesh.cornerPtexCoordinates[corner];
    const glm::vec3 onSurface = t.surface.evaluate(mesh.trianglePtexFaces[corner / 3], uv.x, uv.y).position;
    ASSERT_LT(glm::length(mesh.positions[mesh.indices[corner]] - onSurface), 1e-6f);
  }
}

/// The view of viewFrom with the object turned by `degrees` about the vertical line through
/// `pivot` (a head turning on its neck): the cage stays where it is, the view moves.
ScreenView turnedView(float degrees, glm::vec3 pivot, float distance) {
  const glm::mat4 turn = glm::translate(glm::mat4(1.0f), pivot) *
                         glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0)) *
                         glm::translate(glm::mat4(1.0f), -pivot);
  ScreenView view = viewFrom(glm::vec3(0.0f), distance);
  view.viewProjection = view.viewProjection * turn;
  return view;
}

// keepsTarget lets a turning object keep its triangles only while they stay within the target
// (+10 %, the oracle's bound) in the new view, measured independently along every edge.
TEST(AdaptiveTessellation, KeptTrianglesStayWithinTheTargetAsTheObjectTurns) {
  Tessellated t = prepare(testing::unitCube(), {.keepPtexCoordinates = true});
  const glm::vec3 neck(1.5f, -1.0f, 0.0f);  // beside the object: turning brings it nearer
  TessellatedMesh mesh;
  EXPECT_FALSE(t.tessellator.keepsTarget(turnedView(0.0f, neck, 6.0f))) << "nothing tessellated yet";
  t.tessellator.tessellate(turnedView(0.0f, neck, 6.0f), mesh);
  int kept = 0, tessellated = 1;
  for (float degrees = 2.0f; degrees <= 60.0f; degrees += 2.0f) {  // all of it in view
    const ScreenView view = turnedView(degrees, neck, 6.0f);
    if (!t.tessellator.keepsTarget(view)) {
      t.tessellator.tessellate(view, mesh);
      ++tessellated;
      continue;
    }
    ++kept;
    EXPECT_LE(worstEdgeError(t.surface, mesh, view), 1.1) << degrees << "°";
  }
  // The object swings about a unit nearer the camera: some views need new triangles.
  EXPECT_GE(kept, 10);
  EXPECT_GE(tessellated, 2);

  t.tessellator.tessellate(turnedView(0.0f, neck, 6.0f), mesh);
  EXPECT_TRUE(t.tessellator.keepsTarget(turnedView(0.0f, neck, 6.3f))) << "a little farther: finer than needed";
  EXPECT_FALSE(t.tessellator.keepsTarget(turnedView(0.0f, neck, 5.2f))) << "nearer: too coarse";
  EXPECT_FALSE(t.tessellator.keepsTarget(turnedView(0.0f, neck, 12.0f))) << "twice as far: far too fine";
  // What the refusals prevent: these triangles seen from a fifth nearer break the bound.
  EXPECT_FALSE(t.tessellator.keepsTarget(turnedView(0.0f, neck, 4.8f)));
  EXPECT_GT(worstEdgeError(t.surface, mesh, turnedView(0.0f, neck, 4.8f)), 1.1);
}

// update, per frame of an object that turns and deforms: the kept triangles until a tessellation
// prepared on another thread is adopted, 5 calls after it began, so no frame after the first
// tessellates on the calling thread. Oracles: every frame's mesh is watertight, lies on the
// surface as it is then, and keeps within the target (+10 %) on screen; an adopted mesh is
// bit for bit what tessellating the surface and view of the preparing frame and then moving
// the vertices (updateVertices) gives, on a surface of its own; and the meshes do not depend on
// the thread count.
TEST(AdaptiveTessellation, UpdateAdoptsATessellationPreparedBeforeTheKeptOneMissesTheTarget) {
  const Cage cage = testing::unitCube();
  const glm::vec3 neck(1.5f, -1.0f, 0.0f);  // beside the object: turning brings it nearer
  // Breathing in three steps, so that a tessellation adopted 5 frames after it was prepared
  // finds the cage moved since.
  const auto poseAt = [&](int frame) {
    std::vector<glm::vec3> pose = cage.positions;
    for (glm::vec3& p : pose) p *= 1.0f + 0.002f * float(frame % 3);
    return pose;
  };
  const auto viewAt = [&](int frame) { return turnedView(0.5f * float(frame), neck, 6.0f); };
  constexpr int kFrames = 120;  // 60° in half-degree steps

  std::vector<TessellatedMesh> firstRun;
  for (unsigned threads : {1u, 2u}) {
    Tessellated t = prepare(cage, {.keepPtexCoordinates = true});
    Tessellated reference = prepare(cage, {.keepPtexCoordinates = true});
    TessellatedMesh mesh, expected;
    std::map<FrameUpdate, int> counts;
    int preparedAt = -1;
    for (int frame = 0; frame <= kFrames; ++frame) {
      ASSERT_TRUE(t.surface.updatePositions(poseAt(frame)).has_value());
      const auto update = t.tessellator.update(viewAt(frame), mesh, threads);
      ASSERT_TRUE(update.has_value()) << update.error().message;
      ++counts[*update];
      if (frame == 0) {
        EXPECT_EQ(*update, FrameUpdate::kTessellated) << "nothing to keep yet";
      } else {
        ASSERT_NE(*update, FrameUpdate::kTessellated) << "frame " << frame;
      }
      if (*update == FrameUpdate::kPrepared) {
        ASSERT_TRUE(reference.surface.updatePositions(poseAt(frame)).has_value());
        reference.tessellator.tessellate(viewAt(frame), expected);
        preparedAt = frame;
      }
      if (*update == FrameUpdate::kAdopted) {
        EXPECT_EQ(frame, preparedAt + 5);
        ASSERT_TRUE(reference.surface.updatePositions(poseAt(frame)).has_value());
        ASSERT_TRUE(reference.tessellator.updateVertices(expected).has_value());
        EXPECT_EQ(mesh.indices, expected.indices) << "frame " << frame;
        EXPECT_EQ(mesh.positions, expected.positions) << "frame " << frame;
        EXPECT_EQ(mesh.normals, expected.normals) << "frame " << frame;
      }
      EXPECT_EQ(countEdges(mesh).notTwo, 0u) << "frame " << frame;
      EXPECT_LE(worstEdgeError(t.surface, mesh, viewAt(frame)), 1.1) << "frame " << frame;
      float offSurface = 0.0f;
      for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
        const glm::vec2 uv = mesh.cornerPtexCoordinates[corner];
        const glm::vec3 onSurface = t.surface.evaluatePosition(mesh.trianglePtexFaces[corner / 3], uv.x, uv.y);
        offSurface = std::max(offSurface, glm::length(mesh.positions[mesh.indices[corner]] - onSurface));
      }
      EXPECT_LT(offSurface, 1e-6f) << "frame " << frame;
      if (threads == 1) {
        firstRun.push_back(mesh);
      } else {
        EXPECT_EQ(mesh.indices, firstRun[std::size_t(frame)].indices) << "frame " << frame;
        EXPECT_EQ(mesh.positions, firstRun[std::size_t(frame)].positions) << "frame " << frame;
      }
    }
    EXPECT_GE(counts[FrameUpdate::kAdopted], 2);
    EXPECT_EQ(counts[FrameUpdate::kAdopted], counts[FrameUpdate::kPrepared]);
    EXPECT_GE(counts[FrameUpdate::kKept], kFrames / 2);

    // A camera that jumps back and a fifth nearer (the object still all in view): the kept
    // triangles would be too coarse, and nothing was prepared for it, so the call tessellates.
    const ScreenView jumped = turnedView(0.0f, neck, 4.8f);
    const auto update = t.tessellator.update(jumped, mesh, threads);
    ASSERT_TRUE(update.has_value());
    EXPECT_EQ(*update, FrameUpdate::kTessellated);
    EXPECT_LE(worstEdgeError(t.surface, mesh, jumped), 1.1);
  }
}

// Cells left coarse outside the view must be refined once they come into it.
TEST(AdaptiveTessellation, APartOutsideTheViewThatComesIntoItIsTessellatedAgain) {
  Tessellated t = prepare(testing::unitCube());
  const ScreenView centred = viewFrom(glm::vec3(0.0f), 3.0f);
  ScreenView panned = centred;  // the object half off the left of the image
  panned.viewProjection = glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f)) * centred.viewProjection;
  TessellatedMesh mesh;
  t.tessellator.tessellate(panned, mesh);
  ASSERT_TRUE(t.tessellator.keepsTarget(panned));
  EXPECT_FALSE(t.tessellator.keepsTarget(centred));
}

TEST(AdaptiveTessellation, UvSeamsSplitVerticesButNotTheSurface) {
  MANE_RESOLVE_OR_SKIP(file, "subdiv/opensubdiv/catmark_cube.obj");
  auto cage = loadCageObj(file);
  ASSERT_TRUE(cage.has_value()) << cage.error().message;
  Tessellated t = prepare(*cage);
  TessellatedMesh mesh;
  t.tessellator.tessellate(viewFrom(glm::vec3(0.0f), 6.0f), mesh);
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  std::size_t split = 0;
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    const std::uint32_t welded = mesh.weldedVertex[v];
    if (welded == v) continue;
    ++split;
    EXPECT_EQ(mesh.positions[v], mesh.positions[welded]);
  }
  EXPECT_GT(split, 0u) << "the cube's unfolded UVs have seams";
  EXPECT_EQ(countEdges(mesh).notTwo, 0u);

  // The cage doubled in size: every vertex moves to exactly twice its place (scaling by a power
  // of two is exact in floating point, and the surface is an affine combination of the cage),
  // seams stay split with equal positions on both sides, and the UVs do not move.
  std::vector<glm::vec3> doubled = cage->positions;
  for (glm::vec3& p : doubled) p *= 2.0f;
  ASSERT_TRUE(t.surface.updatePositions(doubled).has_value());
  const TessellatedMesh before = mesh;
  ASSERT_TRUE(t.tessellator.updateVertices(mesh).has_value());
  EXPECT_EQ(mesh.uvs, before.uvs);
  EXPECT_EQ(mesh.weldedVertex, before.weldedVertex);
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    ASSERT_EQ(mesh.positions[v], 2.0f * before.positions[v]) << "vertex " << v;
    EXPECT_EQ(mesh.positions[v], mesh.positions[mesh.weldedVertex[v]]);
  }
}

TEST(AdaptiveTessellation, RejectsBadSettings) {
  auto surface = LimitSurface::create(testing::unitCube());
  ASSERT_TRUE(surface.has_value());
  EXPECT_FALSE(AdaptiveTessellator::create(*surface, {.maxPixelError = 0.0f}).has_value());
  EXPECT_FALSE(AdaptiveTessellator::create(*surface, {.maxPixelError = NAN}).has_value());
  EXPECT_FALSE(AdaptiveTessellator::create(*surface, {.maxDepth = 11}).has_value());
}

TEST(AdaptiveTessellation, EveryCatmarkRegressionShapeBuildsAndTessellates) {
  for (const char* name : {"catmark_bishop.obj", "catmark_cube.obj", "catmark_pawn.obj", "catmark_pyramid.obj",
                           "catmark_rook.obj", "catmark_tent.obj", "catmark_torus.obj", "catmark_torus_creases0.obj"}) {
    MANE_RESOLVE_OR_SKIP(file, std::string("subdiv/opensubdiv/") + name);
    auto cage = loadCageObj(file);
    ASSERT_TRUE(cage.has_value()) << cage.error().message;
    auto surface = LimitSurface::create(*cage);
    ASSERT_TRUE(surface.has_value()) << name << ": " << surface.error().message;
    auto tessellator = AdaptiveTessellator::create(*surface);
    ASSERT_TRUE(tessellator.has_value());
    glm::vec3 low(1e30f), high(-1e30f);
    for (const glm::vec3& p : cage->positions) {
      low = glm::min(low, p);
      high = glm::max(high, p);
    }
    const float size = glm::length(high - low);
    for (float distance : {4.0f * size, 1.2f * size}) {
      TessellatedMesh mesh;
      tessellator->tessellate(viewFrom(0.5f * (low + high), distance), mesh);
      ASSERT_GT(mesh.triangleCount(), 0u) << name;
      for (const glm::vec3& p : mesh.positions)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
      for (const glm::vec2& uv : mesh.uvs) ASSERT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y));
      if (isClosed(*cage)) {
        EXPECT_EQ(countEdges(mesh).notTwo, 0u) << name << " at distance " << distance;
      }
    }
  }
}

}  // namespace
}  // namespace mane::subdiv
