#include "render/luts/surface_voxels.hpp"

#include <array>
#include <limits>
#include <string>

namespace mane::render {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr std::array<glm::ivec3, 6> kFaceNeighbours{
    {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}}};

bool inGrid(const glm::ivec3& c, int n) {
  return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < n && c.y < n && c.z < n;
}

// Empty cells 6-connected to the outside of the grid (flood fill from the grid's faces).
std::vector<std::uint8_t> exteriorCells(const SolidVoxels& voxels) {
  const int n = voxels.resolution;
  std::vector<std::uint8_t> exterior(voxels.cellCount(), 0);
  std::vector<std::uint32_t> stack;
  const auto visit = [&](const glm::ivec3& c) {
    const std::size_t cell = voxels.index(c.x, c.y, c.z);
    if (voxels.solid[cell] != 0 || exterior[cell] != 0) return;
    exterior[cell] = 1;
    stack.push_back(static_cast<std::uint32_t>(cell));
  };
  for (std::size_t cell = 0; cell < voxels.cellCount(); ++cell) {
    const glm::ivec3 c = voxels.coordinates(cell);
    if (c.x == 0 || c.y == 0 || c.z == 0 || c.x == n - 1 || c.y == n - 1 || c.z == n - 1) visit(c);
  }
  while (!stack.empty()) {
    const glm::ivec3 c = voxels.coordinates(stack.back());
    stack.pop_back();
    for (const glm::ivec3& d : kFaceNeighbours) {
      if (inGrid(c + d, n)) visit(c + d);
    }
  }
  return exterior;
}

// One axis of the Felzenszwalb–Huttenlocher transform: out[q] = min_p in[p] + h²(q − p)² over
// the n samples of one grid line, with the argmin's feature carried to `outFeature`. Samples
// with in[p] = ∞ hold no feature yet and are skipped. `v` and `z` are scratch of n and n + 1.
void transformLine(std::span<const double> in, std::span<const std::uint32_t> inFeature, double h2,
                   std::span<double> out, std::span<std::uint32_t> outFeature, std::span<int> v, std::span<double> z) {
  const int n = static_cast<int>(in.size());
  const auto meet = [&](int q, int p) {  // where the parabolas rooted at q > p intersect
    return ((in[q] + h2 * q * q) - (in[p] + h2 * p * p)) / (2.0 * h2 * (q - p));
  };
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (in[q] == kInfinity) continue;
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInfinity;
      z[1] = kInfinity;
      continue;
    }
    double s = meet(q, v[k]);
    while (s <= z[k]) s = meet(q, v[--k]);  // z[0] = −∞ stops it
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInfinity;
  }
  if (k < 0) {
    for (int q = 0; q < n; ++q) {
      out[q] = kInfinity;
      outFeature[q] = kNone;
    }
    return;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double d = q - v[k];
    out[q] = h2 * d * d + in[v[k]];
    outFeature[q] = inFeature[v[k]];
  }
}

// Nearest surface voxel of every cell: the transform along x, then y, then z.
std::vector<std::uint32_t> nearestSurfaceVoxel(const SolidVoxels& voxels, std::span<const std::uint32_t> cells) {
  const int n = voxels.resolution;
  const std::size_t count = voxels.cellCount();
  std::vector<double> distance(count, kInfinity);
  std::vector<std::uint32_t> feature(count, kNone);
  for (std::size_t m = 0; m < cells.size(); ++m) {
    distance[cells[m]] = 0.0;
    feature[cells[m]] = static_cast<std::uint32_t>(m);
  }
  std::vector<double> lineIn(n), lineOut(n), z(n + 1);
  std::vector<std::uint32_t> featureIn(n), featureOut(n);
  std::vector<int> v(n);
  for (int axis = 0; axis < 3; ++axis) {
    const double h2 = voxels.voxelSize[axis] * voxels.voxelSize[axis];
    const std::size_t stride = axis == 0   ? 1
                               : axis == 1 ? static_cast<std::size_t>(n)
                                           : static_cast<std::size_t>(n) * n;
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        // The line's first cell: `a` and `b` run over the two other axes.
        const glm::ivec3 start = axis == 0   ? glm::ivec3(0, a, b)
                                 : axis == 1 ? glm::ivec3(a, 0, b)
                                             : glm::ivec3(a, b, 0);
        const std::size_t base = voxels.index(start.x, start.y, start.z);
        for (int q = 0; q < n; ++q) {
          lineIn[q] = distance[base + q * stride];
          featureIn[q] = feature[base + q * stride];
        }
        transformLine(lineIn, featureIn, h2, lineOut, featureOut, v, z);
        for (int q = 0; q < n; ++q) {
          distance[base + q * stride] = lineOut[q];
          feature[base + q * stride] = featureOut[q];
        }
      }
    }
  }
  return feature;
}

}  // namespace

std::vector<std::uint32_t> numberSurfaceVoxels(const SolidVoxels& voxels) {
  const int n = voxels.resolution;
  const std::vector<std::uint8_t> exterior = exteriorCells(voxels);
  std::vector<std::uint32_t> cells;
  for (std::size_t cell = 0; cell < voxels.cellCount(); ++cell) {
    if (voxels.solid[cell] == 0) continue;
    const glm::ivec3 c = voxels.coordinates(cell);
    for (const glm::ivec3& d : kFaceNeighbours) {
      const glm::ivec3 e = c + d;
      if (!inGrid(e, n) || exterior[voxels.index(e.x, e.y, e.z)] != 0) {
        cells.push_back(static_cast<std::uint32_t>(cell));
        break;
      }
    }
  }
  return cells;
}

Result<SurfaceVoxels> findSurfaceVoxels(const SolidVoxels& voxels) {
  SurfaceVoxels surface;
  surface.cells = numberSurfaceVoxels(voxels);
  if (surface.cells.empty()) {
    return fail("findSurfaceVoxels: no cell of the " + std::to_string(voxels.resolution) +
                "³ grid is solid; the mesh is thinner than a cell everywhere (raise the resolution).");
  }
  surface.nearest = nearestSurfaceVoxel(voxels, surface.cells);
  return surface;
}

}  // namespace mane::render
