#pragma once
// A skinned, morphing mesh as the renderer takes it: plain data, the same as
// physics::SkinnedMeshData, which render does not include (docs/design.md#dependency-rules).
// Deformed on the GPU by render/passes/skinning_pass.hpp.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace mane::render {

enum class GpuSkinningMethod { LinearBlend, DualQuaternion };

/// Per-vertex offsets scaled by the target's weight; an empty array leaves that attribute alone.
struct GpuMorphTarget {
  std::vector<glm::vec3> positionDeltas;
  std::vector<glm::vec3> normalDeltas;
  std::vector<glm::vec3> tangentDeltas;  ///< added to the tangent's xyz
};

/// A skinned mesh as the pass takes it (the same data as physics::SkinnedMeshData).
struct GpuSkinnedMesh {
  std::vector<glm::vec3> positions;       ///< bind pose
  std::vector<glm::vec3> normals;         ///< unit, one per position, or empty
  std::vector<glm::vec4> tangents;        ///< unit xyz and handedness w = ±1, one per position, or empty
  std::uint32_t influencesPerVertex = 0;  ///< 1 to 8
  std::vector<std::uint32_t> joints;      ///< vertex v's i-th influence is [v·influencesPerVertex + i]
  std::vector<float> weights;             ///< ≥ 0, not all zero per vertex; renormalised by the pass
  std::uint32_t jointCount = 0;
  std::vector<GpuMorphTarget> morphTargets;
  GpuSkinningMethod method = GpuSkinningMethod::LinearBlend;
};

}  // namespace mane::render
