// Limit-surface evaluation from the adaptive patch table.
//
// Oracles: (1) the uniform bicubic B-spline (Catmull-Clark's limit on a regular grid),
// evaluated here from its basis functions; (2) OpenSubdiv's uniform refinement: level-L
// vertices converge to the limit as O(4^-L), and PrimvarRefiner::Limit gives the exact
// limit of each of them; (3) affine invariance of subdivision for a deforming cage.

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <opensubdiv/far/primvarRefiner.h>

#include "subdiv/cage_obj.hpp"
#include "subdiv/detail/osd_topology.hpp"
#include "subdiv/limit.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/subdiv/test_cages.hpp"

namespace mane::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;
using testing::heightGrid;
using testing::unitCube;

// Uniform cubic B-spline basis and its derivatives at t ∈ [0,1].
void bspline(double t, double b[4], double d[4], double dd[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s / 6.0;
  b[1] = (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
  b[2] = (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
  b[3] = t * t * t / 6.0;
  d[0] = -s * s / 2.0;
  d[1] = (3.0 * t * t - 4.0 * t) / 2.0;
  d[2] = (-3.0 * t * t + 2.0 * t + 1.0) / 2.0;
  d[3] = t * t / 2.0;
  dd[0] = s;
  dd[1] = 3.0 * t - 2.0;
  dd[2] = -3.0 * t + 1.0;
  dd[3] = t;
}

float bumpyHeight(int r, int c) {
  return 0.3f * std::sin(1.3f * float(r)) + 0.2f * std::cos(0.7f * float(c * r));
}

TEST(LimitSurface, RegularGridMatchesTheBicubicBSpline) {
  constexpr int kCells = 8;
  const Cage cage = heightGrid(kCells, bumpyHeight);
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  ASSERT_EQ(surface->ptexFaceCount(), std::uint32_t(kCells * kCells));
  double worst = 0.0;
  // Faces whose 4×4 control points are all interior, regular vertices.
  for (int r = 2; r <= kCells - 3; ++r)
    for (int c = 2; c <= kCells - 3; ++c)
      for (double u : {0.0, 0.13, 0.5, 0.77, 1.0})
        for (double v : {0.0, 0.31, 0.5, 0.9}) {
          double bu[4], du[4], ddu[4], bv[4], dv[4], ddv[4];
          bspline(u, bu, du, ddu);
          bspline(v, bv, dv, ddv);
          glm::dvec3 p(0.0), pu(0.0), pv(0.0), puu(0.0), puv(0.0), pvv(0.0);
          for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
              const glm::dvec3 control(cage.positions[std::size_t((r - 1 + j) * (kCells + 1) + (c - 1 + i))]);
              p += bu[i] * bv[j] * control;
              pu += du[i] * bv[j] * control;
              pv += bu[i] * dv[j] * control;
              puu += ddu[i] * bv[j] * control;
              puv += du[i] * dv[j] * control;
              pvv += bu[i] * ddv[j] * control;
            }
          const LimitSample sample = surface->evaluate(std::uint32_t(r * kCells + c), u, v);
          for (auto [got, expected] : {std::pair{sample.position, p},
                                       {sample.du, pu},
                                       {sample.dv, pv},
                                       {sample.duu, puu},
                                       {sample.duv, puv},
                                       {sample.dvv, pvv}})
            worst = std::max(worst, glm::length(glm::dvec3(got) - expected));
        }
  // Float output of double sums of O(1) values: a few float ulps.
  EXPECT_LT(worst, 2e-6);
}

/// Level-L vertices of OpenSubdiv's uniform refinement, each with the base face and ptex
/// (u, v) it sits at, for an all-quad cage.
struct UniformSamples {
  std::vector<glm::dvec3> refined;  ///< the level-L vertex
  std::vector<glm::dvec3> limit;    ///< PrimvarRefiner::Limit of it: the exact limit point
  std::vector<std::uint32_t> face;
  std::vector<glm::dvec2> uv;
};

struct Point3 {
  glm::dvec3 p{0.0};
  void Clear() { p = glm::dvec3(0.0); }
  void AddWithWeight(const Point3& source, double weight) { p += weight * source.p; }
};

UniformSamples uniformSamples(const Cage& cage, int level) {
  auto refiner = std::move(*detail::createTopologyRefiner(cage));
  Far::TopologyRefiner::UniformOptions options(level);
  options.fullTopologyInLastLevel = true;  // PrimvarRefiner::Limit needs the last level's edges
  refiner->RefineUniform(options);
  // Each face's base face and the ptex coordinates of its corners, level by level.
  struct FaceParams {
    std::uint32_t base;
    glm::dvec2 corner[4];
  };
  std::vector<FaceParams> faces;
  for (std::uint32_t f = 0; f < cage.faceSizes.size(); ++f) faces.push_back({f, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}});
  for (int l = 0; l < level; ++l) {
    const Far::TopologyLevel& parent = refiner->GetLevel(l);
    const Far::TopologyLevel& child = refiner->GetLevel(l + 1);
    std::vector<FaceParams> next(std::size_t(child.GetNumFaces()));
    for (int f = 0; f < parent.GetNumFaces(); ++f) {
      const auto verts = parent.GetFaceVertices(f);
      const auto edges = parent.GetFaceEdges(f);
      const FaceParams& params = faces[std::size_t(f)];
      const auto paramOf = [&](int childVertex) {
        if (childVertex == parent.GetFaceChildVertex(f))
          return (params.corner[0] + params.corner[1] + params.corner[2] + params.corner[3]) / 4.0;
        for (int i = 0; i < 4; ++i) {
          if (childVertex == parent.GetVertexChildVertex(verts[i])) return params.corner[i];
          if (childVertex == parent.GetEdgeChildVertex(edges[i]))
            return (params.corner[i] + params.corner[(i + 1) % 4]) / 2.0;
        }
        ADD_FAILURE() << "child vertex not found";
        return glm::dvec2(0.0);
      };
      for (int childFace : parent.GetFaceChildFaces(f)) {
        FaceParams& out = next[std::size_t(childFace)];
        out.base = params.base;
        const auto childVerts = child.GetFaceVertices(childFace);
        for (int i = 0; i < 4; ++i) out.corner[i] = paramOf(childVerts[i]);
      }
    }
    faces = std::move(next);
  }
  std::vector<Point3> points(std::size_t(refiner->GetNumVerticesTotal()));
  for (std::size_t v = 0; v < cage.positions.size(); ++v) points[v].p = glm::dvec3(cage.positions[v]);
  const Far::PrimvarRefinerReal<double> primvars(*refiner);
  Point3* source = points.data();
  for (int l = 1; l <= level; ++l) {
    Point3* destination = source + refiner->GetLevel(l - 1).GetNumVertices();
    primvars.Interpolate(l, source, destination);
    source = destination;
  }
  const Far::TopologyLevel& last = refiner->GetLevel(level);
  std::vector<Point3> limits(std::size_t(last.GetNumVertices()));
  primvars.Limit(source, limits);
  UniformSamples samples;
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto verts = last.GetFaceVertices(f);
    for (int i = 0; i < 4; ++i) {
      samples.refined.push_back(source[verts[i]].p);
      samples.limit.push_back(limits[std::size_t(verts[i])].p);
      samples.face.push_back(faces[std::size_t(f)].base);
      samples.uv.push_back(faces[std::size_t(f)].corner[i]);
    }
  }
  return samples;
}

