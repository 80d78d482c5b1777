#pragma once
// The scene's opaque meshes and their materials on the GPU, and the frame's camera and lights:
// what the passes that draw surfaces share (SurfacePass, DeferredSkinPass, TranslucencyPass).
// Their pipelines bind the frame as set 0 (camera, lights, the first light's hair shadows —
// render/passes/hair_shadow_pass.hpp —, light 0's depth map of the translucent surfaces, its
// shadow map of every surface: shaders/frame_uniforms.glsl) and a material as set 1 (albedo with the specular map in
// its alpha, normal map, the pre-integrated skin table, the diffused irradiance, constants: shaders/skin_lights.glsl),
// and draw the vertices of surface.vert: position, normal, uv, curvature.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "render/environment/spherical_harmonics.hpp"
#include "render/frame.hpp"
#include "render/passes/environment_pass.hpp"
#include "render/passes/hair_density_pass.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/passes/light_depth_pass.hpp"
#include "render/passes/skin_shading.hpp"
#include "render/passes/skinning_pass.hpp"
#include "render/passes/surface_shadow_pass.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// What the surface passes need to know of a material besides its descriptor set.
struct SurfaceMaterial {
  SurfaceShading shading = SurfaceShading::kLambert;
  SkinParameters skin;
  TranslucencyParameters translucency;
  bool doubleSided = true;
};

class SurfaceScene {
public:
  static constexpr std::size_t kMaxLights = 4;  ///< must match shaders/frame_uniforms.glsl

  /// `shadows` (the hair's, attenuating the first light), `lightDepth` (light 0's depth map of the
  /// translucent surfaces) and `surfaceShadows` (light 0's shadows of every surface) must outlive
  /// the scene.
  SurfaceScene(const Device& device, const HairShadowPass& shadows, const LightDepthPass& lightDepth,
               const SurfaceShadowPass& surfaceShadows);

  /// Uploads meshes and materials; replaces what was there. Throws vk::SystemError (or
  /// std::runtime_error when a skin table cannot be baked) on failure.
  void setScene(const StaticScene& scene);

  /// Replaces the positions and normals of dynamic mesh `mesh` (sizes checked by the caller);
  /// only between frames (the renderer waits for each frame before returning).
  void updateVertices(std::size_t mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);
  /// Replaces static mesh `mesh` by `data` (checked by the caller), whose vertex and index counts
  /// may differ: a subdivision surface tessellated again for a new view. Only between frames.
  /// Throws vk::SystemError on failure.
  void replaceMesh(std::size_t mesh, const MeshData& data);

  bool hasMesh(std::size_t mesh) const { return mesh < meshes_.size(); }
  bool isDynamic(std::size_t mesh) const { return mesh < meshes_.size() && meshes_[mesh].dynamic; }
  /// Whether mesh `mesh` is deformed on the GPU (MeshData::skinning): its vertex buffer is then
  /// also a storage buffer, written by a SkinningPass (skinnedVertexTarget) every frame.
  bool isSkinned(std::size_t mesh) const { return mesh < meshes_.size() && meshes_[mesh].skinned; }
  /// Whether the mesh's vertices change from frame to frame (dynamic or skinned): the bounds of
  /// its bind pose say nothing of where it is.
  bool isDeforming(std::size_t mesh) const { return isDynamic(mesh) || isSkinned(mesh); }
  /// Where a SkinningPass writes skinned mesh `mesh`'s deformed positions and normals.
  SkinnedVertexTarget skinnedVertexTarget(std::size_t mesh) const;
  std::size_t vertexCount(std::size_t mesh) const { return meshes_.at(mesh).vertexCount; }
  /// A sphere holding the mesh's vertices, mesh units: of a dynamic mesh as last updated, of a
  /// skinned one in its bind pose.
  const BoundingSphere& bounds(std::size_t mesh) const { return meshes_.at(mesh).bounds; }
  vk::Buffer vertices(std::size_t mesh) const { return *meshes_.at(mesh).vertices.buffer(); }
  vk::Buffer indices(std::size_t mesh) const { return *meshes_.at(mesh).indices.buffer(); }
  std::uint32_t indexCount(std::size_t mesh) const { return meshes_.at(mesh).indexCount; }

