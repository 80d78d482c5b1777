#pragma once
// Keeps a cloth from passing through itself: each free vertex is kept `thickness` away from the
// cloth's triangles that neither it nor an edge neighbour of it belongs to, on the side of the
// triangle it was on at the start of the step, and each edge as far from the edges near it. This is the point–triangle
// constraint of Müller, Heidelberger, Hennix & Ratcliff 2007 (§4.4), with the side taken from the previous positions as
// Bridson, Fedkiw & Anderson 2002 do. Candidates come from a spatial hash of the triangles' boxes
// (Teschner et al. 2003). It runs on one thread in vertex order, so its result does not depend on
// the thread count.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "physics/particles.hpp"

namespace mane::physics {

class ClothSelfCollision {
public:
  /// `triangles`: three vertex indices each, all below `vertexCount`; `thickness` > 0, metres.
  ClothSelfCollision(std::span<const std::uint32_t> triangles, std::size_t vertexCount, float thickness);

  /// One Gauss–Seidel pass over the free vertices: each vertex found closer than `thickness` to a
  /// triangle, or through it, since the previous positions is moved back out together with the
  /// triangle's corners, by their inverse masses.
  void resolve(Particles& particles);

  [[nodiscard]] float thickness() const noexcept { return thickness_; }

private:
  using Cell = std::array<std::int32_t, 3>;
  /// The cells a box overlaps, `from` to `to` on each axis; `empty` when the box is not finite,
  /// lies too far from the origin or spans too many cells.
  struct CellRange {
    Cell from{}, to{};
    bool empty = true;
  };
  static CellRange cellsOf(const glm::vec3& low, const glm::vec3& high, float inverseCell);

  void hashTriangles(const Particles& particles);
  /// Into candidates_, each once: the triangles whose swept boxes meet the box [low, high].
  void gatherTriangles(const glm::vec3& low, const glm::vec3& high);
  void resolveVertices(Particles& particles);
  void resolveEdges(Particles& particles);
  [[nodiscard]] bool touches(std::uint32_t vertex, std::uint32_t triangle) const;
  /// True when `other` is `vertex` or one of its edge neighbours.
  [[nodiscard]] bool neighbours(std::uint32_t vertex, std::uint32_t other) const;

  std::vector<std::uint32_t> triangles_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges_;  // each once, (low, high)
  std::vector<std::uint32_t> triangleEdges_;                    // per triangle corner k: edge (k, k + 1)
  // Per vertex, sorted: itself and its edge neighbours (rows of neighbourStarts_).
  std::vector<std::uint32_t> neighbourStarts_;
  std::vector<std::uint32_t> neighbours_;
  float thickness_;
  // The spatial hash of the current step: cell size, and per bucket the triangles whose boxes
  // overlap a cell that hashes there (rows of bucketStarts_).
  float cellSize_ = 1.0f;
  std::vector<std::pair<glm::vec3, glm::vec3>> boxes_;
  std::vector<CellRange> ranges_;  // per triangle: the cells its box overlaps
  std::vector<std::uint32_t> bucketStarts_;
  std::vector<std::uint32_t> bucketEntries_;
  std::vector<std::uint32_t> candidates_;
  std::vector<std::uint8_t> layered_;  // per vertex: over or under another layer of the cloth
  std::vector<std::uint32_t> seen_;    // per triangle: the last query that listed it
  std::uint32_t query_ = 0;
};

}  // namespace mane::physics
