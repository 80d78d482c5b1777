#pragma once
// The first light's depth map of the translucent surfaces: an orthographic view along the light
// over a sphere that holds them, storing the depth of the first surface the light meets. The
// surface pass reads it twice over (shaders/translucency.glsl):
//  - the depth-map method (Jimenez et al., "Real-Time Realistic Skin Translucency", IEEE CG&A
//    2010): the thickness the light crossed to reach a shaded point is its depth minus the map's;
//  - the voxel method: the entry point, the shaded point moved that far towards the light, picks
//    the row of the voxelized thickness table.
// Only translucent surfaces are drawn: an opaque object in front would otherwise count as the
// entry. Depth is linear (orthographic), so a texel's thickness error is the depth format's, not
// a perspective's.

#include <limits>
#include <span>

#include "render/frame_graph.hpp"
#include "render/passes/opacity_shadow_map_pass.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// One mesh drawn into the map: vertices with a vec3 position at offset 0, every `stride` bytes.
struct LightDepthDraw {
  vk::Buffer vertices;
  vk::Buffer indices;  ///< uint32
  std::uint32_t indexCount = 0;
  glm::mat4 model{1.0f};
};

/// The meshes a depth map is drawn over, gathered into one sphere for its view (prepare).
class DrawnBounds {
public:
  /// Adds a mesh whose vertices lie within `local` (mesh units) placed by `model`: its centre
  /// moved, its radius scaled by the largest axis scale and by `margin`.
  void add(const BoundingSphere& local, const glm::mat4& model, float margin = 1.0f);
  /// A sphere holding every mesh added (the box of their spheres, widened by 0.1 %); the unit
  /// sphere when none was.
  [[nodiscard]] BoundingSphere sphere() const;

private:
  glm::vec3 lo_{std::numeric_limits<float>::max()};
  glm::vec3 hi_{std::numeric_limits<float>::lowest()};
  bool empty_ = true;
};

/// Mirrors `LightDepth` in shaders/light_depth_uniforms.glsl (std140).
struct LightDepthUniforms {
  glm::mat4 lightFromWorld{1.0f};  ///< orthographicLightFrame of the light and the bounds
  /// x: 2R, metres per unit of depth; y: 1/resolution; z: the map's texel size, metres; w: 1 when
  /// the map holds this frame's surfaces.
  glm::vec4 scale{0.0f};
};

class LightDepthPass {
public:
  static constexpr std::uint32_t kResolution = 1024;
  static constexpr vk::Format kFormat = vk::Format::eD32Sfloat;

  /// `vertexStride`: bytes between the positions of the meshes that will be drawn.
  LightDepthPass(const Device& device, std::uint32_t vertexStride);

  /// Sets the view for the next execute: from `towardLight` (unit) over `bounds` (which must
  /// contain every vertex drawn), `drawsAnything` or not.
  void prepare(glm::vec3 towardLight, const BoundingSphere& bounds, bool drawsAnything);
  /// What execute() writes (the map), for a frame graph; it rests in SHADER_READ_ONLY layout,
  /// where readers of the map declare it.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the map of `draws` (every vertex inside prepare's bounds); the barriers around it
  /// come from a frame graph (declare).
  void execute(const vk::raii::CommandBuffer& commands, std::span<const LightDepthDraw> draws) const;

  /// Of the last prepare: what shaders need to read the map.
  [[nodiscard]] const LightDepthUniforms& uniforms() const { return uniforms_; }
  [[nodiscard]] const Image& image() const { return depth_; }
  /// Nearest filtering, clamped: depth formats need not filter linearly.
  [[nodiscard]] const vk::raii::Sampler& sampler() const { return sampler_; }

private:
  Image depth_;
  Pipeline pipeline_;
  vk::raii::Sampler sampler_{nullptr};
  LightDepthUniforms uniforms_;
};

}  // namespace mane::render