  /// Whether `instance` names a mesh and a material of the current scene.
  bool canDraw(const MeshInstance& instance) const {
    return instance.mesh < meshes_.size() && instance.material < materials_.size();
  }
  const SurfaceMaterial& material(std::size_t material) const { return materials_.at(material).surface; }
  const SurfaceMaterial& material(const MeshInstance& instance) const { return material(instance.material); }
  std::size_t materialCount() const { return materials_.size(); }
  /// Whether `instance`'s material is a fur material (SurfaceShading::kFur).
  bool isFur(const MeshInstance& instance) const { return material(instance).shading == SurfaceShading::kFur; }

  /// The diffused irradiance (render/passes/skin_diffusion_pass.hpp) that texture-space skin
  /// material `material` of the scene reads at its uvs; both must outlive the scene. Between frames.
  void setDiffusedIrradiance(std::size_t material, const vk::raii::ImageView& view, const vk::raii::Sampler& sampler);

  /// Re-reads the hair shadow maps' descriptors (after their slots changed). Between frames.
  void refreshShadows();

  /// The environment whose irradiance and specular chain the surfaces are lit by from now on
  /// (none: nullptr); it must outlive its use.
  void setEnvironment(const EnvironmentPass* environment);
  /// The hair's occlusion volume that hides part of the environment from the surfaces, or none.
  /// update() takes its placement as it is then (scale.w = 0: nothing hidden this frame). It must
  /// outlive its use; between frames.
  void setHairVisibility(const HairDensityPass* visibility);

  /// Writes the frame's camera, lights, the hair shadows' and the light depth map's current
  /// uniforms; call before recording the passes that draw surfaces, after HairShadowPass::prepare
  /// and the light depth map's prepare.
  void update(const FrameInput& frame, float aspect);

  /// What a pipeline drawing the scene's meshes starts from: surface.vert's vertex layout, culling
  /// and winding set when drawn, depth tested against and written in `depthFormat`, the model
  /// matrix as push constant.
  GraphicsPipelineSettings meshPipeline(vk::Format depthFormat) const;
  vk::DescriptorSetLayout frameLayout() const { return *frameLayout_; }
  vk::DescriptorSetLayout materialLayout() const { return *materialLayout_; }
  const vk::raii::DescriptorSet& frameSet() const { return frameSet_; }
  const vk::raii::DescriptorSet& materialSet(std::size_t material) const { return materials_.at(material).descriptors; }
  /// Bytes between two vertices of a mesh, position first.
  static constexpr std::uint32_t kVertexStride = 36;

  /// Binds `instance`'s mesh and model, sets its culling and winding, and draws it (the
  /// pipeline and the material's sets are bound; `layout` is the pipeline's).
  void drawMesh(const vk::raii::CommandBuffer& commands, vk::PipelineLayout layout, const MeshInstance& instance) const;

private:
  std::optional<SphericalHarmonics9> environmentIrradiance_;
  Image noEnvironment_;  // bound where there is no environment
  const HairDensityPass* hairVisibility_ = nullptr;
  Image noHairVisibility_;  // bound where there is no hair volume
  vk::raii::Sampler hairVisibilitySampler_{nullptr};
  struct GpuMesh {
    Buffer vertices;
    Buffer indices;
    std::uint32_t indexCount = 0;
    std::size_t vertexCount = 0;
    bool dynamic = false;
    bool skinned = false;
    BoundingSphere bounds;  ///< mesh units (bounds())
  };
  struct GpuMaterial {
    Image albedo;  ///< sRGB; alpha: the specular map's red (albedoWithSpecular)
    Image normalMap;
    Buffer uniforms;  ///< MaterialUniforms
    SurfaceMaterial surface;
    vk::raii::DescriptorSet descriptors{nullptr};
  };

  GpuMesh uploadMesh(const MeshData& mesh) const;
  /// Uploads `material`'s textures and constants into a set of materialPool_.
  GpuMaterial uploadMaterial(const MaterialData& material);

  const Device* device_;
  const HairShadowPass* shadows_;
  const LightDepthPass* lightDepth_;
  const SurfaceShadowPass* surfaceShadows_;
  SkinShading skin_;
  vk::raii::DescriptorSetLayout frameLayout_{nullptr};
  vk::raii::DescriptorSetLayout materialLayout_{nullptr};
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorPool framePool_{nullptr};
  vk::raii::DescriptorSet frameSet_{nullptr};
  Buffer frameUniforms_;
  vk::raii::DescriptorPool materialPool_{nullptr};
  std::vector<GpuMesh> meshes_;
  std::vector<GpuMaterial> materials_;
};

}  // namespace mane::render
