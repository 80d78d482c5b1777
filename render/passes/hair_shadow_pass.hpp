#pragma once
// The hair shadows of a frame: one opacity (or deep opacity) shadow map per groom, all cast by
// the frame's first light, and what the shaders that receive them bind (shaders/hair_shadows.glsl).
//
// A point's transmittance towards the light is the product of the grooms' transmittances,
// exp(−Σ κ_g·o_g): light crossing two grooms is attenuated by both, whatever their order.
// Slots without a map (fewer grooms than kMaxMaps, shadows off, or a groom whose guides have not
// arrived yet) bind a 1×1 empty map with κ = 0, so every descriptor is valid and the product
// skips them.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "render/frame_graph.hpp"
#include "render/hair_data.hpp"
#include "render/passes/opacity_shadow_map_pass.hpp"
#include "render/pipelines.hpp"

namespace mane::render {

/// Mirrors `HairShadowUniforms` in shaders/hair_shadows.glsl (std140): 400 bytes.
struct HairShadowUniforms {
  std::array<OpacityShadowUniforms, 4> maps{};
  glm::uvec4 count{0u};  ///< x: slots in use (the rest have κ = 0)
};
static_assert(sizeof(HairShadowUniforms) == 4 * 96 + 16);

class HairShadowPass {
public:
  static constexpr std::uint32_t kMaxMaps = 4;  ///< grooms beyond the 4th cast no shadow
  /// Descriptors a receiving shader binds from its first shadow binding on: kMaxMaps opacity
  /// arrays, then kMaxMaps first-depth images (shaders/hair_shadows.glsl).
  static constexpr std::uint32_t kBindings = 2 * kMaxMaps;

  /// Errors: a Vulkan failure while creating the empty map.
  [[nodiscard]] static Result<std::unique_ptr<HairShadowPass>> create(const Device& device);

  HairShadowPass(const HairShadowPass&) = delete;
  HairShadowPass& operator=(const HairShadowPass&) = delete;

  /// Drops the maps and makes one per groom (the first kMaxMaps), in `settings`' mode at its
  /// resolution; none when the mode is kOff. Each groom's strands are drawn with radius
  /// width/2 and opacity per crossing `opacity`, and its shadow has extinction κ. Errors name
  /// the groom.
  struct Groom {
    OpacityShadowStrands strands;
    float width = 0.0f;
    float opacity = 1.0f;
    float extinction = 1.0f;
    /// Texels per side of its map, at most the settings' (0: the settings'): coarser for casters
    /// whose strands are sparse, so that each texel holds one and the shadow has no gaps.
    std::uint32_t resolution = 0;
  };
  [[nodiscard]] Result<void> setGrooms(std::span<const Groom> grooms, const HairShadowSettings& settings);

  /// Groom `groom`'s hair lies inside `hair` for the next record(). From the first call on, its
  /// slot binds its map (rewrite the descriptors then: writeDescriptors). Between frames only.
  /// Ignored for grooms without a map. Errors: a sphere that is not finite and positive.
  [[nodiscard]] Result<void> setBounds(std::size_t groom, const BoundingSphere& hair);
  /// Groom `groom`'s strands stand for `width` metres from the next record() on (Groom::width,
  /// for casters whose width follows their placement). Ignored for grooms without a map. Errors:
  /// a width that is not positive and finite.
  [[nodiscard]] Result<void> setStrandWidth(std::size_t groom, float width);
  /// Groom `groom` casts nothing from the next record() on, until setBounds places it again
  /// (a fur whose instance left the frame).
  void clearBounds(std::size_t groom);

  /// Points the map of every groom with bounds at `towardLight` (unit, world space) for the
  /// next execute(), and sets uniforms() for it.
  void prepare(glm::vec3 towardLight);
  /// What execute() reads and writes (each map's strands and images), for a frame graph.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the build of every map prepare() pointed at the light; the barriers before it come
  /// from a frame graph (declare), those after it are the maps' own (OpacityShadowMapPass::execute).
  void execute(const vk::raii::CommandBuffer& commands) const;
  /// prepare and execute alone (tests, benchmarks): after every earlier command.
  void record(const vk::raii::CommandBuffer& commands, glm::vec3 towardLight);
  /// The maps a shader reading the shadows at `stages` sees this frame, for a frame graph.
  void declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const;

  /// The uniforms of the maps as of the last prepare().
  [[nodiscard]] const HairShadowUniforms& uniforms() const { return uniforms_; }

  /// Writes the kBindings descriptors into `set` from `firstBinding` on.
  void writeDescriptors(const vk::raii::DescriptorSet& set, std::uint32_t firstBinding) const;

  [[nodiscard]] std::size_t mapCount() const { return maps_.size(); }
  /// Specialization constants 0 and 1 of shaders/hair_shadows.glsl for the current maps: their
  /// count and mode. Pipelines that receive the shadows are built with them after setGrooms.
  [[nodiscard]] SpecializationConstants shaderConstants() const;
  [[nodiscard]] const OpacityShadowMapPass& map(std::size_t groom) const { return *maps_[groom].map; }

private:
  explicit HairShadowPass(const Device& device);

  struct GroomMap {
    std::unique_ptr<OpacityShadowMapPass> map;
    std::optional<BoundingSphere> bounds;  ///< set: built every frame and bound
    bool lit = false;                      ///< prepare() pointed it at the light: execute() builds it
  };

  const Device* device_;
  std::vector<GroomMap> maps_;
  HairShadowMode mode_ = HairShadowMode::kOff;
  HairShadowUniforms uniforms_;
  // The empty map: one transparent RGBA16F layer and a depth of 1 ("no hair").
  vk::raii::Image emptyOpacity_{nullptr};
  Allocation emptyOpacityMemory_;
  vk::raii::ImageView emptyOpacityView_{nullptr};
  vk::raii::Image emptyDepth_{nullptr};
  Allocation emptyDepthMemory_;
  vk::raii::ImageView emptyDepthView_{nullptr};
  vk::raii::Sampler emptySampler_{nullptr};
};

}  // namespace mane::render
