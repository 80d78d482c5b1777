// Per-vertex curvature against analytic surfaces (sphere, cylinder, plane, paraboloid,
// saddle), its scale law, its handling of broken input, and the skin shader's 1/r on the
// real LeePerrySmith head, whose distribution is printed to choose the LUT's 1/r range.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <random>
#include <utility>

#include <glm/geometric.hpp>

#include "scenes/gltf_loader.hpp"
#include "scenes/mesh_curvature.hpp"
#include "scenes/scene.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

/// An icosahedron whose faces are split into 4 `level` times, every vertex pushed onto the
/// sphere of `radius`; outward normals and winding.
Mesh makeIcosphere(int level, float radius) {
  const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> p = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::uint32_t> tri = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                    4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                                    6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (glm::vec3& v : p) v = glm::normalize(v);
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    const auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, static_cast<std::uint32_t>(p.size()));
      if (inserted) p.push_back(glm::normalize(p[a] + p[b]));
      return it->second;
    };
    std::vector<std::uint32_t> finer;
    for (std::size_t t = 0; t < tri.size(); t += 3) {
      const std::uint32_t a = tri[t], b = tri[t + 1], c = tri[t + 2];
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    tri = std::move(finer);
  }
  Mesh mesh;
  mesh.name = "icosphere";
  for (const glm::vec3& v : p) {
    mesh.positions.push_back(v * radius);
    mesh.normals.push_back(v);
  }
  mesh.indices = std::move(tri);
  return mesh;
}

/// An open tube of radius R around +Y: `segments` around, `rings` + 1 rows, each row turned
/// half a segment from the last so the triangles are nearly equilateral.
Mesh makeTube(int rings, int segments, float radius) {
  Mesh mesh;
  mesh.name = "tube";
  const float step = 2.0f * kPi / static_cast<float>(segments);
  const float height = radius * step * std::sqrt(3.0f) / 2.0f;
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const float angle = (static_cast<float>(s) + 0.5f * static_cast<float>(r % 2)) * step;
      const glm::vec3 n(std::cos(angle), 0.0f, std::sin(angle));
      mesh.positions.push_back(n * radius + glm::vec3(0.0f, static_cast<float>(r) * height, 0.0f));
      mesh.normals.push_back(n);
    }
  }
  const auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * segments + (s + segments) % segments); };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      if (r % 2 == 0) {  // row r + 1 is half a segment ahead: (r+1, s) sits above the middle of (r, s)-(r, s+1)
        mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r + 1, s), at(r, s + 1)});
        mesh.indices.insert(mesh.indices.end(), {at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)});
      } else {  // row r is the one ahead: (r, s) sits below the middle of (r+1, s)-(r+1, s+1)
        mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r + 1, s + 1), at(r, s + 1)});
        mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      }
    }
  }
  return mesh;
}

