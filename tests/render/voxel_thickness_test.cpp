// The voxelized thickness LUT (render/luts/voxel_thickness.hpp) on meshes built
// in code (tests/render/voxel_test_shapes.hpp). The references are independent of the code under
// test:
//  - inside/outside of every cell centre against the analytic solid (box, octahedron whose
//    apexes sit exactly on rays, cube minus ball);
//  - the nearest surface voxel against a brute-force search;
//  - LUT entries against analytic inside lengths of the segment between the two voxel centres:
//    segment–box clipping, segment–ball intersection for the hollow, and a root-bracketed march
//    of the torus's implicit function across its hole.
// Tolerance "one voxel": the voxel's diagonal |h|. A voxelized boundary sits up to half a cell
// from the true one, and a segment's length within a cell is at most the cell's diagonal, so a
// segment crossing the surface k times errs by about k·|h|/2 at worst when it crosses steeply.
// Segments that graze a surface (within a cell of it for many cells) are left out: along them
// the voxel staircase decides, which is the method's resolution, not a defect.
// Also: the run-skipping walk against the plain one (identical bits), the same table for any
// thread count, bad input, and the table's memory at N = 30, 40, 50 (printed with build times).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vector_relational.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "render/luts/solid_segments.hpp"
#include "render/luts/solid_voxels.hpp"
#include "render/luts/surface_voxels.hpp"
#include "render/luts/voxel_thickness.hpp"
#include "tests/render/voxel_test_shapes.hpp"

