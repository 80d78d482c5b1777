#pragma once
// View-dependent tessellation of a limit surface (Bunnell, "Adaptive Tessellation of
// Subdivision Surfaces with Displacement Mapping", GPU Gems 2, ch. 7): every ptex face is
// split as a quadtree until, for each side, diagonal and midline of a cell, the distance
// between the straight segment's midpoint and the limit surface's midpoint, projected to the
// screen, is below a target number of pixels. "Projected" takes the distance at its largest
// magnification there, whatever its direction: an upper bound of its on-screen length that
// does not change as the surface turns, so a turning object keeps its triangles.
//
// No cracks: a point on a side shared by two cells or two faces has one name (a cage vertex,
// a parameter along a cage edge or an n-gon spoke, or a grid point inside a face), so both
// sides use the same vertex. A cell whose neighbour was split further takes the neighbour's
// points on their common side into its own triangulation (a fan around its centre), so the
// mesh has no T-junctions either: every interior edge has exactly two triangles.

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "subdiv/limit.hpp"

namespace mane::subdiv {

/// The camera the error is measured for.
struct ScreenView {
  /// World (the cage's space) → clip space; visible points have |x|, |y| ≤ w and w > 0.
  glm::mat4 viewProjection{1.0f};
  glm::vec2 viewportSize{1280.0f, 720.0f};  ///< pixels
};

struct TessellationSettings {
  /// The largest allowed projected distance, in pixels, between a cell's straight side (or
  /// diagonal or midline) and the limit surface at its midpoint (in any direction: see above).
  float maxPixelError = 1.0f;
  /// The most times a ptex face side is halved (1..10): at most 2^maxDepth segments.
  int maxDepth = 10;
  /// Keep, per triangle, its ptex face and the ptex (u, v) of its corners (for tests and
  /// texture-space tools); off for rendering.
  bool keepPtexCoordinates = false;
};

/// A triangle mesh of the limit surface, counter-clockwise seen from outside.
struct TessellatedMesh {
  std::vector<glm::vec3> positions;    ///< metres
  std::vector<glm::vec3> normals;      ///< unit, from the limit surface's ∂u × ∂v
  std::vector<glm::vec2> uvs;          ///< the cage's UVs; empty when it has none
  std::vector<float> meanCurvature;    ///< 1/metre, positive where convex (LimitSample)
  std::vector<std::uint32_t> indices;  ///< 3 per triangle
  /// Per vertex, the first vertex at the same limit point: itself except where a UV seam
  /// splits a point into one vertex per side (with identical positions and normals).
  std::vector<std::uint32_t> weldedVertex;
  /// With keepPtexCoordinates: per triangle its ptex face, per triangle corner its (u, v).
  std::vector<std::uint32_t> trianglePtexFaces;
  std::vector<glm::vec2> cornerPtexCoordinates;

  [[nodiscard]] std::size_t triangleCount() const { return indices.size() / 3; }
};

/// What the last tessellate call did.
struct TessellationStatistics {
  std::size_t cells = 0;  ///< quadtree leaves
  std::size_t positionEvaluations = 0;
  std::size_t limitPoints = 0;  ///< distinct limit points (vertices before UV seams)
  /// Limit points evaluated in full by the last tessellate (all) or updateVertices (those on
  /// faces whose surface the cage's last moves changed: LimitSurface::changedAt).
  std::size_t pointsEvaluated = 0;
};

/// What AdaptiveTessellator::update did.
enum class FrameUpdate {
  kKept,         ///< kept the last triangles, their vertices moved with the surface
  kPrepared,     ///< kept them, and began preparing the next tessellation on a thread of its own
  kAdopted,      ///< made the prepared tessellation the current one
  kTessellated,  ///< tessellated again itself: there was none yet, or the view changed too fast
};

class AdaptiveTessellator {
public:
  /// Prepares the side tables of `surface`'s ptex faces. The tessellator keeps a pointer to
  /// `surface`, which must outlive it and stay where it is (not be moved); moving its cage
  /// (updatePositions) needs no new tessellator. Errors: a target that is not a positive
  /// finite number, a depth outside 1..10.
  [[nodiscard]] static Result<AdaptiveTessellator> create(const LimitSurface& surface,
                                                          const TessellationSettings& settings = {});

