#pragma once
// Dense strands interpolated from simulated guide strands by a compute pass
// (shaders/strand_interpolation.comp): every frame the caller uploads the guide positions, the
// pass writes the positions and unit tangents of every dense vertex into buffers that the hair
// passes read as vertex data.
//
// The formula is that of physics/interpolation.hpp (single guide with a root offset, or up to 3
// barycentric guides; clumping; offsets in the primary guide's frame; tangents by central
// differences), evaluated operation for operation in the same order with no fused multiply-add,
// so the GPU result matches the CPU reference `physics::interpolateDenseStrands` within 1e-5
// relative (on lavapipe bit for bit). The layout is the one physics builds
// (common/strand_layout.hpp), whose elements are the std430 elements the shader reads.
//
// Buffer layouts (all std430, strand-major: vertex i of dense strand s is element s·Nd + i):
// - guide positions (input, host-visible, written by updateGuides): one vec4 per guide vertex,
//   16 bytes, xyz = position (metres), w = 1 (unused); guide after guide, root first.
//   updateGuides repacks the caller's glm::vec3 points (e.g. physics::HairSystem's
//   particles().positions) into it: one 16-byte load per guide point makes the pass much faster
//   on lavapipe than three 4-byte loads from (x, y, z) triplets, for 4 bytes more per point.
// - positions (output): one vec4 per dense vertex, 16 bytes: xyz = position (metres, the frame
//   of the guides), w = t = i / (Nd − 1), the parameter along the strand (0 root, 1 tip).
// - tangents (output): one vec4 per dense vertex, 16 bytes: xyz = unit tangent root → tip
//   ((0, 0, 0) where the neighbouring points coincide), w = 0.
// As vertex input: binding stride 16 (`kVertexStride`), attribute format R32G32B32A32_SFLOAT
// (`kVertexFormat`) at offset 0, one vertex per dense vertex; or read them as storage buffers.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/frame_graph.hpp"
#include "render/hair_data.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

struct StrandInterpolationSettings {
  /// Keep the outputs in host-visible memory (mapped) and make `record` hand them to host reads
  /// too, so the CPU can read them once the submission has finished (tests, benchmarks, CPU
  /// consumers). Otherwise they are device-local and only the vertex stage reads them.
  bool hostReadable = false;
};

/// The interpolation pass of one dense groom: the layout is uploaded once, the guides every frame.
class StrandInterpolationPass {
public:
  /// Vertex input stride and format of the position and tangent buffers (see the file comment).
  static constexpr std::uint32_t kVertexStride = 16;
  static constexpr vk::Format kVertexFormat = vk::Format::eR32G32B32A32Sfloat;

  /// Uploads `layout` and builds the pipeline. Fails, naming the strand or guide, when the layout
  /// is empty or invalid by the rules of validateStrandLayout (counts, guide and partner indices
  /// in range, weights finite and summing to 1 within 1e-5, finite offsets, clump in [0, 1],
  /// vertexScale keeping every dense vertex on its guides), or when it is larger than the
  /// device's limits (dispatch size, storage buffer range).
  [[nodiscard]] static Result<std::unique_ptr<StrandInterpolationPass>> create(
      const Device& device, const DenseStrandLayout& layout, const StrandInterpolationSettings& settings = {});

  StrandInterpolationPass(const StrandInterpolationPass&) = delete;
  StrandInterpolationPass& operator=(const StrandInterpolationPass&) = delete;

  /// Copies this frame's guide positions (metres, guideCount × Ng points, guide after guide,
  /// root first) into the guide buffer, as vec4s. Call before submitting the commands `record` made, never
  /// while such a submission is still running (the buffer is single: the caller waits for the
  /// previous frame). Fails, copying nothing, when the count does not match the layout, a point
  /// is NaN or infinite (naming guide and vertex), or a guide's root is collinear with its frame
  /// partners' roots — the same inputs the CPU reference rejects.
  [[nodiscard]] Result<void> updateGuides(std::span<const glm::vec3> guidePositions);

  /// What the dispatch writes (the positions and tangents), for a frame graph.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the dispatch; the barriers around it come from a frame graph (declare). The
  /// guides are those of the last updateGuides (call it before the first frame: the buffer
  /// starts zeroed, which no valid frame has).
  void execute(const vk::raii::CommandBuffer& commands) const;
  /// Records the dispatch alone (tests, benchmarks): after every earlier command, and leaving
  /// the outputs visible to vertex attribute fetches, vertex-shader storage reads and buffer
  /// copies (and to the host, when hostReadable).
  void record(const vk::raii::CommandBuffer& commands) const;

  /// Dense vertex positions: vertexTotal() vec4s (STORAGE_BUFFER | VERTEX_BUFFER | TRANSFER_SRC).
  [[nodiscard]] const Buffer& positions() const { return positions_; }
  /// Dense vertex unit tangents: vertexTotal() vec4s (STORAGE_BUFFER | VERTEX_BUFFER | TRANSFER_SRC).
  [[nodiscard]] const Buffer& tangents() const { return tangents_; }
  /// The mapped outputs when hostReadable (read them after the submission finished), else empty.
  [[nodiscard]] std::span<const glm::vec4> mappedPositions() const;
  [[nodiscard]] std::span<const glm::vec4> mappedTangents() const;

  [[nodiscard]] std::uint32_t strandCount() const { return strandCount_; }
  [[nodiscard]] std::uint32_t guideCount() const { return guideCount_; }
  [[nodiscard]] std::uint32_t guideVertexCount() const { return guideVertexCount_; }
  /// Nd, vertices per dense strand.
  [[nodiscard]] std::uint32_t vertexCount() const { return vertexCount_; }
  /// Dense vertices in the outputs: strandCount() × vertexCount().
  [[nodiscard]] std::size_t vertexTotal() const { return std::size_t(strandCount_) * vertexCount_; }

private:
  StrandInterpolationPass(const Device& device, const DenseStrandLayout& layout,
                          const StrandInterpolationSettings& settings);

  std::uint32_t guideCount_;
  std::uint32_t guideVertexCount_;
  std::uint32_t vertexCount_;
  StrandCurve curve_;
  std::uint32_t strandCount_;
  bool hostReadable_;
  std::vector<GuideFrameRef> guideFrames_;  ///< for updateGuides' collapsed-frame check
  Buffer guides_;
  Buffer frames_;
  Buffer strands_;
  Buffer positions_;
  Buffer tangents_;
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  Pipeline pipeline_;
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
};

}  // namespace mane::render
