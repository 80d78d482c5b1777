#pragma once
// Soft shadows of the opaque surfaces from the first light. A depth map of every surface along
// the light (LightDepthPass: orthographic over a sphere holding them), read by the surface shaders
// with percentage-closer soft shadows (shaders/surface_shadows.glsl; Fernando, "Percentage-Closer
// Soft Shadows", SIGGRAPH 2005 sketch), sized by the light's disc (DirectionalLight::discRadius, the
// sun's angular radius α):
//  1. Blockers: the map's depths nearer the light than the shaded point, averaged over a disc of
//     radius d·tan α around it (d: the point's depth below the map's light-side plane, the farthest
//     a blocker can be), 8 taps.
//  2. Penumbra: a blocker a distance Δ above the receiver hides the sun's disc over a band of width
//     2·Δ·tan α, so the filter's radius is Δ·tan α, and no less than kMinimumFilterTexels.
//  3. Filter: 16 taps over that disc, each a bilinear depth comparison (2 × 2 texels), turned per
//     pixel by interleaved gradient noise so that the taps' pattern does not band.
// Surfaces are offset along their normal by kNormalOffsetTexels texels before the lookup, and the
// comparison allows the depth a tilted surface spans across the filter, against self-shadowing;
// towards the terminator (N·L from 0.2 down to 0) the shadow fades out, leaving skin's
// pre-integrated light past the terminator as it was and the surface's own grazing depths unread.
// The shadow scales the first light only: hair and fur shadow through their opacity maps
// (render/passes/hair_shadow_pass.hpp).

#include <span>
#include <vector>

#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/passes/light_depth_pass.hpp"

namespace mane::render {

class SurfaceScene;

/// Mirrors `SurfaceShadow` in shaders/surface_shadow_map.glsl (std140).
struct SurfaceShadowUniforms {
  LightDepthUniforms map;  ///< the depth map's frame; map.scale.w: 1 when it holds this frame's surfaces
  /// x: tan α of the light's disc; y: the widest blocker search, map units (0..1 across); z: the
  /// smallest filter radius, map units; w: the normal offset, metres.
  glm::vec4 penumbra{0.0f};
};

class SurfaceShadowPass {
public:
  static constexpr float kMinimumFilterTexels = 2.5f;
  static constexpr float kNormalOffsetTexels = 1.5f;
  /// Past this radius the search would cost more taps than 8 cover well.
  static constexpr float kWidestSearchTexels = 48.0f;

  /// `vertexStride`: bytes between the positions of the scene's meshes.
  SurfaceShadowPass(const Device& device, std::uint32_t vertexStride);

  /// The casters of `frame` (every instance of `scene`) and the map's view from light 0; draws
  /// nothing without a light.
  void prepare(const FrameInput& frame, const SurfaceScene& scene);
  [[nodiscard]] bool drawsAnything() const { return !draws_.empty(); }
  /// What record() writes, for a frame graph.
  void declare(FrameGraph::Builder& pass) const { depth_.declare(pass); }
  void record(const vk::raii::CommandBuffer& commands) const { depth_.execute(commands, draws_); }
  /// The map's readers: the surface shaders at `stages`.
  void declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const;

  /// Of the last prepare; map.scale.w is 0 before any, and where it drew nothing.
  [[nodiscard]] const SurfaceShadowUniforms& uniforms() const { return uniforms_; }
  [[nodiscard]] const Image& image() const { return depth_.image(); }
  /// Nearest depths, for the blocker search.
  [[nodiscard]] const vk::raii::Sampler& depthSampler() const { return depth_.sampler(); }
  /// Bilinear depth comparisons (less or equal), for the filter.
  [[nodiscard]] const vk::raii::Sampler& compareSampler() const { return compare_; }

private:
  LightDepthPass depth_;
  vk::raii::Sampler compare_;
  std::vector<LightDepthDraw> draws_;
  SurfaceShadowUniforms uniforms_;
};

}  // namespace mane::render
