#include "subdiv/tessellator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "subdiv/detail/flat_index_map.hpp"
#include "subdiv/detail/parallel_ranges.hpp"
#include "subdiv/detail/ptex_sides.hpp"

namespace mane::subdiv {
namespace {

using detail::kGrid;

// Below these a thread costs more than it saves (evaluating a limit point costs about half of
// refining and triangulating a face).
constexpr std::size_t kMinFacesPerWorker = 512;
constexpr std::size_t kMinPointsPerWorker = 1024;
constexpr std::size_t kChunksPerWorker = 16;

// keepsTarget: a kept tessellation's screen error may grow by this fraction, the tests' bound.
// It is checked through the scale at the vertices; the errors were measured at cell midpoints
// between them, where the scale's growth, nearly a ratio of depths, is no larger ...
constexpr double kKeptErrorGrowth = 0.10;
// ... and is tessellated again once every point's scale has fallen below this fraction, when
// it has about 1/0.7 ≈ 1.4 times the triangles the view needs (the count goes with the scale).
constexpr double kKeptFinestScale = 0.7;

// update prepares the next tessellation in the background, between the caller's frames, and
// adopts it this many calls later: at 60 frames a second, time enough for one thread to
// tessellate the LeePerrySmith head filling a 1280×720 image.
constexpr int kPreparedCalls = 5;
// It prepares when the largest growth of a scale, extrapolated from its rate over the last
// kGrowthSpan calls (an even number: an animation that alternates between two poses every
// frame changes it by the same amount each way), would leave the allowance within twice that
// latency; or, whatever the rate, once it has passed this much of the 10 % allowed, or every
// scale has fallen below the next fraction.
constexpr std::size_t kGrowthSpan = 4;
constexpr double kPrepareErrorGrowth = 0.07;
constexpr double kPrepareFinestScale = 0.75;
// The preparing threads give their cores to the caller's work (detail::yieldToForeground)
// between faces and every so many limit points, cells, lines or triangle corners, so the gaps
// stay short against a frame; only a finely split face, or the thread being descheduled, makes a
// long one.
constexpr std::size_t kPointsBetweenYields = 64;
constexpr std::size_t kCellsBetweenYields = 4096;
constexpr std::size_t kLinesBetweenYields = 256;
constexpr std::size_t kCornersBetweenYields = 4096;

/// Whether a tessellation whose points' scales grew by at most `growth` (Impl::scaleGrowth)
/// still keeps within the target and is not too fine.
bool keepsWithin(const std::optional<double>& growth) {
  return growth && *growth <= 1.0 + kKeptErrorGrowth && *growth >= kKeptFinestScale;
}

/// A limit point seen by the camera.
struct ProjectedPoint {
  glm::dvec3 world{0.0};
  /// The most pixels a unit-length step from here can move on screen in any direction.
  double pixelsPerUnit = 0.0;
  bool inFront = false;  ///< w > 0: the pixel scale means something
  unsigned outside = 0;  ///< bits: left, right, below, above, behind
};

/// Where a camera puts points, and how much it magnifies them.
class Projector {
public:
  Projector() = default;
  Projector(const glm::dmat4& viewProjection, glm::dvec2 viewport)
      : viewProjection_(viewProjection),
        halfViewport_(0.5 * viewport),
        rowX_(viewProjection[0][0], viewProjection[1][0], viewProjection[2][0]),
        rowY_(viewProjection[0][1], viewProjection[1][1], viewProjection[2][1]),
        rowW_(viewProjection[0][3], viewProjection[1][3], viewProjection[2][3]),
        xx_(glm::dot(rowX_, rowX_)),
        yy_(glm::dot(rowY_, rowY_)),
        ww_(glm::dot(rowW_, rowW_)),
        xy_(glm::dot(rowX_, rowY_)),
        xw_(glm::dot(rowX_, rowW_)),
        yw_(glm::dot(rowY_, rowW_)) {}

  ProjectedPoint project(const glm::dvec3& world) const {
    ProjectedPoint point;
    point.world = world;
    const glm::dvec4 clip = viewProjection_ * glm::dvec4(world, 1.0);
    point.outside = (clip.x < -clip.w ? 1u : 0u) | (clip.x > clip.w ? 2u : 0u) | (clip.y < -clip.w ? 4u : 0u) |
                    (clip.y > clip.w ? 8u : 0u) | (clip.w <= 0.0 ? 16u : 0u);
    point.inFront = clip.w > 0.0;
    if (point.inFront) point.pixelsPerUnit = pixelsPerUnit(clip);
    return point;
  }

  /// The scale at a point in front of the camera, given its clip coordinates.
  double pixelsPerUnit(const glm::dvec4& clip) const {
    return std::sqrt(
        squaredScale(clip.x / clip.w, clip.y / clip.w, halfViewport_.x / clip.w, halfViewport_.y / clip.w));
  }

