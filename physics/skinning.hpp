#pragma once
// A mesh deformed by morph targets and a skeleton: the CPU path that moves a character's body.
//
// Per vertex, in this order (glTF 2.0 §3.7.2.2 and §3.8.3):
//  1. morph targets: p = p_rest + Σ w_k·Δp_k, and likewise for normals and tangents;
//  2. skinning by up to `influencesPerVertex` joints whose weights sum to 1, either
//     - linear blend skinning (LBS): p' = (Σ w_i·M_i)·p, or
//     - dual-quaternion skinning (DQS, Kavan et al. 2008, "Geometric Skinning with Approximate
//       Dual Quaternion Blending"): the rigid parts of the joint matrices are blended as dual
//       quaternions, which keeps volume where LBS pinches (a twisting wrist, a bending elbow).
//
// Normals. LBS moves a normal by the inverse transpose of the blended matrix's linear part, so a
// non-uniform scale (blended or in a joint) keeps normals perpendicular to the surface; it is
// computed as the cofactor matrix (det·M⁻ᵀ, signed to match M⁻ᵀ), which needs no division.
// Tangents move by the linear part itself, and their handedness flips where it mirrors.
// DQS splits each joint matrix into rotation·stretch (polar decomposition), blends the stretches
// linearly and applies them before the blended rigid motion (Kavan et al. 2008, §4.2), so a
// uniformly scaled skeleton (an armature exported at 100×) deforms correctly too; normals take
// the blended stretch's cofactor and then the rotation. Every normal and tangent is renormalised.
//
// Free of data-dependent ordering, and each vertex is computed alone: the same inputs give the
// same bits for any thread count.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/error.hpp"
#include "physics/task_runner.hpp"

namespace mane::physics {

enum class SkinningMethod { LinearBlend, DualQuaternion };

/// Per-vertex offsets added to the base mesh in proportion to the target's weight. An empty
/// array means the target leaves that attribute alone.
struct MorphTarget {
  std::string name;
  std::vector<glm::vec3> positionDeltas;  ///< metres
  std::vector<glm::vec3> normalDeltas;
  std::vector<glm::vec3> tangentDeltas;  ///< added to the tangent's xyz; the handedness is kept
};

/// A skinned mesh as data: what `SkinnedMesh::create` checks and takes.
struct SkinnedMeshData {
  std::vector<glm::vec3> positions;    ///< bind pose, metres
  std::vector<glm::vec3> normals;      ///< unit, one per position, or empty
  std::vector<glm::vec4> tangents;     ///< unit xyz and handedness w = ±1, one per position, or empty
  std::vector<std::uint32_t> indices;  ///< triangle list, may be empty
  /// Joint influences per vertex; vertex v's i-th is joints/weights[v·influencesPerVertex + i].
  std::size_t influencesPerVertex = 0;
  std::vector<std::uint32_t> joints;  ///< indices into the joint matrices `deform` takes
  std::vector<float> weights;         ///< ≥ 0, not all zero per vertex; renormalised by `create`
  std::size_t jointCount = 0;         ///< how many joint matrices `deform` takes
  std::vector<MorphTarget> morphTargets;
  SkinningMethod method = SkinningMethod::LinearBlend;
};

/// Where `deform` writes: positions, and normals and tangents when the mesh has them.
struct DeformedSurface {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
};

class SkinnedMesh {
public:
  /// Checks `data` and renormalises each vertex's weights to sum to 1. Fails, naming the vertex
  /// (or target) and the problem, when: there are no influences; an array's length does not
  /// match the vertex count; a value is NaN or infinite; a joint index is ≥ `jointCount`; a
  /// weight is negative; a vertex's weights sum to 0; a triangle index is out of range.
  [[nodiscard]] static Result<SkinnedMesh> create(SkinnedMeshData data);

  /// The mesh as created, with renormalised weights.
  [[nodiscard]] const SkinnedMeshData& data() const { return data_; }
  [[nodiscard]] std::size_t vertexCount() const { return data_.positions.size(); }
  [[nodiscard]] std::size_t morphTargetCount() const { return data_.morphTargets.size(); }

  [[nodiscard]] SkinningMethod method() const { return data_.method; }
  void setMethod(SkinningMethod method) { data_.method = method; }

  /// Morphs with `morphWeights` (one per target, in order; any real value), then skins with
  /// `jointMatrices` (one per joint: the joint's world matrix times its inverse bind matrix,
  /// affine), writing to `out` (resized as needed). Fails, leaving `out` unspecified, when a span
  /// has the wrong size or holds a NaN or infinity, or, for DQS, a joint matrix used by a vertex
  /// mirrors or flattens space (its determinant is ≤ 0): a rotation cannot express that.
  /// The tasks of `tasks` deform fixed contiguous ranges of vertices (task t the t-th of
  /// `concurrency` ranges); the output and any error do not depend on what runs them. Also fails
  /// when the task runner fails (the vertices are then deformed on the calling thread).
  [[nodiscard]] Result<void> deform(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights,
                                    DeformedSurface& out, const TaskRunner& tasks) const;
  /// Shorthand for a caller that counts workers: `deform` on `builtInTaskRunner(threads)` (0
  /// counts as 1).
  [[nodiscard]] Result<void> deform(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights,
                                    DeformedSurface& out, unsigned threads = 1) const;

private:
  SkinnedMeshData data_;
};

}  // namespace mane::physics
