#pragma once
// Uniform Catmull-Clark refinement of a cage with OpenSubdiv (Far), as a polygon mesh. The
// adaptive, view-dependent path (subdiv/tessellator.hpp) builds on the same topology.

#include "subdiv/cage.hpp"

namespace mane::subdiv {

/// The faces of refinement level `level` (all quads for level ≥ 1) and their vertices.
struct RefinedMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> quads;  ///< 4 indices per face, counter-clockwise
};

/// Refines `cage` uniformly `level` times (1..8) with the Catmull-Clark scheme and returns
/// the last level. Errors: an invalid cage (see validateCage), a level out of range, or
/// OpenSubdiv rejecting the topology.
Result<RefinedMesh> refineUniformly(const Cage& cage, int level);

}  // namespace mane::subdiv