  /// The largest of pixelsPerUnit(p)² · inverseSquaredScales[k] over points[k], or nothing
  /// when a point is not in front of the camera: for a loop over many points, one division and
  /// one square root a point.
  std::optional<double> largestSquaredGrowth(std::span<const glm::dvec3> points,
                                             std::span<const double> inverseSquaredScales) const {
    double largest = 0.0;
    double nearestW = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < points.size(); ++k) {
      const glm::dvec4 clip = viewProjection_ * glm::dvec4(points[k], 1.0);
      nearestW = std::min(nearestW, clip.w);
      const double inverseW = 1.0 / clip.w;
      const double squared =
          squaredScale(clip.x * inverseW, clip.y * inverseW, halfViewport_.x * inverseW, halfViewport_.y * inverseW);
      largest = std::max(largest, squared * inverseSquaredScales[k]);
    }
    if (!(nearestW > 0.0)) return std::nullopt;
    return largest;
  }

private:
  /// The square of the scale at normalised device coordinates (nx, ny), where a clip unit spans
  /// (sx, sy) pixels: the pixel position's Jacobian has rows a = (M_x − nx·M_w)·sx and
  /// b = (M_y − ny·M_w)·sy, M_r being row r of the matrix without its translation, and the
  /// scale is its largest singular value, the square root of the larger eigenvalue of
  /// [a·a a·b; a·b b·b].
  double squaredScale(double nx, double ny, double sx, double sy) const {
    const double aa = (xx_ - 2.0 * nx * xw_ + nx * nx * ww_) * sx * sx;
    const double bb = (yy_ - 2.0 * ny * yw_ + ny * ny * ww_) * sy * sy;
    const double ab = (xy_ - ny * xw_ - nx * yw_ + nx * ny * ww_) * sx * sy;
    return 0.5 * (aa + bb) + std::sqrt(0.25 * (aa - bb) * (aa - bb) + ab * ab);
  }

  glm::dmat4 viewProjection_{1.0};
  glm::dvec2 halfViewport_{0.5};
  glm::dvec3 rowX_{0.0}, rowY_{0.0}, rowW_{0.0};
  double xx_ = 0.0, yy_ = 0.0, ww_ = 0.0, xy_ = 0.0, xw_ = 0.0, yw_ = 0.0;
};

/// The nine samples of a cell left coarse because they all lay beyond one side of the view.
using CulledSamples = std::array<glm::dvec3, 9>;

/// A quadtree leaf: grid square [i0, i0+size] × [j0, j0+size] of a ptex face.
struct Cell {
  std::uint32_t face = 0;
  std::int64_t i0 = 0, j0 = 0, size = 0;
};

/// A grid point of a ptex face, as the triangulation meets it.
struct GridPoint {
  std::int64_t i = 0, j = 0;
};

}  // namespace

struct AdaptiveTessellator::Impl {
  const LimitSurface* surface = nullptr;
  TessellationSettings settings;
  std::shared_ptr<const detail::PtexSides> sides;  ///< shared with the tessellations it prepares
  std::int64_t smallestCell = 4;
  TessellationStatistics statistics;

  // Per frame.
  Projector projector;
  std::vector<Cell> cells;  ///< all faces' leaves, face after face
  std::vector<std::size_t> firstCellOfFace;
  std::vector<std::vector<std::int64_t>> linePoints;  ///< sorted parameters of cell corners on each line
  /// A triangle corner before it has a vertex number: its shared name and where it lies.
  struct Corner {
    detail::PointName name;
    std::uint32_t face;
    GridPoint point;
  };
  /// What one chunk of ptex faces produces (and its worker's scratch), merged in chunk order.
  struct alignas(64) Worker {
    std::vector<Cell> cells;
    std::vector<CulledSamples> culled;
    bool measuredBehindCamera = false;  ///< a kept cell's error left out samples behind the camera
    std::size_t positionEvaluations = 0;
    std::vector<std::pair<std::int64_t, std::int64_t>> rows, columns;  ///< one face's cell corners: (j, i), (i, j)
    std::vector<GridPoint> polygon;
    std::vector<Corner> corners;  ///< 3 per triangle
  };
  std::vector<Worker> workers;
  // Naming: limit points (one per location) and vertices (one per location and UV side).
  static constexpr std::uint32_t kNoVertex = 0xffffffffu;
  struct Location {
    std::uint32_t face;
    GridPoint point;
    std::uint32_t firstVertex;
    std::uint32_t untaggedVertex;  ///< the vertex with UV tag 0 (most points have only it), or kNoVertex
  };
  struct VertexSource {
    std::uint32_t location;
    std::uint32_t face;
    GridPoint point;
  };
  detail::FlatIndexMap locationIndex;
  detail::FlatIndexMap vertexIndex;           ///< (location, non-zero UV tag) → entry of taggedVertices
  std::vector<std::uint32_t> taggedVertices;  ///< vertices on the far sides of UV seams
  std::vector<Location> locations;
  std::vector<VertexSource> vertices;