namespace mane::render {
namespace {

using test::ballChord;
using test::boxChord;
using test::boxDepth;
using test::torusInside;
using test::TriangleMesh;

double norm(const glm::dvec3& v) {
  return std::sqrt(glm::dot(v, v));
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double voxelDiagonal(const SolidVoxels& voxels) {
  return norm(voxels.voxelSize);
}

// Largest distance from the analytic sphere of radius r to the UV sphere inscribed in it: the
// faces' planes sink at most r·(1 − cos(π/rings)·cos(π/segments)).
double uvSphereSagitta(double r, int rings, int segments) {
  return r * (1.0 - std::cos(3.14159265358979 / rings) * std::cos(3.14159265358979 / segments));
}

// The voxelized-translucency paper's first scene: the cube [−1, 1]³ with a hollow ball of radius
// 0.5 at its centre, the ball's triangles facing inward.
constexpr double kHollowRadius = 0.5;
TriangleMesh hollowCube() {
  return test::combined(test::box(glm::vec3(-1.0f), glm::vec3(1.0f)),
                        test::sphere(glm::vec3(0.0f), static_cast<float>(kHollowRadius), 48, 96, /*inward=*/true));
}

// --- Solid voxelization ------------------------------------------------------------------------

TEST(SolidVoxels, RaysThroughSharedEdgesCountThemOnce) {
  // A box with a box-shaped hollow (wound inward). Both boxes' face diagonals run through the
  // centres of the columns on the grid's diagonal, so those rays meet an edge shared by two
  // triangles on every face: counted twice, the winding number there would be 2 − 1 inside the
  // hollow, and the hollow's cells on the diagonal would come out solid.
  const glm::vec3 lo(-0.3f, 0.0f, 2.0f), hi(0.7f, 1.0f, 3.0f), inLo(0.0f, 0.3f, 2.3f), inHi(0.4f, 0.7f, 2.7f);
  TriangleMesh hollow = test::box(inLo, inHi);
  for (std::size_t t = 0; t < hollow.indices.size(); t += 3) std::swap(hollow.indices[t + 1], hollow.indices[t + 2]);
  const TriangleMesh mesh = test::combined(test::box(lo, hi), hollow);
  for (const int n : {4, 9, 16}) {
    auto voxels = voxelizeSolid(mesh.positions, mesh.indices, n);
    ASSERT_TRUE(voxels) << voxels.error().message;
    int wrong = 0;
    for (std::size_t cell = 0; cell < voxels->cellCount(); ++cell) {
      const glm::dvec3 c = voxels->centre(cell);
      const bool inHollow =
          glm::all(glm::greaterThan(c, glm::dvec3(inLo))) && glm::all(glm::lessThan(c, glm::dvec3(inHi)));
      wrong += (voxels->solid[cell] != 0) == inHollow ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0) << "N = " << n;
  }
}

TEST(SolidVoxels, RaysThroughAVertexWhereFourFacesMeetCountItOnce) {
  // With N odd the octahedron's apexes (±1, 0, 0) project exactly onto the centre column's ray,
  // where four faces meet. A box-shaped hollow (wound inward) on that ray makes a miscount show:
  // four crossings at the apex minus one at the hollow would leave the hollow solid.
  TriangleMesh hollow = test::box(glm::vec3(-0.3f), glm::vec3(0.3f));
  for (std::size_t t = 0; t < hollow.indices.size(); t += 3) std::swap(hollow.indices[t + 1], hollow.indices[t + 2]);
  const TriangleMesh mesh = test::combined(test::octahedron(glm::vec3(0.0f), 1.0f), hollow);
  for (const int n : {9, 15, 31}) {
    auto voxels = voxelizeSolid(mesh.positions, mesh.indices, n);
    ASSERT_TRUE(voxels) << voxels.error().message;
    int wrong = 0, decided = 0;
    for (std::size_t cell = 0; cell < voxels->cellCount(); ++cell) {
      const glm::dvec3 c = voxels->centre(cell);
      const double level = std::abs(c.x) + std::abs(c.y) + std::abs(c.z) - 1.0;
      if (std::abs(level) < 1e-6) continue;  // on the surface: either answer is right
      ++decided;
      const bool inHollow = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) < 0.3;
      if ((level < 0.0 && !inHollow) != (voxels->solid[cell] != 0)) ++wrong;
    }
    EXPECT_EQ(wrong, 0) << "N = " << n << ", " << decided << " cells decided";
  }
}

TEST(SolidVoxels, TheCubesSphericalHollowIsEmptyAndItsMaterialSolid) {
  const TriangleMesh mesh = hollowCube();
  auto voxels = voxelizeSolid(mesh.positions, mesh.indices, 30);
  ASSERT_TRUE(voxels) << voxels.error().message;
  // Cells whose centre is within the tessellation's sagitta of the sphere may go either way.
  const double band = uvSphereSagitta(kHollowRadius, 48, 96) + 1e-6;
  int wrong = 0, hollow = 0;
  for (std::size_t cell = 0; cell < voxels->cellCount(); ++cell) {
    const double r = norm(voxels->centre(cell));
    if (r > kHollowRadius - band && r < kHollowRadius) continue;
    const bool material = r > kHollowRadius;
    hollow += material ? 0 : 1;
    if (material != (voxels->solid[cell] != 0)) ++wrong;
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(hollow, 500);  // 4/3·π·0.5³ / (2/30)³ ≈ 1,767 cells
}

// --- Surface voxels ------------------------------------------------------------------------------

TEST(SurfaceVoxels, OnlyTheOuterShellOfTheHollowCubeIsNumbered) {
  // Every cell on the grid's faces is solid and exterior-facing; the hollow's wall faces no
  // exterior cell, so M is the outer shell alone: N³ − (N − 2)³.
  const TriangleMesh mesh = hollowCube();
  for (const int n : {10, 30}) {
    auto voxels = voxelizeSolid(mesh.positions, mesh.indices, n);
    ASSERT_TRUE(voxels) << voxels.error().message;
    const std::vector<std::uint32_t> cells = numberSurfaceVoxels(*voxels);
    EXPECT_EQ(cells.size(), static_cast<std::size_t>(n * n * n - (n - 2) * (n - 2) * (n - 2))) << "N = " << n;
    EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end()));
  }
}

TEST(SurfaceVoxels, EveryCellMapsToItsNearestSurfaceVoxelAsABruteForceSearchFindsIt) {
  // A torus has a hole and anisotropic cells (flat along z): both stress the distance transform.
  const TriangleMesh mesh = test::torus(1.0f, 0.4f, 64, 32);
  auto voxels = voxelizeSolid(mesh.positions, mesh.indices, 20);
  ASSERT_TRUE(voxels) << voxels.error().message;
  auto surface = findSurfaceVoxels(*voxels);
  ASSERT_TRUE(surface) << surface.error().message;
  int wrong = 0;
  for (std::size_t cell = 0; cell < voxels->cellCount(); ++cell) {
    const glm::dvec3 c = voxels->centre(cell);
    double best = std::numeric_limits<double>::infinity();
    for (const std::uint32_t s : surface->cells) best = std::min(best, norm(voxels->centre(s) - c));
    const double found = norm(voxels->centre(surface->cells[surface->nearest[cell]]) - c);
    if (found > best + 1e-12) ++wrong;
  }
  EXPECT_EQ(wrong, 0) << "of " << voxels->cellCount() << " cells";
}

TEST(SolidSegments, TheRunSkippingWalkGivesThePlainWalksBits) {
  const TriangleMesh mesh = hollowCube();
  auto voxels = voxelizeSolid(mesh.positions, mesh.indices, 30);
  ASSERT_TRUE(voxels) << voxels.error().message;
  const SolidSegmentWalker walker(*voxels);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> cell(0, 29);
  int differ = 0;
  for (int s = 0; s < 20000; ++s) {
    const glm::ivec3 a(cell(rng), cell(rng), cell(rng)), b(cell(rng), cell(rng), cell(rng));
    if (walker.solidFraction(a, b) != solidFractionBetweenCells(*voxels, a, b)) ++differ;
  }
  EXPECT_EQ(differ, 0);
}

// --- The thickness LUT ---------------------------------------------------------------------------

// `count` reproducible pairs (a, b), a ≠ b, of surface voxel numbers below `m`.
std::vector<std::pair<std::uint32_t, std::uint32_t>> randomPairs(std::uint32_t m, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> pick(0, m - 1);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  while (static_cast<int>(pairs.size()) < count) {
    const std::uint32_t a = pick(rng), b = pick(rng);
    if (a != b) pairs.emplace_back(a, b);
  }
  return pairs;
}

TEST(VoxelThicknessLut, AnAxisAlignedSlabsEntriesAreTheDistancesBetweenVoxelCentres) {
  // Every cell of an axis-aligned box is solid, so each entry is exactly |c_a − c_b| up to the
  // half float's rounding (2⁻¹² of the diagonal). A point on a face lies in a grid boundary cell,
  // which is a surface voxel, within |h|/2 of its centre: a lookup between two surface points
  // errs by at most |h| from the chord |p − q|, which lies in the (convex) slab.
  const glm::dvec3 lo(-0.5, -0.3, -0.1), hi(0.5, 0.3, 0.1);
  const TriangleMesh mesh = test::box(glm::vec3(lo), glm::vec3(hi));
  VoxelThicknessSettings settings;
  settings.resolution = 20;
  auto lut = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
  ASSERT_TRUE(lut) << lut.error().message;
  const double rounding = std::ldexp(lut->thicknessScale(), -12);
  double worst = 0.0;
  for (const auto& [a, b] : randomPairs(lut->surfaceVoxelCount(), 20000, 1)) {
    const double expected = norm(lut->surfaceVoxelCentre(a) - lut->surfaceVoxelCentre(b));
    worst = std::max(worst, std::abs(lut->thickness(a, b) - expected));
  }
  EXPECT_LE(worst, rounding);

  const double h = voxelDiagonal(lut->voxels());
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto onSurface = [&] {
    glm::dvec3 p = lo + glm::dvec3(unit(rng), unit(rng), unit(rng)) * (hi - lo);
    const int axis = static_cast<int>(rng() % 3);
    p[axis] = rng() % 2 ? hi[axis] : lo[axis];
    return p;
  };
  double worstLookup = 0.0;
  for (int s = 0; s < 5000; ++s) {
    const glm::dvec3 p = onSurface(), q = onSurface();
    worstLookup = std::max(worstLookup, std::abs(lut->thicknessBetween(glm::vec3(p), glm::vec3(q)) - norm(q - p)));
  }
  EXPECT_LE(worstLookup, h + rounding);
  RecordProperty("worst_lookup_error_in_voxels", std::to_string(worstLookup / h));
}

TEST(VoxelThicknessLut, ARotatedSlabsEntriesMatchTheAnalyticChordWithinOneVoxel) {
  // A slab at an angle to the grid, so its faces are voxel staircases. Reference: the segment
  // between the two voxel centres clipped against the exact slab. Pairs whose segment's middle is
  // less than one voxel below the surface run along a face through the staircase and are left
  // out (see the file comment); the rest must agree within one voxel diagonal |h|.
  const glm::dvec3 half(0.5, 0.3, 0.2), centre(0.1, -0.2, 0.3);
  const glm::dmat3 rotation(glm::dvec3(0.8, 0.6, 0.0), glm::dvec3(-0.48, 0.64, 0.6), glm::dvec3(0.36, -0.48, 0.8));
  const TriangleMesh mesh =
      test::transformed(test::box(-glm::vec3(half), glm::vec3(half)), glm::mat3(rotation), glm::vec3(centre));
  VoxelThicknessSettings settings;
  settings.resolution = 24;
  auto lut = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
  ASSERT_TRUE(lut) << lut.error().message;
  const double h = voxelDiagonal(lut->voxels());
  double worst = 0.0;
  int compared = 0;
  for (const auto& [a, b] : randomPairs(lut->surfaceVoxelCount(), 20000, 4)) {
    const glm::dvec3 p = lut->surfaceVoxelCentre(a), q = lut->surfaceVoxelCentre(b);
    if (boxDepth(0.5 * (p + q), rotation, centre, half) < h) continue;
    ++compared;
    worst = std::max(worst, std::abs(lut->thickness(a, b) - boxChord(p, q, rotation, centre, half)));
  }
  EXPECT_GT(compared, 2000);
  EXPECT_LE(worst, h);
  RecordProperty("worst_error_in_voxels", std::to_string(worst / h));
  std::printf("rotated slab, N = 24: M = %u, %d pairs compared, worst error %.2f voxel diagonals\n",
              lut->surfaceVoxelCount(), compared, worst / h);
}

TEST(VoxelThicknessLut, ThroughTheCubesHollowTheThicknessDropsByTheHollowsChord) {
  // Pairs from the cube's −x face layer to its +x face layer. Without the hollow every cell is
  // solid (the same grid: the box alone has the same bounding box), so the drop from that to the
  // LUT entry is what the hollow takes; the reference is the analytic segment–ball chord. Pairs
  // whose line passes within one voxel of the ball's surface graze it and are left out.
  constexpr int kN = 30;
  const TriangleMesh mesh = hollowCube();
  const TriangleMesh solidCube = test::box(glm::vec3(-1.0f), glm::vec3(1.0f));
  VoxelThicknessSettings settings;
  settings.resolution = kN;
  settings.threads = 2;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  auto lut = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
  const double wall = seconds(start), cpu = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  ASSERT_TRUE(lut) << lut.error().message;
  auto withoutHollow = voxelizeSolid(solidCube.positions, solidCube.indices, kN);
  ASSERT_TRUE(withoutHollow) << withoutHollow.error().message;

  const SolidVoxels& voxels = lut->voxels();
  std::vector<std::uint32_t> left, right;
  for (std::uint32_t m = 0; m < lut->surfaceVoxelCount(); ++m) {
    const int x = voxels.coordinates(lut->surface().cells[m]).x;
    if (x == 0) left.push_back(m);
    if (x == kN - 1) right.push_back(m);
  }
  const double h = voxelDiagonal(voxels);
  std::mt19937 rng(3);
  double worst = 0.0;
  int compared = 0, throughHollow = 0;
  for (int s = 0; s < 20000; ++s) {
    const std::uint32_t a = left[rng() % left.size()], b = right[rng() % right.size()];
    const glm::dvec3 p = lut->surfaceVoxelCentre(a), q = lut->surfaceVoxelCentre(b);
    const glm::dvec3 d = glm::normalize(q - p);
    const double closest = norm(p - glm::dot(p, d) * d);  // the line's distance from the ball's centre
    if (std::abs(closest - kHollowRadius) < h) continue;
    const glm::ivec3 ca = voxels.coordinates(lut->surface().cells[a]), cb = voxels.coordinates(lut->surface().cells[b]);
    const double solid = solidFractionBetweenCells(*withoutHollow, ca, cb) * distanceBetweenCells(voxels, ca, cb);
    const double chord = ballChord(p, q, glm::dvec3(0.0), kHollowRadius);
    ++compared;
    throughHollow += chord > 0.0 ? 1 : 0;
    worst = std::max(worst, std::abs((solid - lut->thickness(a, b)) - chord));
  }
  EXPECT_GT(throughHollow, 1000);
  EXPECT_GT(compared - throughHollow, 1000);
  EXPECT_LE(worst, h);
  RecordProperty("worst_error_in_voxels", std::to_string(worst / h));
  std::printf(
      "cube with hollow, N = %d: M = %u, table %.1f MB, built in %.2f s wall (%.2f s CPU, 2 threads); "
      "%d pairs compared (%d through the hollow), worst error %.2f voxel diagonals\n",
      kN, lut->surfaceVoxelCount(), VoxelThicknessLut::tableBytes(lut->surfaceVoxelCount()) / 1e6, wall, cpu, compared,
      throughHollow, worst / h);
}

TEST(VoxelThicknessLut, ASegmentAcrossTheTorusHoleHasTheAnalyticInsideLength) {
  // Diameters of the torus's outer rim in its plane: the points (R + r)(cos θ, sin θ, 0) and their
  // opposites each find their surface voxel, and the entry between them must match the inside
  // length of the segment between those voxels' centres (a march of the implicit torus) within
  // one voxel diagonal. The exact rim-to-rim figure is 4r (two tube crossings); the voxel
  // centres sit within |h|/2 of the rim points, so the entry is also within 2|h| of it.
  constexpr double kMajor = 1.0, kMinor = 0.4;
  const TriangleMesh mesh = test::torus(static_cast<float>(kMajor), static_cast<float>(kMinor), 96, 48);
  VoxelThicknessSettings settings;
  settings.resolution = 24;
  auto lut = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
  ASSERT_TRUE(lut) << lut.error().message;
  const double h = voxelDiagonal(lut->voxels());
  double worst = 0.0, worstRim = 0.0;
  for (int k = 0; k < 24; ++k) {
    const double theta = k * 3.14159265358979 / 24;
    const glm::dvec3 rim = (kMajor + kMinor) * glm::dvec3(std::cos(theta), std::sin(theta), 0.0);
    const std::uint32_t a = lut->surfaceVoxelAt(glm::vec3(rim)), b = lut->surfaceVoxelAt(glm::vec3(-rim));
    const double inside = torusInside(lut->surfaceVoxelCentre(a), lut->surfaceVoxelCentre(b), kMajor, kMinor);
    EXPECT_GT(inside, 3.0 * kMinor) << "θ = " << theta;  // it does cross both sides of the tube
    worst = std::max(worst, std::abs(lut->thickness(a, b) - inside));
    worstRim = std::max(worstRim, std::abs(lut->thickness(a, b) - 4.0 * kMinor));
  }
  EXPECT_LE(worst, h);
  EXPECT_LE(worstRim, 2.0 * h);
  std::printf("torus, N = 24: M = %u, worst error %.2f voxel diagonals (%.2f against 4r)\n", lut->surfaceVoxelCount(),
              worst / h, worstRim / h);
}

TEST(VoxelThicknessLut, IsSymmetricWithAZeroDiagonalAndEachSurfaceVoxelFindsItself) {
  const TriangleMesh mesh = test::sphere(glm::vec3(0.2f, 0.0f, -0.1f), 0.7f, 24, 48);
  VoxelThicknessSettings settings;
  settings.resolution = 14;
  auto lut = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
  ASSERT_TRUE(lut) << lut.error().message;
  const std::uint32_t m = lut->surfaceVoxelCount();
  ASSERT_EQ(lut->texels().size(), static_cast<std::size_t>(m) * m);
  int asymmetric = 0, lost = 0;
  for (std::uint32_t a = 0; a < m; ++a) {
    EXPECT_EQ(lut->texels()[static_cast<std::size_t>(a) * m + a], 0);
    for (std::uint32_t b = a + 1; b < m; ++b) {
      asymmetric +=
          lut->texels()[static_cast<std::size_t>(a) * m + b] != lut->texels()[static_cast<std::size_t>(b) * m + a];
    }
    lost += lut->surfaceVoxelAt(glm::vec3(lut->surfaceVoxelCentre(a))) != a;
  }
  EXPECT_EQ(asymmetric, 0);
  EXPECT_EQ(lost, 0);
}

TEST(VoxelThicknessLut, IsBitIdenticalRunToRunAndForAnyThreadCount) {
  const TriangleMesh mesh =
      test::combined(test::torus(1.0f, 0.45f, 48, 24), test::sphere(glm::vec3(1.0f, 0.0f, 0.0f), 0.2f, 12, 24, true));
  VoxelThicknessSettings settings;
  settings.resolution = 16;
  settings.threads = 1;
  auto reference = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
  ASSERT_TRUE(reference) << reference.error().message;
  for (const unsigned threads : {1u, 2u, 3u, 0u}) {
    settings.threads = threads;
    auto again = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
    ASSERT_TRUE(again) << again.error().message;
    EXPECT_TRUE(std::ranges::equal(again->texels(), reference->texels())) << threads << " threads";
    EXPECT_TRUE(std::ranges::equal(again->nearestMap(), reference->nearestMap())) << threads << " threads";
  }
}

TEST(VoxelThicknessLut, BadInputGivesAClearError) {
  const TriangleMesh cube = test::box(glm::vec3(0.0f), glm::vec3(1.0f));
  const auto error = [](const TriangleMesh& mesh, int resolution = 8, std::size_t maxBytes = std::size_t{1} << 30) {
    VoxelThicknessSettings settings;
    settings.resolution = resolution;
    settings.maxTableBytes = maxBytes;
    auto lut = VoxelThicknessLut::build(mesh.positions, mesh.indices, settings);
    return lut ? std::string("no error") : lut.error().message;
  };
  using ::testing::HasSubstr;
  EXPECT_THAT(error(cube, 3), HasSubstr("resolution 3 is outside [4, 128]"));
  EXPECT_THAT(error(cube, 129), HasSubstr("resolution 129 is outside [4, 128]"));
  EXPECT_THAT(error(TriangleMesh{}), HasSubstr("no triangles"));

  TriangleMesh broken = cube;
  broken.indices.pop_back();
  EXPECT_THAT(error(broken), HasSubstr("not a multiple of 3"));
  broken = cube;
  broken.indices[7] = 99;
  EXPECT_THAT(error(broken), HasSubstr("index 7 (triangle 2) is 99, but there are 8 positions"));
  broken = cube;
  broken.positions[3].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(error(broken), HasSubstr("position 3 is not finite"));
  broken = cube;
  broken.indices.resize(broken.indices.size() - 3);  // a missing triangle: a hole
  EXPECT_THAT(error(broken), HasSubstr("the mesh is not closed"));
  broken = cube;
  std::swap(broken.indices[1], broken.indices[2]);  // one triangle wound the wrong way
  EXPECT_THAT(error(broken), HasSubstr("the mesh is not closed"));
  // Two triangles back to back: closed, but they enclose no volume.
  const TriangleMesh sheet{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 1}};
  EXPECT_THAT(error(sheet), HasSubstr("flat along axis 2"));
  EXPECT_THAT(error(cube, 8, 1000), HasSubstr("296 surface voxels at resolution 8 need a 175232-byte table"));
}

