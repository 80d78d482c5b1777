#pragma once
// A skinned, morphing mesh deformed by a compute pass (shaders/skinning.comp): the mesh is
// uploaded once, every frame the caller hands over the joint matrices and morph weights, and the
// pass writes the deformed positions, normals and tangents into buffers the renderer draws from.
//
// The formula is the one the CPU path implements (physics/skinning.hpp): morph targets first,
// then linear blend skinning (normals by the blended matrix's cofactor, tangents by its linear
// part) or dual-quaternion skinning (each joint split into rotation·stretch, the stretches
// blended linearly, the rigid parts as dual quaternions). The polar decompositions DQS needs are
// done per joint on the host, in double, by `update`; the shader works per vertex in float. Render
// does not depend on physics, so the mesh comes in as the plain data below; the tests check the
// two paths agree on every vertex.
//
// Buffer layouts (std430, one element per vertex):
// - positions: vec4, xyz deformed position (the joint matrices' space, metres), w = 1;
// - normals: vec4, xyz unit normal ((0, 0, 0) when the mesh has none), w = 0;
// - tangents: vec4, xyz unit tangent ((0, 0, 0) when the mesh has none), w = handedness ±1.
// As vertex input: stride `kVertexStride`, format `kVertexFormat`; or read them as storage buffers.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/error.hpp"
#include "render/frame_graph.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"
#include "render/skinned_mesh_data.hpp"

namespace mane::render {

/// A vertex buffer of another pass (interleaved, its own layout) that the dispatch also writes the
/// deformed position and normal of every vertex into, as packed xyz floats: that pass then draws
/// the deformed mesh with no change to its pipeline. Its other fields (uvs, …) are left alone.
struct SkinnedVertexTarget {
  /// STORAGE_BUFFER usage, at least vertexCount·stride floats; must outlive the pass.
  const Buffer* buffer = nullptr;
  std::uint32_t stride = 0;          ///< floats from one vertex to the next
  std::uint32_t positionOffset = 0;  ///< floats from a vertex's start to its position's x
  std::uint32_t normalOffset = 3;    ///< floats from a vertex's start to its normal's x
};

struct SkinningSettings {
  /// Keep the outputs host-visible (mapped) and make `record` hand them to host reads too (tests,
  /// CPU consumers). Otherwise they are device-local.
  bool hostReadable = false;
  /// Up to kMaxVertexTargets buffers written besides the outputs. The pass synchronises them
  /// itself: after its dispatch they are visible to vertex input, vertex-shader storage reads and
  /// copies (declare produces them).
  std::vector<SkinnedVertexTarget> vertexTargets;
};

class SkinningPass {
public:
  static constexpr std::uint32_t kVertexStride = 16;
  static constexpr vk::Format kVertexFormat = vk::Format::eR32G32B32A32Sfloat;
  static constexpr std::uint32_t kMaxInfluences = 8;
  static constexpr std::uint32_t kMaxVertexTargets = 3;

  /// Uploads `mesh` and builds the pipeline. Fails, naming the vertex or target, when the mesh is
  /// empty, has 0 or more than 8 influences per vertex, an array of the wrong length, a NaN or
  /// infinity, a joint index ≥ jointCount, a negative weight or a vertex whose weights sum to 0,
  /// or when it exceeds the device's dispatch or storage buffer limits; or, for a vertex target,
  /// when there are more than kMaxVertexTargets, one has no buffer, no STORAGE_BUFFER usage, too
  /// few bytes, or offsets that do not fit its stride.
  [[nodiscard]] static Result<std::unique_ptr<SkinningPass>> create(const Device& device, const GpuSkinnedMesh& mesh,
                                                                    const SkinningSettings& settings = {});

  SkinningPass(const SkinningPass&) = delete;
  SkinningPass& operator=(const SkinningPass&) = delete;

  /// This frame's joint matrices (affine, one per joint) and morph weights (one per target).
  /// Call before submitting the commands that run the pass, never while such a submission is
  /// still running (the buffers are single). Fails, changing nothing, when a count is wrong, a
  /// value is NaN or infinite, or, for DQS, a joint matrix mirrors or flattens space (its
  /// determinant is ≤ 0), which no rotation expresses.
  [[nodiscard]] Result<void> update(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights);

  /// What the dispatch writes, for a frame graph: the outputs, and the vertex targets as produced.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the dispatch; its barriers come from a frame graph (declare), but for the vertex
  /// targets', which it records itself after the dispatch.
  void execute(const vk::raii::CommandBuffer& commands) const;
  /// Records the dispatch alone (tests), leaving the outputs visible to vertex fetches,
  /// vertex-shader storage reads, copies and, when hostReadable, the host.
  void record(const vk::raii::CommandBuffer& commands) const;

  /// Deformed outputs: vertexCount() vec4s each (STORAGE_BUFFER | VERTEX_BUFFER | TRANSFER_SRC).
  [[nodiscard]] const Buffer& positions() const { return positions_; }
  [[nodiscard]] const Buffer& normals() const { return normals_; }
  [[nodiscard]] const Buffer& tangents() const { return tangents_; }
  /// The mapped outputs when hostReadable (read them once the submission finished), else empty.
  [[nodiscard]] std::span<const glm::vec4> mappedPositions() const;
  [[nodiscard]] std::span<const glm::vec4> mappedNormals() const;
  [[nodiscard]] std::span<const glm::vec4> mappedTangents() const;

  [[nodiscard]] std::uint32_t vertexCount() const { return vertexCount_; }

private:
  SkinningPass(const Device& device, const GpuSkinnedMesh& mesh, const SkinningSettings& settings);
  [[nodiscard]] std::span<const glm::vec4> mapped(const Buffer& buffer) const;

  std::uint32_t vertexCount_;
  std::uint32_t jointCount_;
  std::uint32_t targetCount_;
  GpuSkinningMethod method_;
  bool hostReadable_;
  Buffer rest_;
  Buffer influences_;
  Buffer morphs_;
  Buffer frame_;   ///< counts and morph weights, host-visible
  Buffer joints_;  ///< per-joint matrices and their DQS parts, host-visible
  Buffer positions_;
  Buffer normals_;
  Buffer tangents_;
  std::vector<SkinnedVertexTarget> vertexTargets_;
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  Pipeline pipeline_;
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
};

}  // namespace mane::render