  // What keepsTarget needs of the last tessellation.
  std::vector<glm::dvec3> pointPositions;  ///< per location, as last evaluated
  /// Per location, 1 / s² for its scale s (pixels per unit) in the view tessellated for.
  std::vector<double> inverseSquaredScales;
  std::vector<CulledSamples> culled;
  bool keepable = false;  ///< no error was left unmeasured behind the camera

  /// update's scaleGrowth of the last calls that kept this tessellation, newest last
  std::array<double, kGrowthSpan + 1> recentGrowth{};
  std::size_t recentGrowthCount = 0;

  std::uint64_t evaluatedRevision = 0;        ///< the surface's revision at the last evaluation
  std::vector<std::uint32_t> staleLocations;  ///< the locations evaluateVertices evaluates

  Impl(const LimitSurface& limit, const TessellationSettings& chosen, std::shared_ptr<const detail::PtexSides> shared)
      : surface(&limit), settings(chosen), sides(std::move(shared)) {
    smallestCell = kGrid >> settings.maxDepth;
  }

  ProjectedPoint evaluate(Worker& worker, std::uint32_t face, std::int64_t i, std::int64_t j) const {
    ++worker.positionEvaluations;
    return projector.project(surface->evaluatePosition(face, double(i) / double(kGrid), double(j) / double(kGrid)));
  }

  /// The distance between the limit point `middle` and the midpoint of the straight segment
  /// a–b, in pixels at `middle` whichever way it points: so the error does not depend on which
  /// way the surface faces, and a turning object keeps its triangles (keepsTarget). 0 when any
  /// of them is behind the camera (invisible, and its scale is meaningless).
  static double chordError(const ProjectedPoint& a, const ProjectedPoint& b, const ProjectedPoint& middle) {
    if (!a.inFront || !b.inFront || !middle.inFront) return 0.0;
    return glm::length(0.5 * (a.world + b.world) - middle.world) * middle.pixelsPerUnit;
  }

  /// The midpoints of a cell's sides (bottom, right, top, left) its parent already evaluated.
  using KnownSides = std::array<const ProjectedPoint*, 4>;

  // Corners 0..3 at (i0, j0), (i1, j0), (i1, j1), (i0, j1).
  void refine(Worker& worker, std::uint32_t face, std::int64_t i0, std::int64_t j0, std::int64_t size,
              const ProjectedPoint (&c)[4], const KnownSides& known) const {
    if (size <= smallestCell) {
      worker.cells.push_back({face, i0, j0, size});
      return;
    }
    const std::int64_t h = size / 2;
    const auto side = [&](int k, std::int64_t i, std::int64_t j) {
      return known[k] != nullptr ? *known[k] : evaluate(worker, face, i, j);
    };
    const ProjectedPoint bottom = side(0, i0 + h, j0);
    const ProjectedPoint right = side(1, i0 + size, j0 + h);
    const ProjectedPoint top = side(2, i0 + h, j0 + size);
    const ProjectedPoint left = side(3, i0, j0 + h);
    const ProjectedPoint centre = evaluate(worker, face, i0 + h, j0 + h);
    // Nothing to refine where all samples lie beyond one side of the view.
    const unsigned outsideAll = c[0].outside & c[1].outside & c[2].outside & c[3].outside & bottom.outside &
                                right.outside & top.outside & left.outside & centre.outside;
    const double error =
        std::max({chordError(c[0], c[1], bottom), chordError(c[1], c[2], right), chordError(c[2], c[3], top),
                  chordError(c[3], c[0], left), chordError(c[0], c[2], centre), chordError(c[1], c[3], centre),
                  chordError(bottom, top, centre), chordError(left, right, centre)});
    if (outsideAll != 0) {
      worker.culled.push_back({c[0].world, c[1].world, c[2].world, c[3].world, bottom.world, right.world, top.world,
                               left.world, centre.world});
      worker.cells.push_back({face, i0, j0, size});
      return;
    }
    if (error <= double(settings.maxPixelError)) {
      for (const ProjectedPoint* sample : {&c[0], &c[1], &c[2], &c[3], &bottom, &right, &top, &left, &centre})
        worker.measuredBehindCamera |= !sample->inFront;
      worker.cells.push_back({face, i0, j0, size});
      return;
    }
    // The midpoints of the four sides the children share, evaluated once for both neighbours
    // (children of the smallest size test nothing).
    ProjectedPoint shared[4];  // between children 0–1, 1–2, 2–3, 3–0
    KnownSides known0{}, known1{}, known2{}, known3{};
    if (h > smallestCell) {
      const std::int64_t q = h / 2;
      shared[0] = evaluate(worker, face, i0 + h, j0 + q);
      shared[1] = evaluate(worker, face, i0 + h + q, j0 + h);
      shared[2] = evaluate(worker, face, i0 + h, j0 + h + q);
      shared[3] = evaluate(worker, face, i0 + q, j0 + h);
      known0 = {nullptr, &shared[0], &shared[3], nullptr};
      known1 = {nullptr, nullptr, &shared[1], &shared[0]};
      known2 = {&shared[1], nullptr, nullptr, &shared[2]};
      known3 = {&shared[3], &shared[2], nullptr, nullptr};
    }
    refine(worker, face, i0, j0, h, {c[0], bottom, centre, left}, known0);
    refine(worker, face, i0 + h, j0, h, {bottom, c[1], right, centre}, known1);
    refine(worker, face, i0 + h, j0 + h, h, {centre, right, c[2], top}, known2);
    refine(worker, face, i0, j0 + h, h, {left, centre, top, c[3]}, known3);
  }

