#pragma once
// A Catmull-Clark control cage: positions and polygonal faces (quads, triangles, n-gons),
// with optional edge creases. Plain data; `validateCage` checks it before OpenSubdiv sees it.

#include <cstdint>
#include <vector>

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

struct Cage {
  std::vector<glm::vec3> positions;         ///< metres
  std::vector<std::uint32_t> faceSizes;     ///< vertices per face, ≥ 3
  std::vector<std::uint32_t> faceVertices;  ///< all faces' vertex indices, counter-clockwise
  std::vector<Crease> creases;
};

/// Rejects cages OpenSubdiv cannot refine meaningfully, naming the face, vertex or edge: a
/// face with fewer than 3 vertices, an index out of range, a face that repeats a vertex, a
/// face with zero area, an edge used by more than two faces (non-manifold), two faces that
/// traverse a shared edge in the same direction (inconsistent winding), a crease on an edge
/// the cage does not have, and non-finite positions.
Result<void> validateCage(const Cage& cage);

}  // namespace mane::subdiv
