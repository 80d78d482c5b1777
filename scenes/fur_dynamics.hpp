#pragma once
// Fur that moves: short guide strands simulated by physics::HairSystem on a furred mesh, turned
// into the per-vertex leans the fur pass bends its shells by (render::FurPass::setLeans). The
// shells stay the photo's; only where their layers sit moves.
//
// Guides. Every k-th vertex of the mesh (k = ⌈vertices / guides⌉, a deterministic choice that
// follows the mesh's vertex density) roots a guide of kFurGuidePoints points, straight out along
// its normal to the fur's height h_b, in the mesh's body frame (metres). They droop under gravity
// as far as the shape stiffness lets them and lag behind the body's motion.
//
// Leans. Each vertex takes its nearest guide (by rest root position, found once). Its lean is
// the guide's tip displacement from where the rigid body would carry the rest tip, in units of
// h_b, with its component along the vertex's normal removed (the fur pass adds the normal part
// itself) and its length capped at kMaxFurLean.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/hair.hpp"
#include "scenes/mesh.hpp"

namespace mane::scenes {

inline constexpr int kFurGuidePoints = 4;
/// Longest lean, in fur heights: beyond it the shells would fold over.
inline constexpr float kMaxFurLean = 1.5f;

struct FurDynamicsSettings {
  int guides = 1000;         ///< guide strands to simulate, ≥ 1 (at most one per vertex)
  float thickness = 0.004f;  ///< h_b, metres: the guides' length
  physics::SolverSettings solver;
};

class FurDynamics {
public:
  /// Guides on `mesh` (model space, with normals) scaled by `scale` into the body frame, which
  /// `body` places in the world at rest. Errors: a mesh without vertices or normals, settings
  /// HairSystem refuses.
  [[nodiscard]] static Result<FurDynamics> create(const Mesh& mesh, float scale, const FurDynamicsSettings& settings,
                                                  const glm::mat4& body);

  /// Simulates `frameDt` seconds with the body arriving at `body` (rigid, body frame → world).
  [[nodiscard]] Result<void> advance(const glm::mat4& body, double frameDt, unsigned threads);

  /// Per mesh vertex, world space, in fur heights (file comment); for `body` (the body's current
  /// placement).
  [[nodiscard]] std::span<const glm::vec3> leans() const { return leans_; }

  [[nodiscard]] const physics::HairSystem& guides() const { return hair_; }

private:
  FurDynamics(physics::HairSystem hair) : hair_(std::move(hair)) {}
  void updateLeans(const glm::mat4& body);

  physics::HairSystem hair_;
  std::vector<glm::vec3> restTips_;          ///< per guide, body frame
  std::vector<std::uint32_t> nearestGuide_;  ///< per vertex
  std::vector<glm::vec3> normals_;           ///< per vertex, body frame
  std::vector<glm::vec3> leans_;
  float thickness_ = 0.0f;
};

}  // namespace mane::scenes