  void refineFaces(Worker& worker, std::size_t begin, std::size_t end) const {
    worker.cells.clear();
    worker.culled.clear();
    worker.measuredBehindCamera = false;
    worker.positionEvaluations = 0;
    for (auto face = std::uint32_t(begin); face < end; ++face) {
      detail::yieldToForeground();
      const ProjectedPoint corners[4] = {evaluate(worker, face, 0, 0), evaluate(worker, face, kGrid, 0),
                                         evaluate(worker, face, kGrid, kGrid), evaluate(worker, face, 0, kGrid)};
      refine(worker, face, 0, 0, kGrid, corners, {});
    }
  }

  /// Concatenates the workers' leaves in face order and indexes them by face.
  void mergeCells() {
    cells.clear();
    culled.clear();
    keepable = true;
    for (const Worker& worker : workers) {
      cells.insert(cells.end(), worker.cells.begin(), worker.cells.end());
      culled.insert(culled.end(), worker.culled.begin(), worker.culled.end());
      keepable &= !worker.measuredBehindCamera;
      statistics.positionEvaluations += worker.positionEvaluations;
    }
    firstCellOfFace.assign(surface->ptexFaceCount() + 1, cells.size());
    for (std::size_t c = cells.size(); c-- > 0;) firstCellOfFace[cells[c].face] = c;
    statistics.cells = cells.size();
  }

