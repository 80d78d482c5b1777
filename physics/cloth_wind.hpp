#pragma once
// Wind on cloth: the pressure of air on each triangle, as on a sail. Each triangle of area A and
// unit normal n, moving with the mean velocity v of its corners in air moving with w, feels
//
//   F = ½ ρ C A (u·n) |u·n| n,   u = w − v,
//
// the dynamic pressure of the air's component across it (a flat plate's normal force, drag
// coefficient C; e.g. Hoerner, "Fluid-Dynamic Drag", 1965, ch. 3), a third of it at each
// corner. A vertex of the cloth weighs σ times a third of the rest area of its triangles (σ the
// cloth's mass per area), so its acceleration is the sum of its corners' forces over that mass:
// a flat sheet square to the wind accelerates at ½ ρ C |w|² / σ everywhere, edges included.
//
// Deterministic: each triangle's force is written to its own slot, and each vertex sums its
// triangles' in a fixed order (the mesh's), whichever thread computes what.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

struct ClothWind {
  glm::vec3 velocity{0.0f};      ///< the air's, world m/s (finite)
  float arealDensity = 0.3f;     ///< σ, kg/m², > 0 (sailcloth: 0.2 to 0.5)
  float dragCoefficient = 1.2f;  ///< C, ≥ 0 (a flat plate square to the flow: about 1.2)
};

/// The density of air, kg/m³ (ISA at sea level).
inline constexpr float kClothAirDensity = 1.225f;

/// The air's push on a whole cloth: what the pins hand on to whatever holds them.
struct WindPush {
  glm::vec3 force{0.0f};   ///< N
  glm::vec3 moment{0.0f};  ///< N m, about the point it was asked about
};

class ClothWindLoad {
public:
  /// For a mesh of `vertexCount` vertices and `triangles` (three indices each, checked by the
  /// cloth), whose rest shape is `rest` (metres). Fails on settings out of range, naming them.
  [[nodiscard]] static Result<ClothWindLoad> create(const ClothWind& wind, std::span<const std::uint32_t> triangles,
                                                    std::span<const glm::vec3> rest);

  /// Fails on a velocity that is not finite.
  [[nodiscard]] Result<void> setVelocity(const glm::vec3& velocity);
  [[nodiscard]] const ClothWind& wind() const { return wind_; }

  /// Each triangle in [first, end)'s force at one corner, from the positions now and a step of
  /// `step` seconds ago.
  void computeForces(std::span<const glm::vec3> positions, std::span<const glm::vec3> previous, float step,
                     std::size_t first, std::size_t end);
  /// The acceleration of vertex `v` from the forces computed last (m/s²).
  [[nodiscard]] glm::vec3 acceleration(std::uint32_t v) const;
  /// The forces computed last, each triangle's acting at its centroid in `positions`, summed in
  /// the triangles' order; the moment about `about`.
  [[nodiscard]] WindPush total(std::span<const glm::vec3> positions, const glm::vec3& about) const;
  [[nodiscard]] std::size_t triangleCount() const { return triangles_.size() / 3; }

private:
  ClothWind wind_;
  std::vector<std::uint32_t> triangles_;
  std::vector<std::uint32_t> vertexTriangleStarts_;  // the triangles of vertex v: [starts[v], starts[v + 1])
  std::vector<std::uint32_t> vertexTriangles_;
  std::vector<float> inverseMass_;      // per vertex, 1/kg
  std::vector<glm::vec3> cornerForce_;  // per triangle, N
};

}  // namespace mane::physics
