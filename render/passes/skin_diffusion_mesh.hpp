#pragma once
// A mesh as texture-space diffusion draws it (render/passes/skin_diffusion_pass.hpp): positions,
// normals and texture coordinates in one device-local vertex buffer, and its triangle list. It
// keeps its own copy, apart from the surface scene's buffers (surface_scene.hpp), so the pass
// stands alone (the surface scene's vertices start with the same three fields, at a 36-byte
// stride: sharing them would take only the irradiance pipeline's stride).

#include <cstdint>

#include <glm/glm.hpp>

#include "render/frame.hpp"
#include "render/passes/skinning_pass.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// The vertex layout of shaders/skin_irradiance.vert: locations 0, 1, 2.
struct SkinDiffusionVertex {
  glm::vec3 position;  ///< mesh units
  glm::vec3 normal;    ///< need not be unit length
  glm::vec2 uv;        ///< v = 0 at the top of the image
};
static_assert(sizeof(SkinDiffusionVertex) == 32);

class SkinDiffusionMesh {
public:
  /// Uploads `mesh`. Errors, naming the field and the index: no triangles, an index count that
  /// is not a multiple of 3, an index past the positions, normals or uvs that are not one per
  /// position, a value that is NaN or infinite, or no triangle with an area in uv space.
  [[nodiscard]] static Result<SkinDiffusionMesh> create(const Device& device, const MeshData& mesh);

  const Buffer& vertices() const { return vertices_; }
  /// Where a SkinningPass writes the deformed positions and normals of a skinned mesh (the
  /// vertex buffer is a storage buffer too). uvScale stays the bind pose's.
  SkinnedVertexTarget vertexTarget() const;
  const Buffer& indices() const { return indices_; }
  std::uint32_t indexCount() const { return indexCount_; }
  /// sqrt(Σ area in mesh units / Σ area in uv): mesh units per unit of uv, the mesh's mean
  /// stretch; the pass blurs the texels off the mesh with it.
  double uvScale() const { return uvScale_; }

private:
  SkinDiffusionMesh() = default;

  Buffer vertices_;
  Buffer indices_;
  std::uint32_t indexCount_ = 0;
  double uvScale_ = 1.0;
};

}  // namespace mane::render