  /// Collects the corners of cells on every line (face boundary), from all faces.
  void collectLinePoints() {
    linePoints.resize(sides->lineCount());
    for (auto& points : linePoints) points.clear();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (c % kCellsBetweenYields == 0) detail::yieldToForeground();
      const Cell& cell = cells[c];
      const std::int64_t i1 = cell.i0 + cell.size, j1 = cell.j0 + cell.size;
      const auto add = [&](int side, std::int64_t from, std::int64_t to) {
        const detail::SideOnLine& s = sides->side(cell.face, side);
        linePoints[s.line].push_back(s.toLine(from));
        linePoints[s.line].push_back(s.toLine(to));
      };
      if (cell.j0 == 0) add(0, cell.i0, i1);
      if (i1 == kGrid) add(1, cell.j0, j1);
      if (j1 == kGrid) add(2, cell.i0, i1);
      if (cell.i0 == 0) add(3, cell.j0, j1);
    }
    for (std::size_t l = 0; l < linePoints.size(); ++l) {
      if (l % kLinesBetweenYields == 0) detail::yieldToForeground();
      std::vector<std::int64_t>& points = linePoints[l];
      std::sort(points.begin(), points.end());
      points.erase(std::unique(points.begin(), points.end()), points.end());
    }
  }

  /// Appends the points strictly between `from` and `to` on a side of a cell, in that order.
  /// `fixed` is the coordinate that does not vary (j for horizontal sides, i for vertical).
  void appendBetween(Worker& worker, std::uint32_t face, bool horizontal, std::int64_t fixed, std::int64_t from,
                     std::int64_t to) const {
    std::vector<GridPoint>& polygon = worker.polygon;
    const std::int64_t low = std::min(from, to), high = std::max(from, to);
    const std::size_t start = polygon.size();
    const auto push = [&](std::int64_t varying) {
      polygon.push_back(horizontal ? GridPoint{varying, fixed} : GridPoint{fixed, varying});
    };
    const bool onBoundary = fixed == 0 || fixed == kGrid;
    if (onBoundary) {
      const int side = horizontal ? (fixed == 0 ? 0 : 2) : (fixed == 0 ? 3 : 1);
      const detail::SideOnLine& s = sides->side(face, side);
      const std::int64_t a = s.toLine(low), b = s.toLine(high);
      const auto& points = linePoints[s.line];
      auto first = std::upper_bound(points.begin(), points.end(), std::min(a, b));
      auto last = std::lower_bound(points.begin(), points.end(), std::max(a, b));
      for (auto it = first; it < last; ++it) push(s.fromLine(*it));
      // Line order follows the line; make it ascending in the face coordinate first.
      if (s.scale < 0) std::reverse(polygon.begin() + std::ptrdiff_t(start), polygon.end());
    } else {
      const auto& list = horizontal ? worker.rows : worker.columns;
      auto first = std::upper_bound(list.begin(), list.end(), std::pair{fixed, low});
      auto last = std::lower_bound(list.begin(), list.end(), std::pair{fixed, high});
      for (auto it = first; it < last; ++it) push(it->second);
    }
    if (from > to) std::reverse(polygon.begin() + std::ptrdiff_t(start), polygon.end());
  }

  void emitTriangle(Worker& worker, std::uint32_t face, GridPoint a, GridPoint b, GridPoint c) const {
    for (const GridPoint& p : {a, b, c}) worker.corners.push_back({sides->name(face, p.i, p.j), face, p});
  }

  void triangulateFace(Worker& worker, std::uint32_t face) const {
    auto& rows = worker.rows;
    auto& columns = worker.columns;
    auto& polygon = worker.polygon;
    rows.clear();
    columns.clear();
    for (std::size_t c = firstCellOfFace[face]; c < firstCellOfFace[face + 1]; ++c) {
      const Cell& cell = cells[c];
      for (std::int64_t dj : {std::int64_t(0), cell.size})
        for (std::int64_t di : {std::int64_t(0), cell.size}) {
          rows.emplace_back(cell.j0 + dj, cell.i0 + di);
          columns.emplace_back(cell.i0 + di, cell.j0 + dj);
        }
    }
    for (auto* list : {&rows, &columns}) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    for (std::size_t c = firstCellOfFace[face]; c < firstCellOfFace[face + 1]; ++c) {
      const Cell& cell = cells[c];
      const std::int64_t i0 = cell.i0, j0 = cell.j0, i1 = i0 + cell.size, j1 = j0 + cell.size;
      // The cell's boundary, counter-clockwise in (u, v), with its neighbours' extra points.
      polygon.clear();
      polygon.push_back({i0, j0});
      appendBetween(worker, face, true, j0, i0, i1);
      polygon.push_back({i1, j0});
      appendBetween(worker, face, false, i1, j0, j1);
      polygon.push_back({i1, j1});
      appendBetween(worker, face, true, j1, i1, i0);
      polygon.push_back({i0, j1});
      appendBetween(worker, face, false, i0, j1, j0);
      if (polygon.size() == 4) {
        emitTriangle(worker, face, polygon[0], polygon[1], polygon[2]);
        emitTriangle(worker, face, polygon[0], polygon[2], polygon[3]);
        continue;
      }
      const GridPoint centre{i0 + cell.size / 2, j0 + cell.size / 2};
      for (std::size_t k = 0; k < polygon.size(); ++k)
        emitTriangle(worker, face, centre, polygon[k], polygon[(k + 1) % polygon.size()]);
    }
  }

  void triangulateFaces(Worker& worker, std::size_t begin, std::size_t end) const {
    worker.corners.clear();
    // Most cells make 2 to 4 triangles: room for 3 each spares the growing vector's copies
    // into fresh memory, which is dear where page faults are (see Preparation::warm).
    worker.corners.reserve((firstCellOfFace[end] - firstCellOfFace[begin]) * 9);
    for (auto face = std::uint32_t(begin); face < end; ++face) {
      detail::yieldToForeground();
      triangulateFace(worker, face);
    }
  }

  std::uint32_t vertexFor(const Corner& corner) {
    const auto [location, newLocation] = locationIndex.insert(corner.name.location);
    if (newLocation) locations.push_back({corner.face, corner.point, std::uint32_t(vertices.size()), kNoVertex});
    if (corner.name.uvTag == 0) {  // no second lookup for the common case
      std::uint32_t& untagged = locations[location].untaggedVertex;
      if (untagged == kNoVertex) {
        untagged = std::uint32_t(vertices.size());
        vertices.push_back({location, corner.face, corner.point});
      }
      return untagged;
    }
    const std::uint64_t key = (std::uint64_t(location) << 32) | corner.name.uvTag;
    const auto [slot, newSlot] = vertexIndex.insert(key);
    if (newSlot) {
      taggedVertices.push_back(std::uint32_t(vertices.size()));
      vertices.push_back({location, corner.face, corner.point});
    }
    return taggedVertices[slot];
  }

  /// Numbers vertices in order of first use over all workers' corners, in face order: the
  /// numbering a single thread gives.
  void numberVertices(TessellatedMesh& mesh) {
    std::size_t cornerCount = 0;
    for (const Worker& worker : workers) cornerCount += worker.corners.size();
    // About 1 limit point per 6 corners on a fine mesh; the maps grow if more come.
    locationIndex.clear(cornerCount / 4);
    vertexIndex.clear();
    taggedVertices.clear();
    locations.clear();
    vertices.clear();
    mesh.indices.resize(cornerCount);
    mesh.trianglePtexFaces.clear();
    mesh.cornerPtexCoordinates.clear();
    std::size_t next = 0;
    for (const Worker& worker : workers)
      for (const Corner& corner : worker.corners) {
        if (next % kCornersBetweenYields == 0) detail::yieldToForeground();
        mesh.indices[next++] = vertexFor(corner);
      }
    if (!settings.keepPtexCoordinates) return;
    for (const Worker& worker : workers)
      for (std::size_t k = 0; k < worker.corners.size(); ++k) {
        const Corner& corner = worker.corners[k];
        mesh.cornerPtexCoordinates.emplace_back(double(corner.point.i) / double(kGrid),
                                                double(corner.point.j) / double(kGrid));
        if (k % 3 == 0) mesh.trianglePtexFaces.push_back(corner.face);
      }
  }

  /// Evaluates the vertices at their ptex points: all of them (`uvsToo`, a new tessellation),
  /// or those on faces whose surface has changed since the last evaluation, leaving mesh.uvs and
  /// weldedVertex as they are (a moved cage moves neither).
  void evaluateVertices(TessellatedMesh& mesh, unsigned threads, bool uvsToo) {
    const std::size_t count = vertices.size();
    const bool uvs = uvsToo && surface->hasUvs();
    staleLocations.clear();
    for (std::size_t l = 0; l < locations.size(); ++l)
      if (uvsToo || surface->changedAt(locations[l].face) > evaluatedRevision)
        staleLocations.push_back(std::uint32_t(l));
    evaluatedRevision = surface->revision();
    statistics.pointsEvaluated = staleLocations.size();
    pointPositions.resize(locations.size());
    if (uvsToo) inverseSquaredScales.resize(locations.size());
    mesh.positions.resize(count);
    mesh.normals.resize(count);
    mesh.meanCurvature.resize(count);
    if (uvsToo) {
      mesh.weldedVertex.resize(count);
      mesh.uvs.resize(uvs ? count : 0);
    }
    const auto toUv = [](std::int64_t coordinate) { return double(coordinate) / double(kGrid); };
    const std::size_t stale = staleLocations.size();
    detail::forEachRange(stale, detail::workerCount(stale, threads, kMinPointsPerWorker),
                         [&](std::size_t, std::size_t begin, std::size_t end) {
                           for (std::size_t k = begin; k < end; ++k) {
                             if (k % kPointsBetweenYields == 0) detail::yieldToForeground();
                             const std::uint32_t l = staleLocations[k];
                             const Location& location = locations[l];
                             const double u = toUv(location.point.i), v = toUv(location.point.j);
                             const LimitSample sample = uvs ? surface->evaluate(location.face, u, v)
                                                            : surface->evaluateShape(location.face, u, v);
                             const std::uint32_t first = location.firstVertex;
                             pointPositions[l] = glm::dvec3(sample.position);
                             // The scales a kept tessellation is measured against (keepsTarget).
                             if (uvsToo) {
                               const double scale = projector.project(pointPositions[l]).pixelsPerUnit;
                               inverseSquaredScales[l] = 1.0 / (scale * scale);
                             }
                             mesh.positions[first] = sample.position;
                             mesh.normals[first] = sample.normal;
                             mesh.meanCurvature[first] = sample.curvature.mean;
                             if (uvs) mesh.uvs[first] = sample.uv;
                           }
                         });
    // The other sides of UV seams: the same limit point, their own face's UVs.
    const auto copySeams = [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        const VertexSource& source = vertices[v];
        const std::uint32_t first = locations[source.location].firstVertex;
        if (uvsToo) mesh.weldedVertex[v] = first;
        if (first == v) continue;
        mesh.positions[v] = mesh.positions[first];
        mesh.normals[v] = mesh.normals[first];
        mesh.meanCurvature[v] = mesh.meanCurvature[first];
        if (uvs) mesh.uvs[v] = surface->evaluateUv(source.face, toUv(source.point.i), toUv(source.point.j));
      }
    };
    // Copies alone are not worth a thread.
    if (uvs)
      detail::forEachRange(count, detail::workerCount(count, threads, kMinPointsPerWorker), copySeams);
    else
      copySeams(0, 0, count);
    statistics.limitPoints = locations.size();
  }

  void tessellate(const ScreenView& view, TessellatedMesh& mesh, unsigned threads) {
    statistics = {};
    recentGrowthCount = 0;
    projector = Projector(glm::dmat4(view.viewProjection), glm::dvec2(view.viewportSize));
    const std::size_t faces = surface->ptexFaceCount();
    const std::size_t workerTotal = detail::workerCount(faces, threads, kMinFacesPerWorker);
    // Faces near the camera or the silhouette split far more than the rest, and they sit
    // together in face order: small interleaved chunks share them between the workers.
    const std::size_t chunks = workerTotal == 1 ? 1 : workerTotal * kChunksPerWorker;
    workers.resize(chunks);
    detail::forEachChunk(faces, chunks, workerTotal, [&](std::size_t c, std::size_t begin, std::size_t end) {
      refineFaces(workers[c], begin, end);
    });
    mergeCells();
    collectLinePoints();
    detail::forEachChunk(faces, chunks, workerTotal, [&](std::size_t c, std::size_t begin, std::size_t end) {
      triangulateFaces(workers[c], begin, end);
    });
    numberVertices(mesh);
    evaluateVertices(mesh, threads, true);
    // A point behind the camera has no scale (0), so no finite inverse.
    keepable &= std::none_of(inverseSquaredScales.begin(), inverseSquaredScales.end(),
                             [](double inverse) { return std::isinf(inverse); });
  }

  /// The largest growth of any point's scale from the view tessellated for to `view` (see
  /// keepsTarget), or nothing when the triangles cannot be kept in `view` whatever it is: no
  /// tessellation to keep, an error left unmeasured behind the camera, a point now behind it, or
  /// a cell left coarse outside the view that has come into it.
  std::optional<double> scaleGrowth(const ScreenView& view, unsigned threads) const {
    if (!keepable || inverseSquaredScales.empty()) return std::nullopt;
    const Projector candidate(glm::dmat4(view.viewProjection), glm::dvec2(view.viewportSize));
    const std::size_t count = pointPositions.size();
    const std::size_t workers = detail::workerCount(count, threads, kMinPointsPerWorker);
    // Per range, combined after: the largest of the ranges' largest is the same whatever the split.
    std::vector<std::optional<double>> largestPerRange(workers);
    detail::forEachRange(count, workers, [&](std::size_t w, std::size_t begin, std::size_t end) {
      largestPerRange[w] = candidate.largestSquaredGrowth(std::span(pointPositions).subspan(begin, end - begin),
                                                          std::span(inverseSquaredScales).subspan(begin, end - begin));
    });
    double largestSquared = 0.0;
    for (const std::optional<double>& largest : largestPerRange) {
      if (!largest) return std::nullopt;
      largestSquared = std::max(largestSquared, *largest);
    }
    const double largestGrowth = std::sqrt(largestSquared);
    if (!keepsWithin(largestGrowth)) return largestGrowth;  // refused whatever the culled cells say
    // The coarse cells outside the view must stay outside it: the same test refine made.
    for (const CulledSamples& samples : culled) {
      unsigned outsideAll = ~0u;
      for (const glm::dvec3& sample : samples) outsideAll &= candidate.project(sample).outside;
      if (outsideAll == 0) return std::nullopt;
    }
    return largestGrowth;
  }

  /// Records a kept call's scale growth and says whether the next tessellation should be
  /// prepared now (see kGrowthSpan).
  bool recordGrowthAndPredictLoss(double growth) {
    std::rotate(recentGrowth.begin(), recentGrowth.begin() + 1, recentGrowth.end());
    recentGrowth.back() = growth;
    recentGrowthCount = std::min(recentGrowthCount + 1, recentGrowth.size());
    if (growth > 1.0 + kPrepareErrorGrowth || growth < kPrepareFinestScale) return true;
    if (recentGrowthCount < recentGrowth.size()) return false;
    const double rate = (growth - recentGrowth.front()) / double(kGrowthSpan);
    return growth + 2.0 * kPreparedCalls * rate > 1.0 + kKeptErrorGrowth;
  }
};

