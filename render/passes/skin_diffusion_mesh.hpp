#pragma once
// A mesh as texture-space diffusion draws it (render/passes/skin_diffusion_pass.hpp): positions,
// normals and texture coordinates in one device-local buffer, which the irradiance pass reads by
// vertex index, and the draw list of render/passes/skin_uv_seams.hpp (its own triangles, then the
// skirts that reach across its uv seams) as a vertex buffer. It keeps its own copy of the
// vertices, apart from the surface scene's buffers (surface_scene.hpp), so the pass stands alone.

#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "render/frame.hpp"
#include "render/passes/skinning_pass.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// A vertex as shaders/skin_irradiance.vert reads it from the storage buffer (eight floats).
struct SkinDiffusionVertex {
  glm::vec3 position;  ///< mesh units
  glm::vec3 normal;    ///< need not be unit length
  glm::vec2 uv;        ///< v = 0 at the top of the image
};
static_assert(sizeof(SkinDiffusionVertex) == 32);

class SkinDiffusionMesh {
public:
  /// How far past a uv seam the skirts reach (skin_uv_seams.hpp): 32 texels of a 1024² map where
  /// the mesh has its median uv density. The blurs reach 3σ of the profile's widest Gaussian
  /// (8.2 mm for d'Eon's), so this carries them across the seams where a texel spans 0.26 mm or
  /// more at 1024² (nalu's head: 0.31 mm). A wider reach costs fill and gained nothing on it.
  static constexpr float kDefaultSeamReach = 1.0f / 32.0f;

  /// Uploads `mesh` with skirts reaching `seamReach` (uv units, in [0, 0.25]; 0: none) past its
  /// seams. Errors, naming the field and the index: no triangles, an index count that is not a
  /// multiple of 3, an index past the positions, normals or uvs that are not one per position, a
  /// value that is NaN or infinite, no triangle with an area in uv space, or a bad reach.
  [[nodiscard]] static Result<SkinDiffusionMesh> create(const Device& device, const MeshData& mesh,
                                                        float seamReach = kDefaultSeamReach);

  /// SkinDiffusionVertex per mesh vertex, a storage buffer.
  const Buffer& vertices() const { return vertices_; }
  /// Where a SkinningPass writes the deformed positions and normals of a skinned mesh (the
  /// vertex buffer is a storage buffer too). uvScale stays the bind pose's.
  SkinnedVertexTarget vertexTarget() const;
  /// SkinDrawVertex, a triangle list: drawCount() vertices.
  const Buffer& drawList() const { return drawList_; }
  std::uint32_t drawCount() const { return drawCount_; }
  /// Set 1 of the irradiance pipeline: vertices() as a storage buffer read by the vertex shader.
  const vk::raii::DescriptorSet& verticesSet() const { return descriptors_->set; }
  /// The layout of verticesSet(); a pipeline layout made with another identical one is compatible.
  static vk::raii::DescriptorSetLayout makeVerticesLayout(const Device& device);
  /// sqrt(Σ area in mesh units / Σ area in uv): mesh units per unit of uv, the mesh's mean
  /// stretch; the pass blurs the texels off the mesh with it.
  double uvScale() const { return uvScale_; }

private:
  SkinDiffusionMesh() = default;

  Buffer vertices_;
  Buffer drawList_;
  std::uint32_t drawCount_ = 0;
  double uvScale_ = 1.0;
  // Held apart, so that a move replaces them whole: the old set is freed before its pool goes.
  struct Descriptors {
    vk::raii::DescriptorSetLayout layout{nullptr};
    vk::raii::DescriptorPool pool{nullptr};
    vk::raii::DescriptorSet set{nullptr};
  };
  std::unique_ptr<Descriptors> descriptors_;
};

}  // namespace mane::render