/// The graph z = (a·x² + b·y²) / 2 over a (2m + 1)² grid of spacing h centred on the origin
/// (vertex `centreVertex`), each cell cut along alternating diagonals; normals +Z-ish.
Mesh makeQuadricPatch(int m, float h, float a, float b) {
  Mesh mesh;
  const int side = 2 * m + 1;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const float x = static_cast<float>(i - m) * h;
      const float y = static_cast<float>(j - m) * h;
      mesh.positions.emplace_back(x, y, 0.5f * (a * x * x + b * y * y));
      mesh.normals.push_back(glm::normalize(glm::vec3(-a * x, -b * y, 1.0f)));
    }
  }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * side + i); };
  for (int j = 0; j + 1 < side; ++j) {
    for (int i = 0; i + 1 < side; ++i) {
      if ((i + j) % 2 == 0) {
        mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
        mesh.indices.insert(mesh.indices.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  return mesh;
}

std::uint32_t centreVertex(int m) {
  return static_cast<std::uint32_t>(m * (2 * m + 1) + m);
}

VertexCurvature curvatureOf(const Mesh& mesh, const CurvatureSettings& settings = {}) {
  auto result = computeVertexCurvature(mesh, settings);
  EXPECT_TRUE(result.has_value()) << result.error().message;
  return result ? std::move(*result) : VertexCurvature{};
}

struct Worst {
  float h = 0.0f;  // largest relative error of H
  float k = 0.0f;  // largest relative error of K
};

Worst worstSphereError(int level, float radius) {
  const VertexCurvature c = curvatureOf(makeIcosphere(level, radius));
  Worst worst;
  for (std::size_t i = 0; i < c.vertexCount(); ++i) {
    EXPECT_EQ(c.flags[i], 0) << "vertex " << i;
    worst.h = std::max(worst.h, std::abs(c.meanCurvature[i] * radius - 1.0f));
    worst.k = std::max(worst.k, std::abs(c.gaussianCurvature[i] * radius * radius - 1.0f));
  }
  return worst;
}

// Meyer's operators on an icosphere of radius R. K = angle deficit / A_mixed converges as
// O(h²) (about 4× per level, 8 % at level 1 to 0.07 % at level 5) and is within 2 % of 1/R²
// at every vertex (valence 5 and 6) from level 3 (642 vertices) on. H from the cotangent
// Laplacian is within 1e-3 of 1/R at every level; its residual (≈ 1e-4 at level 5) is the
// float rounding of the positions, which grows as the edges shrink, so it is bounded rather
// than required to fall.
TEST(MeshCurvature, IcosphereConvergesToTheSphereCurvature) {
  const float radius = 0.37f;
  float previousK = 1e9f;
  for (int level = 1; level <= 5; ++level) {
    const Worst worst = worstSphereError(level, radius);
    std::printf("icosphere level %d: worst |H·R − 1| = %.5f, worst |K·R² − 1| = %.5f\n", level, worst.h, worst.k);
    EXPECT_LT(worst.h, 1e-3f) << "level " << level;
    EXPECT_LT(worst.k, 0.6f * previousK) << "level " << level;
    if (level >= 3) {
      EXPECT_LT(worst.k, 0.02f) << "level " << level;
    }
    previousK = worst.k;
  }
}

TEST(MeshCurvature, SphereHasEqualPrincipalCurvaturesAndSignFollowsTheNormal) {
  Mesh sphere = makeIcosphere(4, 2.0f);
  const VertexCurvature outward = curvatureOf(sphere);
  for (glm::vec3& n : sphere.normals) n = -n;
  const VertexCurvature inward = curvatureOf(sphere);
  for (std::size_t i = 0; i < outward.vertexCount(); ++i) {
    // κ1,2 = H ± sqrt(max(H² − K, 0)): on a sphere H² ≈ K, so both within 2 % of 1/R.
    EXPECT_NEAR(outward.maxCurvature[i], 0.5f, 0.01f);
    EXPECT_NEAR(outward.minCurvature[i], 0.5f, 0.01f);
    EXPECT_FLOAT_EQ(inward.meanCurvature[i], -outward.meanCurvature[i]);
    EXPECT_FLOAT_EQ(inward.gaussianCurvature[i], outward.gaussianCurvature[i]);
  }
  // Without normals the sign comes from the triangles' winding (outward here).
  sphere.normals.clear();
  const VertexCurvature unnormalled = curvatureOf(sphere);
  for (std::size_t i = 0; i < outward.vertexCount(); ++i) {
    EXPECT_FLOAT_EQ(unnormalled.meanCurvature[i], outward.meanCurvature[i]);
  }
}

// A cylinder of radius R: H = 1/(2R), K = 0, κ1 = 1/R, κ2 = 0 at interior vertices. 64
// segments: the inscribed polygon's chords are within 0.1 % of the circle.
TEST(MeshCurvature, TubeInteriorHasHalfTheInverseRadiusAndNoGaussianCurvature) {
  const float radius = 0.5f;
  const int segments = 64;
  const VertexCurvature c = curvatureOf(makeTube(10, segments, radius));
  for (std::size_t i = 0; i < c.vertexCount(); ++i) {
    const std::size_t row = i / segments;
    if (row == 0 || row == 10) {  // the open ends
      EXPECT_EQ(c.flags[i], kCurvatureBoundary) << "vertex " << i;
      EXPECT_EQ(c.meanCurvature[i], 0.0f);
      continue;
    }
    ASSERT_EQ(c.flags[i], 0) << "vertex " << i;
    EXPECT_NEAR(c.meanCurvature[i] * 2.0f * radius, 1.0f, 0.01f) << "vertex " << i;
    EXPECT_NEAR(c.gaussianCurvature[i] * radius * radius, 0.0f, 1e-3f) << "vertex " << i;
    EXPECT_NEAR(c.maxCurvature[i] * radius, 1.0f, 0.02f) << "vertex " << i;
    EXPECT_NEAR(c.minCurvature[i] * radius, 0.0f, 0.02f) << "vertex " << i;
  }
}

// A tilted plane with jittered interior vertices: the cotangent Laplacian of a linear
// function vanishes and the angles around a vertex sum to 2π, whatever the triangles.
TEST(MeshCurvature, IrregularPlaneIsFlat) {
  Mesh plane = makeQuadricPatch(10, 0.1f, 0.0f, 0.0f);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> jitter(-0.03f, 0.03f);
  const glm::vec3 u = glm::normalize(glm::vec3(1.0f, 0.2f, 0.3f));
  const glm::vec3 v = glm::normalize(glm::cross(glm::vec3(0.1f, 0.4f, 1.0f), u));
  for (glm::vec3& p : plane.positions) {
    const bool edge = std::abs(p.x) > 0.99f || std::abs(p.y) > 0.99f;
    const float x = p.x + (edge ? 0.0f : jitter(random));
    const float y = p.y + (edge ? 0.0f : jitter(random));
    p = glm::vec3(3.0f, -1.0f, 2.0f) + x * u + y * v;
  }
  plane.normals.assign(plane.positions.size(), glm::cross(u, v));
  const VertexCurvature c = curvatureOf(plane);
  int interior = 0;
  for (std::size_t i = 0; i < c.vertexCount(); ++i) {
    if (c.flags[i] != 0) continue;
    ++interior;
    // Float positions near 3 units from the origin: rounding of ~3e-7 over 0.1-unit edges.
    EXPECT_NEAR(c.meanCurvature[i], 0.0f, 1e-3f) << "vertex " << i;
    EXPECT_NEAR(c.gaussianCurvature[i], 0.0f, 1e-3f) << "vertex " << i;
  }
  EXPECT_EQ(interior, 19 * 19);
}

// z = (a x² + b y²)/2 at the origin: κ = a, b along the axes. The surface bends towards the
// +Z normal, so the signed values are negative: H = −(a + b)/2, K = a·b.
TEST(MeshCurvature, QuadricPatchesGiveTheirPrincipalCurvatures) {
  const int m = 8;
  struct Case {
    float a, b;
  };
  for (const Case q : {Case{2.0f, 0.5f}, Case{1.0f, -1.0f}}) {
    SCOPED_TRACE(::testing::Message() << "a = " << q.a << ", b = " << q.b);
    const VertexCurvature c = curvatureOf(makeQuadricPatch(m, 0.01f, q.a, q.b));
    const std::uint32_t o = centreVertex(m);
    ASSERT_EQ(c.flags[o], 0);
    // Spacing 0.01 ≪ 1/κ: second-order errors of order (κh)² are far below the 1e-2 allowed.
    EXPECT_NEAR(c.meanCurvature[o], -(q.a + q.b) / 2.0f, 1e-2f);
    EXPECT_NEAR(c.gaussianCurvature[o], q.a * q.b, 1e-2f);
    EXPECT_NEAR(c.maxCurvature[o], std::max(-q.a, -q.b), 2e-2f);
    EXPECT_NEAR(c.minCurvature[o], std::min(-q.a, -q.b), 2e-2f);
  }
}

// Curvature is 1/length: scaling the mesh by s scales H and κ by 1/s and K by 1/s².
TEST(MeshCurvature, ScalingTheMeshScalesCurvatureInversely) {
  const Mesh base = makeQuadricPatch(6, 0.05f, 1.5f, -0.7f);
  const VertexCurvature c = curvatureOf(base);
  for (const float s : {0.01f, 7.3f}) {
    Mesh scaled = base;
    for (glm::vec3& p : scaled.positions) p *= s;
    const VertexCurvature cs = curvatureOf(scaled);
    for (std::size_t i = 0; i < c.vertexCount(); ++i) {
      ASSERT_EQ(cs.flags[i], c.flags[i]);
      // Float rounding of the scaled positions only: relative 1e-4.
      EXPECT_NEAR(cs.meanCurvature[i] * s, c.meanCurvature[i], 1e-4f * (1.0f + std::abs(c.meanCurvature[i])));
      EXPECT_NEAR(cs.gaussianCurvature[i] * s * s, c.gaussianCurvature[i],
                  1e-4f * (1.0f + std::abs(c.gaussianCurvature[i])));
      EXPECT_NEAR(cs.maxCurvature[i] * s, c.maxCurvature[i], 1e-3f * (1.0f + std::abs(c.maxCurvature[i])));
    }
  }
}

// glTF splits vertices along UV seams: a sphere cut in half (every vertex of the upper
// half's triangles duplicated) must read exactly as the uncut one, without boundaries, also
// when the copies differ by a rounding-sized offset.
TEST(MeshCurvature, SeamCopiesAreWeldedIntoOneSurfacePoint) {
  const Mesh whole = makeIcosphere(3, 1.0f);
  const VertexCurvature reference = curvatureOf(whole);
  for (const float offset : {0.0f, 1e-6f}) {
    SCOPED_TRACE(offset);
    Mesh cut = whole;
    std::map<std::uint32_t, std::uint32_t> copyOf;
    for (std::size_t t = 0; t < cut.indices.size(); t += 3) {
      const glm::vec3 centroid =
          cut.positions[cut.indices[t]] + cut.positions[cut.indices[t + 1]] + cut.positions[cut.indices[t + 2]];
      if (centroid.z <= 0.0f) continue;
      for (std::size_t k = t; k < t + 3; ++k) {
        auto [it, inserted] = copyOf.try_emplace(cut.indices[k], static_cast<std::uint32_t>(cut.positions.size()));
        if (inserted) {
          cut.positions.push_back(whole.positions[cut.indices[k]] + glm::vec3(offset));
          cut.normals.push_back(whole.normals[cut.indices[k]]);
        }
        cut.indices[k] = it->second;
      }
    }
    const VertexCurvature c = curvatureOf(cut);
    for (auto [original, copy] : copyOf) {
      EXPECT_EQ(c.weldedVertex[copy], original);
      EXPECT_EQ(c.flags[copy], 0);
      EXPECT_NEAR(c.meanCurvature[copy], reference.meanCurvature[original], 1e-4f);
      EXPECT_NEAR(c.gaussianCurvature[copy], reference.gaussianCurvature[original], 1e-3f);
    }
    // With welding off, the cut is a boundary.
    const VertexCurvature unwelded = curvatureOf(cut, CurvatureSettings{.relativeWeldTolerance = 0.0f});
    if (offset > 0.0f) {
      EXPECT_EQ(unwelded.flags[copyOf.begin()->second] & kCurvatureBoundary, kCurvatureBoundary);
    }
  }
}

TEST(MeshCurvature, BrokenIndicesAndPositionsAreErrorsThatNameThePlace) {
  Mesh mesh = makeIcosphere(1, 1.0f);
  Mesh outOfRange = mesh;
  outOfRange.indices[3 * 5 + 1] = 999;
  auto result = computeVertexCurvature(outOfRange);
  ASSERT_FALSE(result.has_value());
  EXPECT_NE(result.error().message.find("triangle 5 uses vertex 999"), std::string::npos) << result.error().message;

  Mesh nan = mesh;
  nan.positions[7].y = std::nanf("");
  result = computeVertexCurvature(nan);
  ASSERT_FALSE(result.has_value());
  EXPECT_NE(result.error().message.find("vertex 7"), std::string::npos) << result.error().message;
  EXPECT_NE(result.error().message.find("non-finite"), std::string::npos) << result.error().message;

  Mesh ragged = mesh;
  ragged.indices.pop_back();
  EXPECT_FALSE(computeVertexCurvature(ragged).has_value());
  Mesh fewNormals = mesh;
  fewNormals.normals.pop_back();
  EXPECT_FALSE(computeVertexCurvature(fewNormals).has_value());

  // A NaN vertex no triangle uses is harmless.
  Mesh spare = mesh;
  spare.positions.emplace_back(std::nanf(""), 0.0f, 0.0f);
  spare.normals.emplace_back(0.0f, 1.0f, 0.0f);
  result = computeVertexCurvature(spare);
  ASSERT_TRUE(result.has_value()) << result.error().message;
  EXPECT_EQ(result->flags.back(), kCurvatureUnused);
}

// Zero-area triangles are skipped and their vertices flagged; the rest of the sphere is
// untouched, nothing is NaN, and the skin 1/r fills the flagged vertices from their rings.
TEST(MeshCurvature, ZeroAreaTrianglesAreSkippedAndFlagged) {
  const float radius = 1.0f;
  Mesh mesh = makeIcosphere(4, radius);
  const VertexCurvature reference = curvatureOf(mesh);
  mesh.indices.insert(mesh.indices.end(), {0, 0, 1});  // doubled corner
  const std::uint32_t onEdge = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back(0.5f * (mesh.positions[2] + mesh.positions[3]));  // collinear corner
  mesh.normals.push_back(mesh.normals[2]);
  mesh.indices.insert(mesh.indices.end(), {2, onEdge, 3});
  const VertexCurvature c = curvatureOf(mesh);
  EXPECT_EQ(c.skippedTriangles, 2u);
  for (std::uint32_t v : {0u, 1u, 2u, 3u, onEdge}) EXPECT_EQ(c.flags[v], kCurvatureDegenerate) << "vertex " << v;
  for (std::size_t i = 4; i < reference.vertexCount(); ++i) {
    EXPECT_EQ(c.meanCurvature[i], reference.meanCurvature[i]);
  }
  auto inverseRadius = skinInverseRadius(mesh, c, {.smoothingPasses = 0});
  ASSERT_TRUE(inverseRadius.has_value()) << inverseRadius.error().message;
  for (std::uint32_t v : {0u, 1u, 2u, 3u}) EXPECT_NEAR((*inverseRadius)[v] * radius, 1.0f, 0.02f);
}

// A fin on one edge of a sphere (three triangles on one edge), and a second sphere touching
// the first at one vertex (two fans): both are flagged non-manifold, the rest is unaffected.
TEST(MeshCurvature, NonManifoldEdgesAndVerticesAreFlagged) {
  Mesh mesh = makeIcosphere(3, 1.0f);
  const std::size_t n = mesh.positions.size();
  const std::uint32_t a = mesh.indices[0], b = mesh.indices[1];
  mesh.positions.push_back(3.0f * mesh.positions[a]);
  mesh.normals.push_back(mesh.normals[a]);
  mesh.indices.insert(mesh.indices.end(), {a, b, static_cast<std::uint32_t>(n)});
  VertexCurvature c = curvatureOf(mesh);
  EXPECT_NE(c.flags[a] & kCurvatureNonManifold, 0);
  EXPECT_NE(c.flags[b] & kCurvatureNonManifold, 0);
  EXPECT_EQ(c.meanCurvature[a], 0.0f);

  Mesh pair = makeIcosphere(2, 1.0f);
  const Mesh second = pair;
  const auto offset = static_cast<std::uint32_t>(pair.positions.size());
  // Sphere 2 sits at twice sphere 1's vertex 0, so its vertex 3 (the antipode of its vertex
  // 0) lands on sphere 1's vertex 0; set exactly.
  const glm::vec3 shift = 2.0f * second.positions[0];
  for (std::size_t i = 0; i < second.positions.size(); ++i) {
    pair.positions.push_back(i == 3 ? pair.positions[0] : second.positions[i] + shift);
    pair.normals.push_back(second.normals[i]);
  }
  for (std::uint32_t v : second.indices) pair.indices.push_back(v + offset);
  c = curvatureOf(pair);
  EXPECT_EQ(c.weldedVertex[offset + 3], 0u);
  EXPECT_EQ(c.flags[0], kCurvatureNonManifold);
  EXPECT_EQ(c.flags[1], 0);
  EXPECT_NEAR(c.meanCurvature[1], 1.0f, 0.05f);
}

// The skin's 1/r: |H| or max(|κ1|, |κ2|), boundary vertices filled from their rings.
TEST(SkinInverseRadius, MeasuresOnSphereAndTube) {
  const float radius = 0.5f;
  const Mesh sphere = makeIcosphere(4, radius);
  const VertexCurvature cs = curvatureOf(sphere);
  const Mesh tube = makeTube(10, 64, radius);
  const VertexCurvature ct = curvatureOf(tube);
  for (const auto measure : {SkinCurvatureMeasure::meanAbsolute, SkinCurvatureMeasure::maxPrincipalAbsolute}) {
    const bool mean = measure == SkinCurvatureMeasure::meanAbsolute;
    auto onSphere = skinInverseRadius(sphere, cs, {.measure = measure});
    auto onTube = skinInverseRadius(tube, ct, {.measure = measure});
    ASSERT_TRUE(onSphere.has_value() && onTube.has_value());
    for (float r : *onSphere) EXPECT_NEAR(r * radius, 1.0f, 0.02f);
    // Including the open ends, filled from the next row. max(|κ1|,|κ2|) = 1/R, |H| = 1/(2R).
    for (float r : *onTube) EXPECT_NEAR(r * radius, mean ? 0.5f : 1.0f, 0.02f);
  }
}

// Scan noise: a sphere (edges ≈ R/16) with ±0.1 % radial jitter, which puts an error of
// order jitter/edge² ≈ 0.3/R on 1/r. Each smoothing pass brings the RMS error of 1/r against
// 1/R down, and the mean stays within 5 % of 1/R (|H| of a noisy H is biased upward).
TEST(SkinInverseRadius, SmoothingReducesNoise) {
  Mesh sphere = makeIcosphere(4, 1.0f);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> jitter(-0.001f, 0.001f);
  for (glm::vec3& p : sphere.positions) p *= 1.0f + jitter(random);
  const VertexCurvature c = curvatureOf(sphere);
  double previousError = 1e9;
  for (int passes : {0, 1, 2, 4, 8}) {
    auto r = skinInverseRadius(sphere, c, {.smoothingPasses = passes});
    ASSERT_TRUE(r.has_value());
    double sum = 0.0, sumSqError = 0.0;
    for (float x : *r) {
      sum += x;
      sumSqError += (x - 1.0) * (x - 1.0);
    }
    const double mean = sum / static_cast<double>(r->size());
    const double rmsError = std::sqrt(sumSqError / static_cast<double>(r->size()));
    std::printf("noisy sphere, %d passes: mean 1/r·R = %.4f, RMS error = %.4f\n", passes, mean, rmsError);
    EXPECT_NEAR(mean, 1.0, 0.05);
    EXPECT_LT(rmsError, previousError);
    previousError = rmsError;
  }
}

TEST(SkinInverseRadius, MismatchedCurvatureIsAnError) {
  const Mesh sphere = makeIcosphere(1, 1.0f);
  const VertexCurvature c = curvatureOf(makeIcosphere(2, 1.0f));
  EXPECT_FALSE(skinInverseRadius(sphere, c).has_value());
}

TEST(SkinLutCoordinate, IsLinearInInverseMillimetresAndClamped) {
  const SkinLutCurvatureRange range{.millimetresPerUnit = 25.0f, .minInverseRadius = 0.1f, .maxInverseRadius = 0.5f};
  EXPECT_FLOAT_EQ(inverseRadiusPerMillimetre(5.0f, 25.0f), 0.2f);
  EXPECT_FLOAT_EQ(skinLutCoordinate(25.0f * 0.1f, range), 0.0f);
  EXPECT_FLOAT_EQ(skinLutCoordinate(25.0f * 0.3f, range), 0.5f);
  EXPECT_FLOAT_EQ(skinLutCoordinate(25.0f * 0.5f, range), 1.0f);
  EXPECT_FLOAT_EQ(skinLutCoordinate(0.0f, range), 0.0f);
  EXPECT_FLOAT_EQ(skinLutCoordinate(1000.0f, range), 1.0f);
}

/// The value below which fraction p/100 of the total weight lies (values paired with weights).
float weightedPercentile(std::vector<std::pair<float, float>> valueWeight, double p) {
  std::sort(valueWeight.begin(), valueWeight.end());
  double total = 0.0;
  for (auto [value, weight] : valueWeight) total += weight;
  double below = 0.0;
  for (auto [value, weight] : valueWeight) {
    below += weight;
    if (below >= p / 100.0 * total) return value;
  }
  return valueWeight.back().first;
}

// The real head: finishes, nothing NaN, and prints the distribution of 1/r in 1/mm at the
// scale nalu.json gives the head, to choose the LUT's 1/r range.
TEST(SkinInverseRadius, LeePerrySmithHeadDistribution) {
  MANE_RESOLVE_OR_SKIP(file, "head/LeePerrySmith/LeePerrySmith.glb");
  auto head = loadGltf(file);
  ASSERT_TRUE(head.has_value()) << head.error().message;
  auto scene = loadScene(std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  const MeshInstance* instance = scene->findMesh("head");
  ASSERT_NE(instance, nullptr);
  const float millimetresPerUnit = instance->transform.scale * 1000.0f;

  const auto start = std::chrono::steady_clock::now();
  auto curvature = computeVertexCurvature(*head);
  ASSERT_TRUE(curvature.has_value()) << curvature.error().message;
  const auto curvatureDone = std::chrono::steady_clock::now();
  auto inverseRadius = skinInverseRadius(*head, *curvature);
  ASSERT_TRUE(inverseRadius.has_value()) << inverseRadius.error().message;
  const auto end = std::chrono::steady_clock::now();
  const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };

  std::size_t flagged[4] = {};
  std::size_t representatives = 0;
  double convexArea = 0.0, totalArea = 0.0;
  for (std::size_t i = 0; i < curvature->vertexCount(); ++i) {
    for (int bit = 0; bit < 4; ++bit) flagged[bit] += (curvature->flags[i] >> bit) & 1;
    ASSERT_TRUE(std::isfinite(curvature->meanCurvature[i]) && std::isfinite(curvature->gaussianCurvature[i]) &&
                std::isfinite(curvature->maxCurvature[i]) && std::isfinite(curvature->minCurvature[i]))
        << "vertex " << i;
    ASSERT_TRUE(std::isfinite((*inverseRadius)[i]) && (*inverseRadius)[i] >= 0.0f) << "vertex " << i;
    if (curvature->weldedVertex[i] != i) continue;
    ++representatives;
    totalArea += curvature->mixedArea[i];
    if (curvature->meanCurvature[i] > 0.0f) convexArea += curvature->mixedArea[i];
  }
  std::printf(
      "LeePerrySmith: %zu vertices (%zu after welding), %zu triangles, %zu skipped; flagged: %zu boundary, "
      "%zu non-manifold, %zu degenerate, %zu unused; H > 0 on %.0f %% of the area\n",
      head->vertexCount(), representatives, head->triangleCount(), curvature->skippedTriangles, flagged[0], flagged[1],
      flagged[2], flagged[3], 100.0 * convexArea / totalArea);
  std::printf("time: curvature %.1f ms, 1/r (fill + 2 smoothing passes) %.1f ms\n", ms(start, curvatureDone),
              ms(curvatureDone, end));
  std::printf("1/r in 1/mm at %.1f mm per unit (nalu.json); per welded vertex, and weighted by area (A):\n",
              millimetresPerUnit);
  std::printf("%-22s %7s %7s %7s %7s %7s %7s %7s %7s\n", "measure, passes", "p1", "p5", "p25", "p50", "p75", "p95",
              "p99", "max");
  for (const auto measure : {SkinCurvatureMeasure::meanAbsolute, SkinCurvatureMeasure::maxPrincipalAbsolute}) {
    for (int passes : {0, 2, 8}) {
      auto r = skinInverseRadius(*head, *curvature, {.measure = measure, .smoothingPasses = passes});
      ASSERT_TRUE(r.has_value());
      std::vector<std::pair<float, float>> perMm;  // (1/r in 1/mm, area in unit²)
      for (std::size_t i = 0; i < r->size(); ++i) {
        if (curvature->weldedVertex[i] == i) {
          perMm.emplace_back(inverseRadiusPerMillimetre((*r)[i], millimetresPerUnit), curvature->mixedArea[i]);
        }
      }
      const char* name = measure == SkinCurvatureMeasure::meanAbsolute ? "|H|" : "max(|k1|,|k2|)";
      for (const bool byArea : {false, true}) {
        std::printf("%-16s %2d %s", name, passes, byArea ? "A" : " ");
        for (double p : {1.0, 5.0, 25.0, 50.0, 75.0, 95.0, 99.0, 100.0}) {
          auto weighted = perMm;
          if (!byArea) {
            for (auto& [value, weight] : weighted) weight = 1.0f;
          }
          std::printf(" %7.4f", weightedPercentile(std::move(weighted), p));
        }
        std::printf("\n");
      }
    }
  }
  // The head is one closed-enough surface: most vertices have curvature of their own.
  EXPECT_LT(flagged[0] + flagged[1] + flagged[2], head->vertexCount() / 10);
}

}  // namespace
}  // namespace mane::scenes