struct Distances {
  double toRefined = 0.0;  ///< max |adaptive limit − level-L vertex|
  double toLimit = 0.0;    ///< max |adaptive limit − exact limit of that vertex|
};

Distances compareWithUniform(const Cage& cage, const LimitSurface& surface, int level) {
  const UniformSamples samples = uniformSamples(cage, level);
  Distances distances;
  for (std::size_t i = 0; i < samples.refined.size(); ++i) {
    const glm::dvec3 p = surface.evaluatePosition(samples.face[i], samples.uv[i].x, samples.uv[i].y);
    distances.toRefined = std::max(distances.toRefined, glm::length(p - samples.refined[i]));
    distances.toLimit = std::max(distances.toLimit, glm::length(p - samples.limit[i]));
  }
  return distances;
}

TEST(LimitSurface, AgreesWithUniformRefinementOfTheCube) {
  const Cage cage = unitCube();
  auto surface = LimitSurface::create(cage, {.maxIsolationLevel = 6});
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  double previous = 1e30;
  for (int level = 1; level <= 5; ++level) {
    const Distances d = compareWithUniform(cage, *surface, level);
    // Refined vertices approach the limit as O(4^-L) (measured: 0.199, 0.048, 0.012, 0.0029,
    // 0.00073): at least a factor 3.5 per level.
    EXPECT_LT(d.toRefined, previous / 3.5) << "level " << level;
    previous = d.toRefined;
    // Level-L vertices (L ≤ the isolation level) are corners of patches, where even the
    // Gregory end caps around the valence-3 corners interpolate the exact limit (measured
    // ~5e-16 for a cube of size 2).
    EXPECT_LT(d.toLimit, 1e-9) << "level " << level;
  }
  EXPECT_LT(previous, 1e-3);
}