Result<AdaptiveTessellator> AdaptiveTessellator::create(const LimitSurface& surface,
                                                        const TessellationSettings& settings) {
  if (!std::isfinite(settings.maxPixelError) || !(settings.maxPixelError > 0.0f))
    return fail("the tessellation's pixel error target must be a positive number, not " +
                std::to_string(settings.maxPixelError));
  if (settings.maxDepth < 1 || settings.maxDepth > detail::kMaxDepth)
    return fail("the tessellation depth " + std::to_string(settings.maxDepth) + " is outside 1.." +
                std::to_string(detail::kMaxDepth));
  return AdaptiveTessellator(
      std::make_unique<Impl>(surface, settings, std::make_shared<const detail::PtexSides>(surface.cage())));
}

/// The next tessellation, which update prepares in the background from a snapshot of the
/// surface. Once adopted, it holds the storage of the tessellation it replaced, for the next.
struct AdaptiveTessellator::Preparation {
  std::optional<LimitSurface> snapshot;
  std::unique_ptr<Impl> tessellation;
  TessellatedMesh mesh;
  bool pending = false;  ///< started and not yet adopted or dropped
  int calls = 0;         ///< update calls since it started
  std::jthread thread;   ///< declared last, so joined first

  ~Preparation() { finish(); }  // whatever foreground work runs meanwhile