TEST(VoxelThicknessLut, TableMemoryGrowsAsTheSquareOfTheSurfaceVoxelCount) {
  // The cube with a hollow at the paper's resolutions. Only N = 30 is built in full (in
  // ThroughTheCubesHollow…); for 40 and 50 the surface voxels are counted, which is all the
  // table's size depends on: M = N³ − (N − 2)³ for a cube, 2·M² bytes.
  const TriangleMesh mesh = hollowCube();
  for (const int n : {30, 40, 50}) {
    const auto start = std::chrono::steady_clock::now();
    auto voxels = voxelizeSolid(mesh.positions, mesh.indices, n);
    ASSERT_TRUE(voxels) << voxels.error().message;
    const std::size_t m = numberSurfaceVoxels(*voxels).size();
    const double elapsed = seconds(start);
    EXPECT_EQ(m, static_cast<std::size_t>(n * n * n - (n - 2) * (n - 2) * (n - 2)));
    const std::size_t bytes = VoxelThicknessLut::tableBytes(m);
    EXPECT_EQ(bytes, 2 * m * m);
    std::printf(
        "N = %d: M = %zu surface voxels, table %zu bytes = %.1f MB (half floats; %.1f MB as floats), "
        "voxelized and numbered in %.3f s\n",
        n, m, bytes, bytes / 1e6, 2.0 * bytes / 1e6, elapsed);
    RecordProperty("table_bytes_N" + std::to_string(n), std::to_string(bytes));
  }
}

TEST(Translucency, TransmittedIntensityFollowsBeerLambertPerChannel) {
  const glm::vec3 incident(2.0f, 1.0f, 0.5f), sigma(1.0f, 4.0f, 0.0f);
  const glm::vec3 none = transmittedIntensity(incident, sigma, 0.0f);
  EXPECT_EQ(none, incident);
  const glm::vec3 once = transmittedIntensity(incident, sigma, 0.5f);
  EXPECT_NEAR(once.x, 2.0 * std::exp(-0.5), 1e-6);
  EXPECT_NEAR(once.y, 1.0 * std::exp(-2.0), 1e-6);
  EXPECT_EQ(once.z, 0.5f);  // σ = 0: no loss
  // Two layers of d transmit what one layer of 2d does.
  const glm::vec3 twice = transmittedIntensity(once, sigma, 0.5f), thick = transmittedIntensity(incident, sigma, 1.0f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(twice[c], thick[c], 1e-6f);
}

}  // namespace
}  // namespace mane::render
