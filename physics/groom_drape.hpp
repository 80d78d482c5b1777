#pragma once
// Guides laid over the body they grow from, as a comb and gravity would lay them: the rest shape
// a procedural groom gets before it is simulated. Grown straight, a long guide stands off the
// scalp; the simulation then drapes it from its root as a chain hangs, so that on the crown,
// where the slope falls every way, the strands fall every way and part into a whorl. Laid over
// the head at rest instead, each strand keeps its combed direction along the scalp, and the
// shape constraints (SolverSettings::shapeStiffness) keep it there as the head moves.
//
// Deterministic on every platform: + − × ÷ and sqrt only, the colliders' distances included.

#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/colliders.hpp"

namespace mane::physics {

/// How guides are laid over their body.
struct DrapeSettings {
  /// Gravity's direction in the guides' frame (need not be unit length; not zero). The scene
  /// gives its groom's gravity, or −y where that is zero.
  glm::vec3 down{0.0f, -1.0f, 0.0f};
  /// How quickly a strand off its body turns towards `down`, per metre of its length: walked in
  /// steps of h metres, each next step's direction is the last one's plus droop·h times the unit
  /// `down`, renormalised. In [0, 1000]; 0 keeps the grown direction.
  float droop = 20.0f;
  /// Every particle but the root is kept about this far outside the colliders (a step's sag and
  /// the smoothing aside), metres ≥ 0; the colliders' thickness is added.
  float layer = 0.001f;
  /// Along its first this many metres (≥ 0) a strand lies on the colliders, as a comb lays it:
  /// its particles are held at the layer, pulled in as well as pushed out, and do not droop.
  float combedLength = 0.08f;
};

/// Lays each guide (points root first, in the colliders' frame, metres) over `colliders`. The
/// strand is walked from its root in short steps (an eighth of its mean segment), at first
/// along the direction it grew (its first segment), each step's end moved along the colliders'
/// distance gradient to `layer` plus their thickness: onto that layer along the first
/// `combedLength` of the strand and wherever it rests on them (they lie under it, on a slope
/// gentle enough to hold it), elsewhere only out of them; off the comb each step turns the next
/// towards `down` by `droop`. The path is then smoothed over about a segment (a moving average,
/// pushed back out of the colliders). The root stays and each next particle is placed on it its
/// rest segment length from the last (as a chord), so segment lengths are kept. Fails, changing
/// nothing, on settings out of range or a guide with a segment of no length or not finite.
[[nodiscard]] Result<void> drapeGuides(std::vector<std::vector<glm::vec3>>& guides, const ColliderSet& colliders,
                                       const DrapeSettings& settings);

}  // namespace mane::physics