  /// Tessellates a snapshot of the surface for `view` in the background, to be adopted
  /// (`pending`) or only to warm the storage (`warm`).
  void run(const Impl& current, const ScreenView& view, unsigned threads, bool toAdopt) {
    finish();
    if (snapshot)
      *snapshot = *current.surface;  // in the storage of the last
    else
      snapshot.emplace(*current.surface);
    if (!tessellation) tessellation = std::make_unique<Impl>(*snapshot, current.settings, current.sides);
    tessellation->surface = &*snapshot;
    pending = toAdopt;
    calls = 0;
    auto work = [this, view, threads] { tessellation->tessellate(view, mesh, threads); };
    try {
      thread = std::jthread([work] {
        const detail::BackgroundScope background;
        work();
      });
    } catch (const std::system_error&) {
      work();  // no thread to be had: the same tessellation, made now
    }
  }

  void start(const Impl& current, const ScreenView& view, unsigned threads) { run(current, view, threads, true); }

  /// Tessellates the surface for `view` in the background and drops the result, so that
  /// the first tessellation prepared for adoption finds its storage allocated and touched: page
  /// faults make the first tessellation of the head at near several times slower than the next,
  /// longer than the kPreparedCalls frames it has before it is adopted.
  void warm(const Impl& current, const ScreenView& view, unsigned threads) { run(current, view, threads, false); }

