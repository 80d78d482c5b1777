#pragma once
// A quad-dominant cage from a triangle cage: pairs of triangles that share an edge become one
// quad (the shared edge removed). Catmull-Clark splits a triangle into three quads around a
// new extraordinary vertex of valence 3, and a vertex of a triangulated mesh has valence
// about 6: a triangle cage makes every limit patch an end cap. Pairing triangles halves the
// faces around most vertices, brings their valence towards 4 and leaves regular bicubic
// patches where the quads meet four at a vertex.
//
// The process is deterministic: candidate pairs are ranked by the quad they would make (its
// worst corner, then the order of the triangles' shared edge in the cage), and taken best
// first while neither triangle is taken.

#include <cstddef>

#include "subdiv/cage.hpp"

namespace mane::subdiv {

struct QuadPairingSettings {
  /// A pair is merged only when every corner of the quad has |cos angle| at most this
  /// (0.8: corners between 36.9° and 143.1°), so the quad is convex and not a sliver.
  float maxCornerCosine = 0.8f;
  /// ... and the two triangles' normals have a cosine of at least this (0.5: folded by at
  /// most 60° along the shared edge).
  float minNormalCosine = 0.5f;
};

struct QuadPairing {
  Cage cage;                  ///< the quads first (in the order they were paired), then the other faces as they were
  std::size_t quads = 0;      ///< made by pairing
  std::size_t triangles = 0;  ///< left unpaired
};

/// Merges pairs of `cage`'s triangles into quads. Only triangles are paired (other faces are
/// kept as they are, after the quads), and only across an edge shared by exactly two faces
/// that is not creased and whose UVs agree on both sides, so the limit surface's UVs keep
/// their seams. Positions, UVs, creases on kept edges, corners and the boundary rule are
/// kept. `cage` must be valid (validateCage).
[[nodiscard]] QuadPairing pairTrianglesIntoQuads(const Cage& cage, const QuadPairingSettings& settings = {});

}  // namespace mane::subdiv