TEST(LimitSurface, AgreesExactlyWithUniformLimitOnARegularTorus) {
  MANE_RESOLVE_OR_SKIP(file, "subdiv/opensubdiv/catmark_torus.obj");
  const Cage cage = [&] {
    auto loaded = loadCageObj(file);
    return loaded ? *loaded : Cage{};
  }();
  ASSERT_FALSE(cage.positions.empty());
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  double previous = 1e30;
  for (int level = 1; level <= 4; ++level) {
    const Distances d = compareWithUniform(cage, *surface, level);
    EXPECT_LT(d.toRefined, previous / 3.5) << "level " << level;  // measured 0.065 … 0.001
    previous = d.toRefined;
    // Every vertex is regular: the patches are the exact limit everywhere.
    EXPECT_LT(d.toLimit, 1e-9) << "level " << level;
  }
}

TEST(LimitSurface, UvsThatAreAffineInThePositionStayAffine) {
  // UV = (x, y) / 6 at every cage vertex of a flat grid, with a UV seam down the middle
  // (separate UV values for the two sides, equal numbers): both smooth interior rules and
  // the linear seam/boundary rules reproduce affine functions, so the limit UV must equal
  // the limit position's (x, y) / 6 everywhere.
  constexpr int kCells = 6;
  Cage cage = heightGrid(kCells, [](int, int) { return 0.0f; });
  for (const glm::vec3& p : cage.positions) cage.uvs.emplace_back(p.x / 6.0f, p.y / 6.0f);
  const auto leftCount = std::uint32_t(cage.uvs.size());
  for (const glm::vec3& p : cage.positions) cage.uvs.emplace_back(p.x / 6.0f, p.y / 6.0f);
  for (std::size_t k = 0; k < cage.faceVertices.size(); ++k) {
    const bool rightHalf = (k / 4) % kCells >= kCells / 2;
    cage.faceUvIndices.push_back(cage.faceVertices[k] + (rightHalf ? leftCount : 0u));
  }
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  ASSERT_TRUE(surface->hasUvs());
  double worst = 0.0;
  for (std::uint32_t face = 0; face < surface->ptexFaceCount(); ++face)
    for (double u : {0.0, 0.3, 0.5, 1.0})
      for (double v : {0.0, 0.6, 1.0}) {
        const LimitSample s = surface->evaluate(face, u, v);
        worst = std::max(worst, double(glm::length(s.uv - glm::vec2(s.position) / 6.0f)));
      }
  EXPECT_LT(worst, 1e-6);
}

TEST(LimitSurface, DeformingTheCageKeepsTopologyAndFollowsAffineMaps) {
  const Cage cage = unitCube();
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value());
  std::vector<LimitSample> before;
  for (std::uint32_t f = 0; f < surface->ptexFaceCount(); ++f) before.push_back(surface->evaluate(f, 0.3, 0.6));
  // Subdivision weights sum to 1, so an affine map of the cage maps the limit surface.
  const auto affine = [](glm::vec3 p) { return glm::vec3(2.0f * p.x + 1.0f, 0.5f * p.y - 3.0f, p.z + 0.25f * p.x); };
  std::vector<glm::vec3> moved;
  for (const glm::vec3& p : cage.positions) moved.push_back(affine(p));
  ASSERT_TRUE(surface->updatePositions(moved).has_value());
  for (std::uint32_t f = 0; f < surface->ptexFaceCount(); ++f) {
    const LimitSample after = surface->evaluate(f, 0.3, 0.6);
    EXPECT_LT(glm::length(after.position - affine(before[f].position)), 1e-5f);
  }
  // The same surface as one built from the moved cage.
  Cage movedCage = cage;
  movedCage.positions = moved;
  auto rebuilt = LimitSurface::create(movedCage);
  ASSERT_TRUE(rebuilt.has_value());
  for (std::uint32_t f = 0; f < surface->ptexFaceCount(); ++f)
    EXPECT_LT(glm::length(surface->evaluate(f, 0.7, 0.1).position - rebuilt->evaluate(f, 0.7, 0.1).position), 1e-6f);

  EXPECT_FALSE(surface->updatePositions(std::span(moved).first(3)).has_value());
  moved[2].y = std::nanf("");
  EXPECT_NE(surface->updatePositions(moved).error().message.find("vertex 2"), std::string::npos);
}

