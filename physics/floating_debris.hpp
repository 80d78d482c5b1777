#pragma once
// Debris afloat: flat triangles of wood, each three Verlet particles (Jakobsen 2001) held at
// their rest distances, lifted by the water and carried by its orbital motion.
//
// Each corner carries a third of the piece's mass and of its volume, a slab `thickness` deep.
// Its submerged share s is how far it lies under the sea's surface over the thickness, plus one
// half, clamped to [0, 1]; the water pushes it up by g s / d (d the wood's density over the
// water's) and drags it towards the water's velocity at c s per second. In calm water a corner
// rests where s = d: (½ − d) × thickness above the surface. The surface under a piece is found
// once a step at its centroid (OceanWaves::surfaceAt) and taken as the plane of the water's
// normal there for its three corners.
//
// A floating body may stand among them as an ellipsoid (a ship's hull): no piece is strewn where
// a corner would lie inside it, and a corner that drifts in is put back on its surface, along the
// line from its centre.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/ocean_waves.hpp"

namespace mane::physics {

struct FloatingDebrisSettings {
  int pieces = 24;               ///< 0 … 4096
  glm::vec2 centre{0.0f};        ///< (x, z) metres: the pieces are strewn over a disc about it
  float radius = 30.0f;          ///< metres, ≥ 0
  float size = 1.0f;             ///< the pieces' side, metres, > 0 (each between half and all of it)
  float thickness = 0.1f;        ///< metres, > 0
  float relativeDensity = 0.5f;  ///< d: the wood's density over the water's, (0, 1)
  float dragPerSecond = 3.0f;    ///< c, 1/s, ≥ 0
  std::uint64_t seed = 7;        ///< where the pieces lie and how they are cut
  int constraintIterations = 4;  ///< ≥ 1
};

/// An ellipsoid the debris keeps out of: the unit sphere carried into the world by
/// `worldFromUnitSphere`, an invertible affine map (finite, its determinant not 0).
struct DebrisObstacle {
  glm::mat4 worldFromUnitSphere{1.0f};
};

class FloatingDebris {
public:
  /// The pieces, each lying still on the sea's surface at `time`, in the plane of its normal
  /// there, and outside `obstacle` where given (a piece whose corners would fall inside it is
  /// strewn again, up to 16 times, then pushed out where the last try put it). Fails on settings
  /// out of the documented ranges or an obstacle that is not invertible, naming it.
  [[nodiscard]] static Result<FloatingDebris> create(const FloatingDebrisSettings& settings, const OceanWaves& ocean,
                                                     double time, const DebrisObstacle* obstacle = nullptr);

  /// Advances by `dt` seconds (> 0) on `ocean` as it is at `time`, keeping every corner out of
  /// `obstacle` (as it stands at `time`; invertible) where given.
  void step(const OceanWaves& ocean, double time, float dt, const DebrisObstacle* obstacle = nullptr);

  /// The pieces' corners, three per piece.
  [[nodiscard]] std::span<const glm::vec3> corners() const { return positions_; }
  [[nodiscard]] std::span<const glm::vec3> previousCorners() const { return previous_; }
  [[nodiscard]] const FloatingDebrisSettings& settings() const { return settings_; }

private:
  explicit FloatingDebris(const FloatingDebrisSettings& settings) : settings_(settings) {}

  FloatingDebrisSettings settings_;
  std::vector<glm::vec3> positions_;
  std::vector<glm::vec3> previous_;
  std::vector<float> restLengths_;  ///< three per piece: edges 01, 12, 20
};

}  // namespace mane::physics
