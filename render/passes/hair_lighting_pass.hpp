#pragma once
// Marschner shading of dense hair at its vertices (shaders/hair_lighting.comp), before the
// ribbons are drawn (render/passes/hair_pass.hpp), which interpolate it along each segment.
//
// Why per vertex. The scattering S(ωi, ωr) of a fibre depends only on its tangent and the light
// and view directions (the azimuthal integral is inside N), so it is the same across a ribbon's
// width and changes only as the tangent turns along the strand. One evaluation per vertex, in a
// compute pass that spreads over all cores, replaces one per fragment: on lavapipe, hair
// fragments are many times the ribbon's pixel area (the rasterizer shades whole pixel blocks of
// thin, overlapping ribbons, docs/lavapipe.md#thin-strands), so shading per fragment would
// dominate the hair draw. The lookups read the LUT mip level that matches how far the
// tangent turns over the vertex's share of the strand, so curls filter instead of aliasing.
//
// Per vertex, written to radiance() (vec4, strand-major like the positions):
//   rgb = Σ_lights S(ωi, ωr, t) · E_i · (T for the first light) + La · A,   a = T,
// with E_i the light's perpendicular irradiance (colour × intensity), T the hair shadows'
// transmittance (render/passes/hair_shadow_pass.hpp) at the vertex, La the ambient radiance and A the
// groom's white-furnace albedo at θr = 0 (render/luts/marschner.hpp, azimuthalAlbedo). ωr points
// from the vertex to the eye. Under an environment, rgb adds its light scattered by the three
// lobes (render/luts/hair_environment.hpp), times what the hair leaves of it at the vertex
// (setHairVisibility). A strand's colour (setStrandLooks, HairStrandLook::colour)
// multiplies the TT and TRT lobes of S and the ambient term: the light that has crossed fibres.
// The R lobe, reflected off the fibre's surface before entering it, keeps the light's colour.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include <glm/glm.hpp>

#include "render/environment/spherical_harmonics.hpp"
#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/luts/hair_environment.hpp"
#include "render/luts/marschner_lut.hpp"
#include "render/passes/hair_density_pass.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

class HairLightingPass {
public:
  /// Lights read per frame; more are ignored. Must match shaders/hair_lighting.comp.
  static constexpr std::size_t kMaxLights = 4;
  /// The environment's band weights as the shader reads them: per θr sample k and band l, vector
  /// 3k + l holds (TT + TRT per RGB, R).
  using EnvironmentBands = std::array<glm::vec4, 3 * kHairEnvironmentSamples>;

  /// Shades the strands in `positions` and `tangents` (StrandInterpolationPass layout: vec4 per
  /// vertex, strand-major, `verticesPerStrand` per strand; read as texel buffers, so they need
  /// UNIFORM_TEXEL_BUFFER usage, as does a shade list) with `lut`'s model, receiving
  /// `shadows` (its maps as they are now: create the pass after HairShadowPass::setGrooms); all
  /// three must outlive the pass. Errors: no vertices, fewer than 2 per strand,
  /// buffers smaller than the strands, a Vulkan failure.
  [[nodiscard]] static Result<std::unique_ptr<HairLightingPass>> create(const Device& device, const MarschnerLut& lut,
                                                                        const HairShadowPass& shadows,
                                                                        const Buffer& positions, const Buffer& tangents,
                                                                        std::uint32_t strandCount,
                                                                        std::uint32_t verticesPerStrand);

  HairLightingPass(const HairLightingPass&) = delete;
  HairLightingPass& operator=(const HairLightingPass&) = delete;

  /// The frame's eye (from `viewProjection`, see hairEye), lights (the first kMaxLights),
  /// ambient radiance and shadow uniforms, and the environment (setEnvironment). Between frames only (one uniform
  /// buffer). Errors: a light direction that is not finite and non-zero.
  [[nodiscard]] Result<void> update(const glm::mat4& viewProjection, std::span<const DirectionalLight> lights,
                                    glm::vec3 ambient, const HairShadowUniforms& shadows);

  /// The environment's irradiance over π (EnvironmentPass::irradianceOverPi) that lights the hair
  /// from the next update() on, or none. Each vertex adds the environment's radiance scattered by
  /// the groom's lobes towards the eye (render/luts/hair_environment.hpp: each band at the tangent
  /// weighed by the lobes' cones at the eye's θr), on top of the ambient radiance.
  /// The lobes' band weights are baked the first time an environment comes.
  void setEnvironment(const std::optional<SphericalHarmonics9>& irradianceOverPi);