// A copy is a snapshot: it evaluates exactly as the original did when it was taken, keeps that
// shape while the original moves on, and numbers its revisions on from the original's; assigning
// a later state brings it up to date.
TEST(LimitSurface, ACopyKeepsTheShapeItWasTakenWith) {
  const Cage cage = unitCube();
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value());
  std::vector<glm::vec3> moved = cage.positions;
  moved[0] += glm::vec3(0.3f);
  ASSERT_TRUE(surface->updatePositions(moved).has_value());
  LimitSurface copy = *surface;
  std::vector<LimitSample> taken;
  for (std::uint32_t f = 0; f < surface->ptexFaceCount(); ++f) taken.push_back(surface->evaluate(f, 0.3, 0.6));

  ASSERT_TRUE(surface->updatePositions(cage.positions).has_value());
  EXPECT_EQ(copy.revision(), 1u);
  EXPECT_EQ(surface->revision(), 2u);
  bool originalMoved = false;
  for (std::uint32_t f = 0; f < copy.ptexFaceCount(); ++f) {
    const LimitSample sample = copy.evaluate(f, 0.3, 0.6);
    EXPECT_EQ(sample.position, taken[f].position) << "face " << f;
    EXPECT_EQ(sample.normal, taken[f].normal) << "face " << f;
    EXPECT_EQ(sample.curvature.mean, taken[f].curvature.mean) << "face " << f;
    originalMoved |= surface->evaluate(f, 0.3, 0.6).position != taken[f].position;
  }
  EXPECT_TRUE(originalMoved);

  copy = *surface;
  EXPECT_EQ(copy.revision(), 2u);
  for (std::uint32_t f = 0; f < copy.ptexFaceCount(); ++f) {
    EXPECT_EQ(copy.changedAt(f), surface->changedAt(f));
    EXPECT_EQ(copy.evaluate(f, 0.7, 0.1).position, surface->evaluate(f, 0.7, 0.1).position);
  }
}

TEST(LimitSurface, RejectsBadCagesAndSettingsWithTheReason) {
  Cage outOfRange = unitCube();
  outOfRange.faceVertices[3] = 99;
  EXPECT_NE(LimitSurface::create(outOfRange).error().message.find("vertex 99"), std::string::npos);
  Cage badUvs = unitCube();
  badUvs.uvs = {{0.0f, 0.0f}};
  badUvs.faceUvIndices.assign(badUvs.faceVertices.size(), 0u);
  badUvs.faceUvIndices[7] = 5;
  EXPECT_NE(LimitSurface::create(badUvs).error().message.find("texture coordinate 5"), std::string::npos);
  EXPECT_NE(LimitSurface::create(unitCube(), {.maxIsolationLevel = 0}).error().message.find("isolation level"),
            std::string::npos);
}

