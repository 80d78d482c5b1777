#pragma once
// How much of the environment's light the hair leaves at each point near it: the dense strands'
// optical depth gathered in a voxel grid round the grooms (shaders/hair_density_splat.comp), then,
// at each voxel, the hair's transmittance towards 16 directions reduced to its first two bands
// (shaders/hair_visibility.comp). The surfaces' and the hair's environment terms read it
// (shaders/hair_visibility.glsl).
//
// Density. A fibre of width w and opacity α, with the hair shadows' extinction κ
// (render/passes/hair_shadow_pass.hpp), casts κα of its projected area. Fibres of total length ℓ
// in a voxel of side s, turned every way, project ℓw·π/4 on average (a thin cylinder's mean
// shadow is a quarter of its surface), so a ray crossing the voxel sees an optical depth
// κα·w·(π/4)·ℓ/s². Each segment adds that for its length to the voxels it passes, in 1/2²⁰ units
// by integer atomics: the sums do not depend on the order the invocations run in.
//
// Visibility. From each voxel's centre the transmittance exp(−τ) is marched a voxel at a time
// along 16 directions of a spherical Fibonacci set, equal in weight, up to kMarchVoxels away,
// half the voxel's own depth included. Its projection on bands 0 and 1,
// V(ω) ≈ a + b·ω, is stored as occlusion (−b, 1 − a) in an RGBA16F 3D image, sampled linearly
// with a transparent black border: no occlusion outside the grid. A surface facing n receives
// a + ⅔ b·n of the environment's diffuse light (the clamped cosine's band-1 factor), a fibre a.
//
// The grid holds every groom's bounding box with a voxel to spare on each side: cubic voxels,
// kResolution of them along the box's longest side, as many as the box needs along the others,
// in the lowest corner of a kResolution³ image.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "common/error.hpp"
#include "render/frame_graph.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// Where the grid lies, as the shaders take it: uvw = (p − origin)·scale, the occlusion image's
/// coordinates (the grid fills its lowest corner; the rest holds no occlusion).
struct HairVisibilityPlacement {
  glm::vec4 origin{0.0f};  ///< xyz: the grid's lowest corner, metres
  glm::vec4 scale{0.0f};   ///< xyz: 1/(the image's side), 1/m; w: 1 where the grid holds hair this frame
};

/// An axis-aligned box, metres; empty where low > high.
struct HairBounds {
  glm::vec3 low{1.0f};
  glm::vec3 high{0.0f};
  [[nodiscard]] bool empty() const { return glm::any(glm::greaterThan(low, high)); }
};

/// A zeroed occlusion volume of side³ voxels in SHADER_READ_ONLY layout: nothing occluded, for the
/// readers' binding where a scene has no hair.
[[nodiscard]] Image clearedVisibilityVolume(const Device& device, std::uint32_t side);
/// Linear, with a transparent black border: nothing occluded outside the grid.
[[nodiscard]] vk::raii::Sampler makeVisibilitySampler(const Device& device);

class HairDensityPass {
public:
  /// Voxels along the grid's longest side, and at most along any.
  static constexpr std::uint32_t kResolution = 24;
  static constexpr std::uint32_t kMarchVoxels = 10;

  /// For `grooms` (their strands, widths, opacities and extinctions as the hair shadows take
  /// them; the positions need UNIFORM_TEXEL_BUFFER usage and must outlive the pass). Errors: no
  /// grooms, a groom without strands, a Vulkan failure.
  [[nodiscard]] static Result<std::unique_ptr<HairDensityPass>> create(const Device& device,
                                                                       std::span<const HairShadowPass::Groom> grooms);

  HairDensityPass(const HairDensityPass&) = delete;
  HairDensityPass& operator=(const HairDensityPass&) = delete;

  /// Sets this frame's grid round `bounds`, one box per groom in create()'s order; a groom whose
  /// box is empty (strands not yet placed) is left out. Between frames.
  void place(std::span<const HairBounds> bounds);
  [[nodiscard]] const HairVisibilityPlacement& placement() const { return placement_; }
  /// The voxels along each axis this frame, and their side (metres).
  [[nodiscard]] glm::uvec3 voxels() const { return voxels_; }
  [[nodiscard]] float voxelSide() const { return voxelSide_; }

  /// The three steps, each a pass of a frame graph: the density cleared, the strands splatted
  /// into it, the visibility marched from it.
  void declareClear(FrameGraph::Builder& pass) const;
  void executeClear(const vk::raii::CommandBuffer& commands) const;
  void declareSplat(FrameGraph::Builder& pass) const;
  void executeSplat(const vk::raii::CommandBuffer& commands) const;
  void declareVisibility(FrameGraph::Builder& pass) const;
  void executeVisibility(const vk::raii::CommandBuffer& commands) const;
  /// All three, outside a frame graph, with their barriers (tests).
  void record(const vk::raii::CommandBuffer& commands) const;

  /// The occlusion image (GENERAL layout once written) and its sampler, and how its readers
  /// declare it.
  [[nodiscard]] const Image& occlusion() const { return occlusion_; }
  [[nodiscard]] const vk::raii::Sampler& sampler() const { return sampler_; }
  void declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const;
  /// The density in 1/2²⁰ units of optical depth across a voxel, x fastest, over voxels() (tests).
  [[nodiscard]] const Buffer& density() const { return density_; }

private:
  struct GroomSplat {
    const Buffer* positions = nullptr;
    vk::raii::BufferView positionTexels{nullptr};
    vk::raii::DescriptorSet set{nullptr};
    std::uint32_t segments = 0;
    std::uint32_t verticesPerStrand = 0;
    float depthPerMetre = 0.0f;  // κα·w·π/4, over s² when placed
    bool placed = false;         // splatted this frame
  };

  explicit HairDensityPass(const Device& device);

  HairVisibilityPlacement placement_;
  glm::uvec3 voxels_{kResolution};
  float voxelSide_ = 1.0f;
  Buffer density_;
  vk::raii::BufferView densityTexels_{nullptr};
  Image occlusion_;
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorSetLayout splatLayout_{nullptr};
  vk::raii::DescriptorSetLayout visibilityLayout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet visibilitySet_{nullptr};
  std::vector<GroomSplat> grooms_;  // after the pool their sets come from, so that they go first
  Pipeline splat_;
  Pipeline visibility_;
};

}  // namespace mane::render