  /// Waits for the tessellation to be made.
  void finish() {
    if (thread.joinable()) {
      // The foreground work this is called in must not pause the threads it waits for.
      const detail::WaitingForBackground waiting;
      thread.join();
    }
    pending = false;
  }
};

AdaptiveTessellator::AdaptiveTessellator(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
AdaptiveTessellator::AdaptiveTessellator(AdaptiveTessellator&&) noexcept = default;
AdaptiveTessellator& AdaptiveTessellator::operator=(AdaptiveTessellator&&) noexcept = default;
AdaptiveTessellator::~AdaptiveTessellator() = default;

void AdaptiveTessellator::tessellate(const ScreenView& view, TessellatedMesh& mesh, unsigned threads) {
  const detail::ForegroundWork foreground(threads);
  if (preparation_) preparation_->finish();  // made for the tessellation this one replaces: dropped
  impl_->tessellate(view, mesh, threads);
}

Result<FrameUpdate> AdaptiveTessellator::update(const ScreenView& view, TessellatedMesh& mesh, unsigned threads) {
  const detail::ForegroundWork foreground(threads);
  if (!preparation_) preparation_ = std::make_unique<Preparation>();
  if (impl_->vertices.empty()) {
    // The background warms its storage: beside this tessellation on one thread, after it on
    // more (finish lets it run on every core); either way before the call returns, so no later
    // frame shares a core with the warming.
    preparation_->warm(*impl_, view, threads);
    impl_->tessellate(view, mesh, threads);  // not tessellate(), which would wait for the warming first
    preparation_->finish();
    return FrameUpdate::kTessellated;
  }
  std::optional<double> growth = impl_->scaleGrowth(view, threads);
  const bool preparing = preparation_->pending;
  if (preparing && (++preparation_->calls >= kPreparedCalls || !keepsWithin(growth))) {
    Preparation& prepared = *preparation_;
    prepared.finish();
    // The prepared tessellation saw the surface as the snapshot was: from here on it reads the
    // surface itself, and evaluateVertices moves the points on faces that changed since.
    prepared.tessellation->surface = impl_->surface;
    std::swap(impl_, prepared.tessellation);
    std::swap(mesh, prepared.mesh);
    impl_->evaluateVertices(mesh, threads, false);
    growth = impl_->scaleGrowth(view, threads);
    if (keepsWithin(growth)) return FrameUpdate::kAdopted;
  }
  if (!keepsWithin(growth)) {
    tessellate(view, mesh, threads);
    return FrameUpdate::kTessellated;
  }
  if (auto updated = updateVertices(mesh, threads); !updated) return std::unexpected(updated.error());
  if (!impl_->recordGrowthAndPredictLoss(*growth) || preparing) return FrameUpdate::kKept;
  preparation_->start(*impl_, view, threads);
  return FrameUpdate::kPrepared;
}

Result<void> AdaptiveTessellator::updateVertices(TessellatedMesh& mesh, unsigned threads) {
  const detail::ForegroundWork foreground(threads);
  if (impl_->vertices.empty() || mesh.positions.size() != impl_->vertices.size())
    return fail("updating the vertices of a tessellation: the mesh has " + std::to_string(mesh.positions.size()) +
                " vertices, the last tessellation " + std::to_string(impl_->vertices.size()));
  impl_->evaluateVertices(mesh, threads, false);
  return {};
}

bool AdaptiveTessellator::keepsTarget(const ScreenView& view) const {
  return keepsWithin(impl_->scaleGrowth(view, 1));
}

const TessellationStatistics& AdaptiveTessellator::statistics() const {
  return impl_->statistics;
}

const TessellationSettings& AdaptiveTessellator::settings() const {
  return impl_->settings;
}

}  // namespace mane::subdiv