  /// The hair's occlusion volume that hides part of the environment from each vertex, or none;
  /// update() takes its placement as it is then. It must outlive its use; between frames.
  void setHairVisibility(const HairDensityPass* visibility);

  /// Re-reads the shadow maps' descriptors (after HairShadowPass' slots changed). Between frames.
  void refreshShadows();

  /// The vertices to shade (HairPass::shadeList); the others keep their radiance. The list's
  /// layout: a VkDispatchIndirectCommand of workgroups of kWorkgroupSize, the count of vertices
  /// listed, then their indices (uint each); UNIFORM_TEXEL_BUFFER usage. It must outlive the
  /// pass. Until then every vertex is shaded.
  void setShadeList(const Buffer& shadeList);

  /// Each strand's colour, from `looks` in uploadStrandLooks' layout (render/strand_looks.hpp),
  /// which must outlive the pass; until then every strand's colour is 1 (the preset's own).
  /// Between frames. Errors (nothing changed): a buffer smaller than two texels per strand.
  [[nodiscard]] Result<void> setStrandLooks(const Buffer& looks);

  /// A shade list of every vertex 0 .. vertices − 1.
  [[nodiscard]] static Buffer everyVertex(const Device& device, std::uint32_t vertices);

  static constexpr std::uint32_t kWorkgroupSize = 64;  ///< local_size_x of shaders/hair_lighting.comp

  /// What the dispatch reads (the strands, the shade list, the shadow maps) and writes (the
  /// radiance), for a frame graph.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the dispatch; the barriers around it come from a frame graph (declare).
  void execute(const vk::raii::CommandBuffer& commands) const;
  /// Records the dispatch alone (tests, benchmarks): after every earlier command (the
  /// interpolation, the shadow maps, HairPass's shade list), leaving radiance() visible to
  /// vertex-shader storage reads, vertex attribute reads and copies.
  void record(const vk::raii::CommandBuffer& commands) const;

  /// vec4 per vertex: rgb radiance towards the eye, a the first light's shadow transmittance.
  [[nodiscard]] const Buffer& radiance() const { return radiance_; }

private:
  HairLightingPass(const Device& device, const MarschnerLut& lut, const HairShadowPass& shadows,
                   const Buffer& positions, const Buffer& tangents, std::uint32_t vertexCount,
                   std::uint32_t verticesPerStrand);
  void bindStrandLooks(const Buffer& looks);

  const Device* device_;
  const HairShadowPass* shadows_;
  const Buffer* positions_;
  const Buffer* tangents_;
  glm::vec3 ambientAlbedo_{0.0f};
  HairShadingParams params_;
  std::optional<EnvironmentBands> environmentBands_;  // baked with the first environment
  std::optional<SphericalHarmonics9> environment_;
  std::uint32_t verticesPerStrand_;
  Buffer radiance_;
  Buffer uniforms_;
  vk::raii::BufferView uniformTexels_{nullptr};    ///< uniforms_ as RGBA32UI texels, how the shader reads them
  vk::raii::BufferView positionTexels_{nullptr};   ///< the strands' positions, RGBA32F texels
  vk::raii::BufferView tangentTexels_{nullptr};    ///< and their tangents
  vk::raii::BufferView shadeListTexels_{nullptr};  ///< the shade list, R32UI texels
  Buffer everyVertex_;                             ///< the shade list until setShadeList
  Buffer everyStrandPlain_;                        ///< looks of factor 1, until setStrandLooks
  vk::raii::BufferView strandLookTexels_{nullptr};  ///< the strands' looks, RGBA32F texels
  const Buffer* shadeList_ = nullptr;
  const HairDensityPass* hairVisibility_ = nullptr;
  Image noHairVisibility_;  ///< bound where there is no occlusion volume
  vk::raii::Sampler hairVisibilitySampler_{nullptr};
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Pipeline pipeline_;
};

/// The eye of a world → clip matrix: the point (w = 1) or, for an orthographic projection, the
/// unit direction towards the eye (w = 0) that projects to clip (0, 0, 1, 0).
[[nodiscard]] glm::vec4 hairEye(const glm::mat4& viewProjection);

}  // namespace mane::render
