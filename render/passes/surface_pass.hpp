#pragma once
// Opaque meshes lit by directional lights: albedo texture × base colour, tangent-space normal
// map, Lambert diffuse plus ambient; the first light is attenuated by the hair shadows
// (render/passes/hair_shadows.hpp). The skin shading of the skin issue will replace the BRDF.

#include <vector>

#include "render/frame.hpp"
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

  /// Uploads meshes and materials; replaces what was there. Throws vk::SystemError on failure.
  void setScene(const StaticScene& scene);

  /// Replaces the positions and normals of dynamic mesh `mesh` (sizes checked by the caller);
  /// only between frames (the renderer waits for each frame before returning).
  void updateVertices(std::size_t mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);
  bool isDynamic(std::size_t mesh) const { return mesh < meshes_.size() && meshes_[mesh].dynamic; }
  std::size_t vertexCount(std::size_t mesh) const { return meshes_.at(mesh).vertexCount; }

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
    bool hasNormalMap = false;
    glm::vec3 baseColor{1.0f};
    vk::raii::DescriptorSet descriptors{nullptr};
  };

  const Device* device_;
  const HairShadows* shadows_;
  vk::raii::DescriptorSetLayout frameLayout_{nullptr};
  vk::raii::DescriptorSetLayout materialLayout_{nullptr};
  Pipeline pipeline_;
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorPool framePool_{nullptr};
  vk::raii::DescriptorSet frameSet_{nullptr};
  Buffer frameUniforms_;
  vk::raii::DescriptorPool materialPool_{nullptr};
  std::vector<GpuMesh> meshes_;
  std::vector<GpuMaterial> materials_;
};

}  // namespace mane::render