TEST(LimitSurface, NGonSubFacesMeetWhereTheHeaderSays) {
  // A pentagon fanned by five triangles around an apex, closed: sub-faces everywhere.
  Cage cage;
  for (int i = 0; i < 5; ++i) {
    const double angle = 2.0 * 3.14159265358979 * i / 5.0;
    cage.positions.emplace_back(std::cos(angle), std::sin(angle), 0.0f);
  }
  cage.positions.emplace_back(0.0f, 0.0f, 1.0f);
  cage.faceSizes = {5};
  cage.faceVertices = {4, 3, 2, 1, 0};  // the base, facing down
  for (std::uint32_t i = 0; i < 5; ++i) {
    cage.faceSizes.push_back(3);
    cage.faceVertices.insert(cage.faceVertices.end(), {i, (i + 1) % 5, 5});
  }
  auto surface = LimitSurface::create(cage);
  ASSERT_TRUE(surface.has_value()) << surface.error().message;
  EXPECT_EQ(surface->ptexFaceCount(), 5u + 5u * 3u);
  for (std::uint32_t face = 0; face < cage.faceSizes.size(); ++face) {
    const std::uint32_t first = surface->firstPtexFace(face);
    const std::uint32_t n = cage.faceSizes[face];
    const glm::dvec3 centre = surface->evaluatePosition(first, 1.0, 1.0);
    for (std::uint32_t j = 0; j < n; ++j) {
      EXPECT_EQ(surface->ptexFace(first + j).subFace, int(j));
      EXPECT_LT(glm::length(surface->evaluatePosition(first + j, 1.0, 1.0) - centre), 1e-6);
      // The midpoint of edge (j, j+1) is (1, 0) of sub-face j and (0, 1) of sub-face j+1.
      const glm::dvec3 a = surface->evaluatePosition(first + j, 1.0, 0.0);
      const glm::dvec3 b = surface->evaluatePosition(first + (j + 1) % n, 0.0, 1.0);
      EXPECT_LT(glm::length(a - b), 1e-6);
    }
  }
  // Ptex adjacency is symmetric: my neighbour across edge e lists me across its edge.
  for (std::uint32_t p = 0; p < surface->ptexFaceCount(); ++p) {
    const PtexAdjacency mine = surface->ptexAdjacency(p);
    for (int e = 0; e < 4; ++e) {
      ASSERT_GE(mine.faces[e], 0);
      const PtexAdjacency theirs = surface->ptexAdjacency(std::uint32_t(mine.faces[e]));
      EXPECT_EQ(theirs.faces[mine.edges[e]], int(p)) << "ptex " << p << " edge " << e;
    }
  }
}

// Derivatives are per unit of the ptex face's own (u, v), on quads and on the sub-faces of
// triangles and n-gons alike (OpenSubdiv scales a non-quad face's patches as if from the cage
// face: evaluate undoes it), so |∂u × ∂v| is the area a unit of parameter covers. Oracle:
// central differences of evaluatePosition with step h = 1e-4, exact to O(h²) ≈ 1e-8 relative
// for first derivatives, O(h²)/h² noise ≈ 1e-8/1e-8 for second ones: 1e-5 and 1e-2 relative.
// Every face of the cage of pentagon + 5 triangles above, and a cube's quads.
TEST(LimitSurface, DerivativesArePerUnitOfThePtexFacesOwnParameters) {
  Cage pyramid;
  for (int i = 0; i < 5; ++i) {
    const double angle = 2.0 * 3.14159265358979 * i / 5.0;
    pyramid.positions.emplace_back(std::cos(angle), std::sin(angle), 0.0f);
  }
  pyramid.positions.emplace_back(0.0f, 0.0f, 1.0f);
  pyramid.faceSizes = {5};
  pyramid.faceVertices = {4, 3, 2, 1, 0};
  for (std::uint32_t i = 0; i < 5; ++i) {
    pyramid.faceSizes.push_back(3);
    pyramid.faceVertices.insert(pyramid.faceVertices.end(), {i, (i + 1) % 5, 5});
  }
  for (const Cage& cage : {pyramid, unitCube()}) {
    auto surface = LimitSurface::create(cage, {.maxIsolationLevel = 3});
    ASSERT_TRUE(surface.has_value()) << surface.error().message;
    constexpr double h = 1e-4;
    for (std::uint32_t f = 0; f < surface->ptexFaceCount(); ++f)
      for (const glm::dvec2 uv : {glm::dvec2(0.3, 0.6), glm::dvec2(0.7, 0.2)}) {
        const LimitSample s = surface->evaluate(f, uv.x, uv.y);
        const auto at = [&](double du, double dv) { return surface->evaluatePosition(f, uv.x + du, uv.y + dv); };
        const glm::dvec3 du = (at(h, 0) - at(-h, 0)) / (2 * h), dv = (at(0, h) - at(0, -h)) / (2 * h);
        const glm::dvec3 duu = (at(h, 0) - 2.0 * at(0, 0) + at(-h, 0)) / (h * h);
        const double scale = glm::length(du);
        EXPECT_LT(glm::length(glm::dvec3(s.du) - du), 1e-5 * scale) << "ptex face " << f;
        EXPECT_LT(glm::length(glm::dvec3(s.dv) - dv), 1e-5 * scale) << "ptex face " << f;
        EXPECT_LT(glm::length(glm::dvec3(s.duu) - duu), 1e-2 * std::max(glm::length(duu), scale)) << "ptex face " << f;
      }
  }
}

}  // namespace
}  // namespace mane::subdiv
