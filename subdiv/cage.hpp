#pragma once
// A Catmull-Clark control cage: positions and polygonal faces (quads, triangles, n-gons),
// with optional edge creases, corner sharpness and face-varying texture coordinates. Plain
// data; `validateCage` checks it before OpenSubdiv sees it.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::subdiv {

/// A sharp or semi-sharp edge between two cage vertices (OpenSubdiv sharpness: 0 smooth,
/// 10 and above infinitely sharp).
struct Crease {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  float sharpness = 0.0f;
};

/// A sharp or semi-sharp cage vertex (same sharpness scale as `Crease`): the limit surface
/// keeps a point there instead of rounding it off.
struct Corner {
  std::uint32_t vertex = 0;
  float sharpness = 0.0f;
};

/// How the limit surface treats the cage's boundary (OpenSubdiv's Sdc::VtxBoundaryInterpolation;
/// OBJ tag `t interpolateboundary 1/0/0 n` with n = 0, 1, 2).
enum class BoundaryInterpolation {
  kNone,           ///< boundary faces are dropped from the limit surface's support
  kEdgeOnly,       ///< boundary edges are infinitely sharp, corners smooth
  kEdgeAndCorner,  ///< boundary edges and valence-2 corners are infinitely sharp
};

struct Cage {
  std::vector<glm::vec3> positions;         ///< metres (loaders keep their file's units)
  std::vector<std::uint32_t> faceSizes;     ///< vertices per face, ≥ 3
  std::vector<std::uint32_t> faceVertices;  ///< all faces' vertex indices, counter-clockwise
  std::vector<Crease> creases;
  std::vector<Corner> corners;
  /// Face-varying texture coordinates: `faceUvIndices` has one entry per entry of
  /// `faceVertices` indexing `uvs`, or both are empty. Separate indices let a vertex carry
  /// different UVs in different faces (UV seams).
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> faceUvIndices;
  BoundaryInterpolation boundary = BoundaryInterpolation::kEdgeAndCorner;

  [[nodiscard]] bool hasUvs() const { return !faceUvIndices.empty(); }
};

/// What is wrong with a cage, with the element it concerns so that a loader can name the
/// line of its file.
struct CageProblem {
  std::string message;
  std::optional<std::size_t> face;    ///< index into faceSizes
  std::optional<std::size_t> crease;  ///< index into creases
  std::optional<std::size_t> corner;  ///< index into corners
};

/// Finds the first reason OpenSubdiv could not refine `cage` meaningfully, naming the face,
/// vertex or edge: a face with fewer than 3 vertices, an index out of range, a face that
/// repeats a vertex, a face with zero area, an edge used by more than two faces
/// (non-manifold), two faces that traverse a shared edge in the same direction (inconsistent
/// winding), a crease on an edge the cage does not have, a corner on a vertex it does not
/// have, a negative or non-finite sharpness, UV indices that do not match the face vertices
/// or fall outside `uvs`, and non-finite positions or UVs. Empty when the cage is usable.
[[nodiscard]] std::optional<CageProblem> findCageProblem(const Cage& cage);

/// `findCageProblem` as a Result: the problem's message as the error.
[[nodiscard]] Result<void> validateCage(const Cage& cage);

}  // namespace mane::subdiv
