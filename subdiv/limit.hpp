#pragma once
// The Catmull-Clark limit surface of a cage, evaluated exactly (up to the end caps) at any
// point of any ptex face: feature-adaptive refinement with OpenSubdiv (Far::TopologyRefiner
// ::RefineAdaptive) isolates extraordinary vertices, creases and UV seams; a patch table
// covers every face with bicubic patches, and a PatchMap finds the patch under (face, u, v).
// The topology is built once; a deforming cage only re-runs the precomputed stencils.
//
// Parametrisation (OpenSubdiv's ptex faces): a quad is one ptex face with (0,0) at its first
// vertex, u towards the second and v towards the last. An n-gon (n ≠ 4) is split into n ptex
// faces; sub-face j has (0,0) at the face's vertex j, (1,0) at the midpoint of the edge from
// vertex j to j+1, (1,1) at the face's centre and (0,1) at the midpoint of the edge from
// vertex j−1 to j. Ptex faces are numbered in cage face order.

#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "subdiv/cage.hpp"
#include "subdiv/curvature.hpp"

namespace mane::subdiv {

/// Everything the limit surface says about one of its points. Derivatives are taken with
/// respect to the ptex face's (u, v) ∈ [0,1]², so they are in metres per unit parameter.
struct LimitSample {
  glm::vec3 position{0.0f};  ///< metres
  glm::vec3 du{0.0f};        ///< ∂S/∂u
  glm::vec3 dv{0.0f};        ///< ∂S/∂v
  glm::vec3 duu{0.0f};       ///< ∂²S/∂u²
  glm::vec3 duv{0.0f};       ///< ∂²S/∂u∂v
  glm::vec3 dvv{0.0f};       ///< ∂²S/∂v²
  glm::vec3 normal{0.0f};    ///< normalize(∂u × ∂v): outward for counter-clockwise faces
  glm::vec2 uv{0.0f};        ///< the cage's texture coordinates, interpolated; 0 without UVs
  SurfaceCurvature curvature;
};

/// How the patches next to extraordinary vertices (valence ≠ 4), which have no closed-form
/// bicubic limit, are approximated at the last isolation level.
enum class EndCap {
  /// Gregory patches (OpenSubdiv's recommended default): they interpolate the exact limit
  /// position and tangent plane at the extraordinary vertex and join their neighbours with
  /// tangent continuity, so normals have no visible seams; curvature there is approximate.
  kGregory,
  /// B-spline patches from a regularised one-ring: cheaper, but the surface only
  /// approximates the limit position at the extraordinary vertex.
  kBSpline,
};

struct LimitSurfaceSettings {
  /// Adaptive refinement depth (1..10). Each level halves the region an end cap covers
  /// around an extraordinary vertex, and semi-sharp creases of sharpness s need ⌈s⌉ levels
  /// to be exact; every level adds refined vertices, which cost time on each cage update.
  int maxIsolationLevel = 4;
  EndCap endCap = EndCap::kGregory;
};

/// Where a ptex face comes from.
struct PtexFace {
  std::uint32_t cageFace = 0;
  int subFace = -1;  ///< −1 for a quad, else the corner j of an n-gon (see the header comment)
};

/// The ptex faces across each edge of a ptex face (edges 0..3: v = 0, u = 1, v = 1, u = 0),
/// −1 on a boundary, and which edge of that neighbour it is (OpenSubdiv's
/// Far::PtexIndices::GetAdjacency).
struct PtexAdjacency {
  std::array<int, 4> faces{-1, -1, -1, -1};
  std::array<int, 4> edges{-1, -1, -1, -1};
};

class LimitSurface {
public:
  /// Validates `cage` (see validateCage), refines it adaptively and builds the patch table,
  /// the patch map, the stencils that update refined and local points from cage positions,
  /// and the UVs' face-varying patches. Errors: an invalid cage or settings, or OpenSubdiv
  /// rejecting the topology.
  [[nodiscard]] static Result<LimitSurface> create(const Cage& cage, const LimitSurfaceSettings& settings = {});

  /// A copy is a snapshot of the surface as it is now: it shares the topology, patches, stencils
  /// and UVs, and has its own cage positions and points (assigning one reuses their storage).
  /// Its revisions go on from the original's, so that evaluations of a snapshot can be compared
  /// with later changes to the original (changedAt). For evaluating a shape on another thread
  /// while the surface moves on.
  LimitSurface(const LimitSurface& other);
  LimitSurface& operator=(const LimitSurface& other);
  LimitSurface(LimitSurface&&) noexcept;
  LimitSurface& operator=(LimitSurface&&) noexcept;
  ~LimitSurface();

  /// Moves the cage's vertices (same count and order as the cage it was built from) and
  /// recomputes the refined and local points from the stencils; topology, patches and UVs
  /// are kept. `threads` ≥ 1 workers (0 counts as 1) share the stencils; the points do not
  /// depend on it, bit for bit. Errors: a wrong vertex count or a non-finite position.
  [[nodiscard]] Result<void> updatePositions(std::span<const glm::vec3> cagePositions, unsigned threads = 1);

  /// How many times updatePositions has moved the cage (0 as built).
  [[nodiscard]] std::uint64_t revision() const;
  /// The revision whose updatePositions last changed the surface over `ptexFace`: the last that
  /// moved a cage vertex of a face sharing a vertex with its cage face (the limit surface over a
  /// face depends on no others). 0 when none has. Evaluations there since are still exact.
  [[nodiscard]] std::uint64_t changedAt(std::uint32_t ptexFace) const;

  /// Full evaluation at (u, v) ∈ [0,1]² of `ptexFace` (< ptexFaceCount(); u and v are
  /// clamped to the face).
  [[nodiscard]] LimitSample evaluate(std::uint32_t ptexFace, double u, double v) const;
  /// `evaluate` without the texture coordinates, which a deforming cage does not move.
  [[nodiscard]] LimitSample evaluateShape(std::uint32_t ptexFace, double u, double v) const;
  /// The position alone: cheaper, for error estimates.
  [[nodiscard]] glm::dvec3 evaluatePosition(std::uint32_t ptexFace, double u, double v) const;
  /// The texture coordinates alone.
  [[nodiscard]] glm::vec2 evaluateUv(std::uint32_t ptexFace, double u, double v) const;

  [[nodiscard]] std::uint32_t ptexFaceCount() const;
  [[nodiscard]] PtexFace ptexFace(std::uint32_t ptexFace) const;
  /// The first ptex face of a cage face (an n-gon's sub-faces follow it).
  [[nodiscard]] std::uint32_t firstPtexFace(std::uint32_t cageFace) const;
  [[nodiscard]] PtexAdjacency ptexAdjacency(std::uint32_t ptexFace) const;

  /// The cage with its current positions.
  [[nodiscard]] const Cage& cage() const;
  [[nodiscard]] bool hasUvs() const;
  /// Patches in the table and points (cage + refined + local) the stencils maintain.
  [[nodiscard]] std::size_t patchCount() const;
  [[nodiscard]] std::size_t controlPointCount() const;

private:
  struct Impl;
  explicit LimitSurface(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace mane::subdiv
