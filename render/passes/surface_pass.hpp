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
//
// Translucency (MaterialData::translucency; shaders/translucency.glsl): light 0 also reaches a
// translucent surface through the material behind it. Before the main pass the translucent
// instances are drawn into light 0's depth map (render/passes/light_depth_map.hpp); a shaded
// point then finds the thickness d the light crossed, either from that map alone or, for the
// voxel method, through its mesh's thickness table (render/passes/thickness_table.hpp) between
// the entry point and itself, and adds light 0's radiance × T(d) × max(0.3 − N·L, 0) to its
// diffuse irradiance (Jimenez et al. 2010), T being skin's profile transmittance or exp(−σd).
// A mesh's table is built on the CPU the first frame that draws it with a voxel material
// (seconds at N = 50: see VoxelThicknessLut), once per resolution, and kept with the scene.
//
// Deferred skin (single-sample targets that keep a G-buffer: RenderTargetSettings::skinGBuffer).
// lavapipe runs a fragment shader on whole 4 × 4 blocks of every triangle it touches: on nalu's
// head at 1280×720, whose triangles cover about 5 pixels each, a pipeline-statistics query counted
// 4.4 shader invocations per covered pixel. So where a frame's pre-integrated skin (without
// translucency) uses one material, it is drawn first into the G-buffer and the depth by
// shaders/skin_gbuffer.frag, which does only what needs screen derivatives (the normal map's frame,
// the textures' mip levels). The main pass then lights it with shaders/skin_deferred.frag on a
// triangle over the screen at the far plane, depth-tested "greater" against the skin, so that
// lavapipe skips the shading of the blocks without skin and lights each skin pixel once, before
// drawing the other surfaces over it. Both halves run the forward shader's operations on the
// same values (the G-buffer is RGBA32F), so the image is the same.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "render/frame.hpp"
#include "render/luts/preintegrated_skin_lut.hpp"
#include "render/passes/hair_shadows.hpp"
#include "render/passes/light_depth_map.hpp"
#include "render/passes/thickness_table.hpp"
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
  bool hasMesh(std::size_t mesh) const { return mesh < meshes_.size(); }
  /// Replaces static mesh `mesh` by `data` (checked by the caller), whose vertex and index counts
  /// may differ: a subdivision surface tessellated again for a new view. What was derived from
  /// the old triangles goes with them: the bounds, and the thickness tables (the next
  /// prepareThickness builds them again). Only between frames. Throws vk::SystemError on failure.
  void replaceMesh(std::size_t mesh, const MeshData& data);
  std::size_t vertexCount(std::size_t mesh) const { return meshes_.at(mesh).vertexCount; }

  /// The diffused irradiance (render/passes/skin_diffusion.hpp) that texture-space skin
  /// material `material` of the scene reads at its uvs; both must outlive the scene. Between frames.
  void setDiffusedIrradiance(std::size_t material, const vk::raii::ImageView& view, const vk::raii::Sampler& sampler);

  /// Re-reads the hair shadow maps' descriptors (after their slots changed). Between frames.
  void refreshShadows();

  /// Builds the thickness tables that the frame's voxel-translucent instances need and do not
  /// have yet. Errors name the mesh: a dynamic mesh, or one VoxelThicknessLut cannot voxelize
  /// (not closed, say).
  [[nodiscard]] Result<void> prepareThickness(const FrameInput& frame);

  /// Whether the frame draws a translucent material (and so needs recordLightDepth).
  [[nodiscard]] bool drawsTranslucency(const FrameInput& frame) const;

  /// Records light 0's depth map of the frame's translucent instances; outside a rendering
  /// scope, before update().
  void recordLightDepth(const vk::raii::CommandBuffer& commands, const FrameInput& frame);

  /// Writes the frame's camera, lights, the hair shadows' and the light depth map's current
  /// uniforms; call before recording the main pass, after HairShadows::record and recordLightDepth.
  void update(const FrameInput& frame, float aspect);

  /// Whether `instance`'s material is a fur material (SurfaceShading::kFur).
  bool isFur(const MeshInstance& instance) const {
    return materials_.at(instance.material).shading == SurfaceShading::kFur;
  }

  /// Whether `instance` names a mesh and a material of the current scene.
  bool canDraw(const MeshInstance& instance) const {
    return instance.mesh < meshes_.size() && instance.material < materials_.size();
  }

  /// Draws every instance (Renderer::render has checked them with canDraw) but those with a fur material while
  /// FrameInput::furShells is on (the fur pass draws them), and with `skinDeferred` those
  /// drawSkinGBuffer drew; call inside a dynamic rendering scope with matching formats.
  void draw(const vk::raii::CommandBuffer& commands, const FrameInput& frame, bool skinDeferred = false) const;

  /// The G-buffer (RenderTarget::skinGBuffer) the deferred skin writes and reads; it must
  /// outlive the pass. Before setScene, which builds the deferred skin's pipelines only when a
  /// G-buffer is set.
  void setSkinGBuffer(std::span<const Image> gBuffer);
  /// Whether the frame's skin is deferred (see "Deferred skin"): a G-buffer is set, and the
  /// frame's pre-integrated skin instances without translucency, at least one, share a material.
  [[nodiscard]] bool defersSkin(const FrameInput& frame) const;
  /// Draws those instances into the G-buffer; inside RenderTarget::beginSkinGBuffer's scope.
  void drawSkinGBuffer(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const;
  /// Lights the G-buffer's skin; first in the scene pass begun with afterSkin
  /// (RenderTarget::beginScene), whose depth is still the G-buffer pass's.
  void drawSkinLighting(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const;

private:
  // A thickness table of a mesh and the descriptor set (set 2) that binds it.
  struct Thickness {
    std::unique_ptr<ThicknessTable> table;
    vk::raii::DescriptorPool pool{nullptr};
    vk::raii::DescriptorSet set{nullptr};
  };
  struct GpuMesh {
    Buffer vertices;
    Buffer indices;
    std::uint32_t indexCount = 0;
    std::size_t vertexCount = 0;
    bool dynamic = false;
    BoundingSphere bounds;  ///< mesh units
    // Static meshes of a scene with voxel-translucent materials keep their triangles on the CPU
    // until their table is built.
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> triangles;
    std::map<int, Thickness> thickness;  ///< by voxel resolution
  };
  struct GpuMaterial {
    Image albedo;  ///< sRGB; alpha: the specular map's red (albedoWithSpecular)
    Image normalMap;
    Buffer uniforms;  ///< MaterialUniforms
    SurfaceShading shading = SurfaceShading::kLambert;
    SkinParameters skin;
    TranslucencyParameters translucency;
    bool doubleSided = true;
    vk::raii::DescriptorSet descriptors{nullptr};
  };

  /// Uploads `mesh`'s vertices and triangles; a static mesh keeps them on the CPU too when
  /// `keepTriangles` (for the voxel thickness tables).
  GpuMesh uploadMesh(const MeshData& mesh, bool keepTriangles) const;
  /// Uploads `material`'s textures and constants into a set of materialPool_.
  GpuMaterial uploadMaterial(const MaterialData& material);
  /// The table for `range`, baked on first use.
  const PreintegratedSkinLut& skinTable(SkinIntegrationRange range);
  /// What materials that never read the skin table bind in its place, made on first use: the
  /// binding must hold an image of the type the shader declares, a 2D array.
  const Image& unreadSkinTable();

  const Device* device_;
  const HairShadows* shadows_;
  std::array<std::unique_ptr<PreintegratedSkinLut>, 2> skinTables_;  ///< Penner, curvature-dependent
  std::unique_ptr<Image> unreadSkinTable_;
  vk::raii::DescriptorSetLayout frameLayout_{nullptr};
  vk::raii::DescriptorSetLayout materialLayout_{nullptr};
  vk::raii::DescriptorSetLayout thicknessLayout_{nullptr};
  /// Builds the pipelines the materials of the scene use, for the hair shadows' current maps.
  void buildPipelines();
  // Pipelines: shading (Lambert, pre-integrated skin, texture-space skin) × translucency method.
  static constexpr std::size_t kShadings = 3;
  static constexpr std::size_t kTranslucencyMethods = 3;
  static std::size_t pipelineFor(const GpuMaterial& material);
  /// Binds `instance`'s mesh and model, sets its culling, and draws it (the pipeline and the
  /// material's sets are bound).
  void drawMesh(const vk::raii::CommandBuffer& commands, vk::PipelineLayout layout, const MeshInstance& instance) const;
  /// Pre-integrated skin without translucency: what the deferred skin draws.
  static bool deferrable(const GpuMaterial& material);
  /// The one material of the frame's deferrable instances; none when they have none or several.
  std::optional<std::size_t> deferredMaterial(const FrameInput& frame) const;
  /// The table of `mesh` at `material`'s voxel resolution; nullptr for other methods and until
  /// prepareThickness built it.
  const Thickness* thicknessOf(const GpuMesh& mesh, const GpuMaterial& material) const;

  struct Formats {
    vk::Format color;
    vk::Format depth;
    vk::SampleCountFlagBits samples;
  };
  Formats formats_{};
  std::array<Pipeline, kShadings * kTranslucencyMethods> pipelines_;  ///< one layout; unused ones empty
  // The deferred skin: its G-buffer pass, its lighting (sets: frame, material, G-buffer), and
  // the G-buffer's set (empty until setSkinGBuffer) with its images' size.
  Pipeline skinGBufferPipeline_;
  Pipeline skinShadingPipeline_;
  vk::raii::DescriptorSetLayout gBufferLayout_{nullptr};
  vk::raii::DescriptorPool gBufferPool_{nullptr};
  vk::raii::DescriptorSet gBufferSet_{nullptr};
  vk::Extent2D gBufferExtent_{};
  LightDepthMap lightDepth_;
  // Bound for meshes drawn without a table: valid, never read.
  Buffer emptyGrid_;
  Buffer emptyWords_;
  vk::raii::DescriptorPool emptyThicknessPool_{nullptr};
  vk::raii::DescriptorSet emptyThickness_{nullptr};
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorPool framePool_{nullptr};
  vk::raii::DescriptorSet frameSet_{nullptr};
  Buffer frameUniforms_;
  vk::raii::DescriptorPool materialPool_{nullptr};
  std::vector<GpuMesh> meshes_;
  std::vector<GpuMaterial> materials_;
};

}  // namespace mane::render