  AdaptiveTessellator(AdaptiveTessellator&&) noexcept;
  AdaptiveTessellator& operator=(AdaptiveTessellator&&) noexcept;
  ~AdaptiveTessellator();

  /// Tessellates the surface as it is now for `view` into `mesh`, reusing its storage (call
  /// once per frame when the camera or the cage moves). `threads` ≥ 1 workers (0 counts as 1)
  /// share the ptex faces and limit points. Deterministic: the same surface and view give the
  /// same mesh, vertex order included, bit for bit whatever `threads` is. A tessellation that
  /// update was preparing is waited for and dropped.
  void tessellate(const ScreenView& view, TessellatedMesh& mesh, unsigned threads = 1);

  /// Moves the vertices of the last tessellation onto the surface as it is now (after
  /// LimitSurface::updatePositions), keeping its triangles: each vertex on a face whose surface
  /// has changed since (LimitSurface::changedAt) is evaluated again at its ptex point; `mesh`
  /// keeps the others, so it must be as the last tessellate or updateVertices left it. For a
  /// deforming cage seen from a still camera, between tessellations: at most about a third of
  /// tessellate's cost, less when only part of the cage moves. The screen error is what the
  /// last tessellate call measured for the shape it saw; the caller tessellates again when the
  /// view or the shape has changed enough for that to matter. Deterministic like tessellate.
  /// Errors: `mesh` is not the last tessellation's output (different vertex count), or there
  /// was none.
  [[nodiscard]] Result<void> updateVertices(TessellatedMesh& mesh, unsigned threads = 1);

  /// Whether the last tessellation still keeps within the target (up to 10 % more, the tests'
  /// bound) seen through `view`, so that tessellate need not run. The error is a world distance
  /// times the pixels per unit at the point, so it holds while no point's scale has grown by
  /// more than 10 %, none has come from behind the camera, and no cell left coarse outside the
  /// view has come into it. A turning or slightly moving object keeps its triangles; one the
  /// camera has come nearer to does not, nor one it has moved away from until every point's
  /// scale is below 0.7 of what it was (too many triangles). Shape changes since (updateVertices)
  /// are not measured. False before any tessellate.
  [[nodiscard]] bool keepsTarget(const ScreenView& view) const;

  /// The per-frame update of a moving surface seen by a moving camera, after
  /// LimitSurface::updatePositions: the last triangles while they keep within the target
  /// (keepsTarget), their vertices moved with the surface (updateVertices). When the growth of the
  /// points' scales, extrapolated from the last few calls, would use up the 10 % allowed within
  /// about ten calls (or has used 7 % of it, or every scale has shrunk below 0.75), it copies the
  /// surface and tessellates the copy for this view in the background, on `threads` threads of its
  /// own that pause while this object's and LimitSurface's calls on more than one thread run, so
  /// that those frames keep every core; on the 5th call after that, or sooner if the kept triangles
  /// stop keeping within the target, it waits for that tessellation, makes it the current one and
  /// moves its vertices to the surface as it is then. It tessellates on the calling threads only
  /// when there is no tessellation yet, or when even the prepared one does not keep within the
  /// target (a camera that jumped). What it does depends on the calls alone (views and surfaces),
  /// never on timing, so the meshes are as deterministic as tessellate's. The first call, which
  /// tessellates, also tessellates once in the background and drops the result, so that the first
  /// prepared tessellation finds its storage ready. Errors: as updateVertices (`mesh` must be what
  /// the last call left).
  [[nodiscard]] Result<FrameUpdate> update(const ScreenView& view, TessellatedMesh& mesh, unsigned threads = 1);

  [[nodiscard]] const TessellationStatistics& statistics() const;
  [[nodiscard]] const TessellationSettings& settings() const;

private:
  struct Impl;
  struct Preparation;
  explicit AdaptiveTessellator(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Preparation> preparation_;  ///< the next tessellation, while update prepares one
};

}  // namespace mane::subdiv
