#pragma once
// Translucency (MaterialData::translucency; shaders/translucency.glsl): light 0 also reaches a
// translucent surface through the material behind it. Before the main pass the translucent
// instances are drawn into light 0's depth map (render/passes/light_depth_pass.hpp); a shaded
// point then finds the thickness d the light crossed, either from that map alone or, for the
// voxel method, through its mesh's thickness table (render/passes/thickness_table.hpp) between
// the entry point and itself, and adds light 0's radiance × T(d) × max(0.3 − N·L, 0) to its
// diffuse irradiance (Jimenez et al. 2010), T being skin's profile transmittance or exp(−σd).
// A mesh's table is built on the CPU the first frame that draws it with a voxel material (a
// slow build at fine resolutions: see VoxelThicknessLut), once per resolution, and kept with
// the scene. The surfaces that read it are drawn by SurfacePass (render/passes/surface_pass.hpp),
// which binds a mesh's table as set 2.

#include <map>
#include <memory>
#include <vector>

#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/passes/light_depth_pass.hpp"
#include "render/passes/surface_scene.hpp"
#include "render/passes/thickness_table.hpp"
#include "render/resources.hpp"

namespace mane::render {

class TranslucencyPass {
public:
  explicit TranslucencyPass(const Device& device);

  /// Keeps the triangles of `scene`'s static meshes where a material uses the voxel method (for
  /// their tables), and drops the tables of the scene before.
  void setScene(const StaticScene& scene);
  /// Static mesh `mesh` is now `data` (SurfaceScene::replaceMesh): its tables go with the old
  /// triangles (the next prepareThickness builds them again). Between frames.
  void replaceMesh(std::size_t mesh, const MeshData& data);

  /// Builds the thickness tables that the frame's voxel-translucent instances need and do not
  /// have yet. Errors name the mesh: a dynamic or skinned mesh, or one VoxelThicknessLut cannot voxelize
  /// (not closed, say).
  [[nodiscard]] Result<void> prepareThickness(const FrameInput& frame, const SurfaceScene& scene);

  /// Whether the frame draws a translucent material (and so needs the light depth map).
  [[nodiscard]] bool drawsTranslucency(const FrameInput& frame, const SurfaceScene& scene) const;

  /// Points light 0's depth map at the frame's translucent instances, for recordLightDepth;
  /// before SurfaceScene::update.
  void prepareLightDepth(const FrameInput& frame, const SurfaceScene& scene);
  /// What recordLightDepth writes, for a frame graph.
  void declareLightDepth(FrameGraph::Builder& pass) const;
  /// Records light 0's depth map of the instances prepareLightDepth found, outside a rendering
  /// scope; the barriers around it come from a frame graph (declareLightDepth).
  void recordLightDepth(const vk::raii::CommandBuffer& commands) const;
  /// What a fragment shader reading light 0's depth map uses, for a frame graph.
  void declareReads(FrameGraph::Builder& pass) const;

  const LightDepthPass& lightDepth() const { return lightDepth_; }
  /// Set 2 of the pipelines that draw translucent surfaces: a mesh's thickness table.
  vk::DescriptorSetLayout thicknessLayout() const { return *thicknessLayout_; }
  /// What `instance` binds as set 2: its mesh's table at its material's voxel resolution; for
  /// other methods and until prepareThickness built it, a valid set that is never read.
  const vk::raii::DescriptorSet& thicknessSet(const MeshInstance& instance, const SurfaceScene& scene) const;

private:
  // A thickness table of a mesh and the descriptor set that binds it.
  struct Thickness {
    std::unique_ptr<ThicknessTable> table;
    vk::raii::DescriptorPool pool{nullptr};
    vk::raii::DescriptorSet set{nullptr};
  };
  // Static meshes of a scene with voxel-translucent materials keep their triangles on the CPU
  // until their table is built.
  struct MeshTables {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> triangles;
    std::map<int, Thickness> thickness;  ///< by voxel resolution
  };
  /// `mesh`'s triangles when `keep` and it is static; none otherwise.
  static MeshTables trianglesOf(const MeshData& mesh, bool keep);
  const Thickness* thicknessOf(const MeshInstance& instance, const SurfaceScene& scene) const;

  const Device* device_;
  LightDepthPass lightDepth_;
  std::vector<LightDepthDraw> lightDepthDraws_;  ///< of the last prepareLightDepth
  bool voxelMaterials_ = false;                  ///< the scene has a voxel-translucent material
  std::vector<MeshTables> meshes_;               ///< per scene mesh
  vk::raii::DescriptorSetLayout thicknessLayout_{nullptr};
  // Bound for meshes drawn without a table: valid, never read.
  Buffer emptyGrid_;
  Buffer emptyWords_;
  vk::raii::DescriptorPool emptyThicknessPool_{nullptr};
  vk::raii::DescriptorSet emptyThickness_{nullptr};
};

}  // namespace mane::render
