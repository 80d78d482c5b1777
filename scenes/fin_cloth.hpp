#pragma once
// A fin to simulate as cloth: rays fanning from a root, a membrane folded along them, its edge
// cut back between the rays' tips (the seed's fins are cloth, any mesh made so by constraining
// its edges). Shape holds keep the rays where the body holds them, so that the membrane ripples
// between rays that keep the fin open.

#include <cstdint>
#include <vector>

#include "physics/cloth.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {

/// Four membrane columns between two rays: each ray's ridge then spans a quarter of the gap on
/// either side, narrow enough that smooth normals shade it as a line.
inline constexpr int kFinColumnsPerGap = 4;

struct FinCloth {
  /// Vertex (row, column) is index row · columns + column; row 0 the root, column 0 the first
  /// ray, every `kFinColumnsPerGap`-th column a ray. uv: (column, row) over [0, 1].
  Mesh mesh;
  int columns = 0;
  std::vector<std::uint32_t> base;  ///< rows 0 and 1: what the body holds
  /// Each ray's vertices past the base, held by `FinShape::rayStiffness` there, falling linearly
  /// to half that at the tip.
  std::vector<physics::ClothShapeHold> holds;
};

/// The fin `shape` describes (a valid one: scenes/README.md gives the ranges).
FinCloth makeFin(const FinShape& shape);

}  // namespace mane::scenes
