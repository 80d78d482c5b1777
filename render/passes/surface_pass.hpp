#pragma once
// Opaque meshes lit by directional lights: albedo texture × base colour, tangent-space normal
// map, ambient, and per material either Lambert diffuse or skin; the first light is attenuated
// by the hair shadows (render/passes/hair_shadows.hpp).
//
// Skin (shaders/surface.frag, shaders/preintegrated_skin.glsl):
//  - diffuse: the pre-integrated table (render/luts/preintegrated_skin_lut.hpp) in place of
//    max(N·L, 0), looked up per RGB at the vertex curvature (MeshData::curvatures, converted to
//    1/mm with the instance's scale: world units are metres);
//  - blurred normals per channel (Penner & Borshukov 2011): channel c reads N·L with
//    normalize(mix(N_detail, N_geometric, w_c)); w_c is the share of the channel's profile
//    weight in d'Eon's Gaussians of variance ≥ 0.187 mm² (σ ≥ 0.43 mm, wider than pores;
//    SkinProfile::broadShare): (0.667, 0.209, 0.007) — red light has left the pores' scale
//    before it exits, blue has not;
//  - specular: Kelemen/Szirmay-Kalos with the table's Beckmann term and Schlick's Fresnel
//    (F0 = 0.028) on the detail normal, ρs scaled by the specular map's red channel.
// The tables are baked once per integration range, when a scene first needs one.

#include <vector>

#include <array>
#include <memory>

#include "render/frame.hpp"
#include "render/luts/preintegrated_skin_lut.hpp"
#include "render/passes/hair_shadows.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

class SurfacePass {
public:
  static constexpr std::size_t kMaxLights = 4;  ///< must match shaders/frame_uniforms.glsl

  /// `shadows` (which must outlive the pass) attenuates the first light.
  SurfacePass(const Device& device, const HairShadows& shadows, vk::Format colorFormat, vk::Format depthFormat,
              vk::SampleCountFlagBits samples);

  /// Uploads meshes and materials; replaces what was there. Rebuilds the pipelines for the hair
  /// shadows' current maps (call after HairShadows::setGrooms). Throws vk::SystemError (or
  /// std::runtime_error when a skin table cannot be baked) on failure.
  void setScene(const StaticScene& scene);

  /// Replaces the positions and normals of dynamic mesh `mesh` (sizes checked by the caller);
  /// only between frames (the renderer waits for each frame before returning).
  void updateVertices(std::size_t mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);
  bool isDynamic(std::size_t mesh) const { return mesh < meshes_.size() && meshes_[mesh].dynamic; }
  std::size_t vertexCount(std::size_t mesh) const { return meshes_.at(mesh).vertexCount; }

  /// The diffused irradiance (render/passes/skin_diffusion.hpp) that texture-space skin
  /// material `material` of the scene reads at its uvs; both must outlive the scene. Between frames.
  void setDiffusedIrradiance(std::size_t material, const vk::raii::ImageView& view, const vk::raii::Sampler& sampler);

  /// Re-reads the hair shadow maps' descriptors (after their slots changed). Between frames.
  void refreshShadows();

  /// Writes the frame's camera, lights and the hair shadows' current uniforms; call before
  /// recording the frame, after HairShadows::record.
  void update(const FrameInput& frame, float aspect);

  /// Whether `instance` names a mesh and a material of the current scene.
  bool canDraw(const MeshInstance& instance) const {
    return instance.mesh < meshes_.size() && instance.material < materials_.size();
  }

  /// Draws every instance (Renderer::render has checked them with canDraw); call inside a dynamic rendering scope with
  /// matching formats.
  void draw(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const;

private:
  struct GpuMesh {
    Buffer vertices;
    Buffer indices;
    std::uint32_t indexCount = 0;
    std::size_t vertexCount = 0;
    bool dynamic = false;
  };
  struct GpuMaterial {
    Image albedo;
    Image normalMap;
    Image specularMap;
    bool hasNormalMap = false;
    glm::vec3 baseColor{1.0f};
    SurfaceShading shading = SurfaceShading::kLambert;
    SkinParameters skin;
    glm::vec4 skinConstants{0.0f};  ///< skin: roughness, ρs, the table's maxCurvature (1/mm)
    glm::vec4 blur{0.0f};           ///< skin: per channel, the geometric normal's weight
    vk::raii::DescriptorSet descriptors{nullptr};
  };

  /// The table for `range`, baked on first use.
  const PreintegratedSkinLut& skinTable(SkinIntegrationRange range);

  const Device* device_;
  const HairShadows* shadows_;
  std::array<std::unique_ptr<PreintegratedSkinLut>, 2> skinTables_;  ///< Penner, curvature-dependent
  vk::raii::DescriptorSetLayout frameLayout_{nullptr};
  vk::raii::DescriptorSetLayout materialLayout_{nullptr};
  /// Builds the Lambert and skin pipelines for the hair shadows' current maps.
  void buildPipelines();
  static constexpr std::size_t kLambertPipeline = 0;
  static constexpr std::size_t kSkinPipeline = 1;              ///< pre-integrated
  static constexpr std::size_t kTextureSpaceSkinPipeline = 2;  ///< diffuse from the diffused irradiance
  static std::size_t pipelineFor(const GpuMaterial& material);

  struct Formats {
    vk::Format color;
    vk::Format depth;
    vk::SampleCountFlagBits samples;
  };
  Formats formats_{};
  std::array<Pipeline, 3> pipelines_;  ///< one layout, specialised shaders
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorPool framePool_{nullptr};
  vk::raii::DescriptorSet frameSet_{nullptr};
  Buffer frameUniforms_;
  vk::raii::DescriptorPool materialPool_{nullptr};
  std::vector<GpuMesh> meshes_;
  std::vector<GpuMaterial> materials_;
};

}  // namespace mane::render
