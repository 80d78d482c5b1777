#pragma once
// Texture-space diffusion for skin, after
//   [dEL07] d'Eon & Luebke, "Advanced Techniques for Realistic Real-Time Skin Rendering",
//           GPU Gems 3, ch. 14 (2007), §14.4–14.5.
// Subsurface scattering as a blur of irradiance over the surface, done in the mesh's texture
// space where the surface lies flat:
//  1. Irradiance (recordIrradiance, shaders/skin_irradiance.{vert,frag}): the mesh is drawn at its
//     uvs into an RGBA16F map, rgb E = ambient + Σ max(N·L, 0)·radiance (N the interpolated
//     normal, or the normal map's), a = coverage (1 on the mesh, 0 elsewhere); and into an RG16F
//     stretch map, the millimetres of surface one texel spans along u and along v, from the
//     derivatives of the world position (exact and constant per triangle).
//  2. Blurs (recordBlurs, shaders/skin_diffusion_blur.comp): the profile's six Gaussians as a
//     cascade of separable blurs, along u then v, 12 dispatches; each blur's width in texels is
//     σ_mm / stretch at the texel, so the blur has one width in millimetres over the whole face
//     ([dEL07] §14.4.2). The taps and their accuracy: render/passes/skin_diffusion_kernel.hpp.
//     After each Gaussian its result is added into running sums with the profile's RGB weights,
//     and the last blur divides (below). The result: diffusedIrradiance(), per texel the light
//     that leaves the skin there before it is coloured by the albedo; a final pass samples it at
//     the fragment's uv and multiplies by the albedo ("post-scatter" texturing, [dEL07] §14.5.2).
//
// Seams. Each island of the uv layout is drawn with a skirt: the surface across its seams,
// unfolded past its border and drawn behind the islands (render/passes/skin_uv_seams.hpp), so the
// irradiance map holds, around each island, the light of the skin that lies there. The blurs
// then carry light across the seams as across any other line of the surface. The blurs also
// treat the coverage c as a weight (normalised convolution): they blur E·c and c alike, and the
// result is Σ_i w_i·blur_i(E·c) / Σ_i w_i·blur_i(c) per RGB, so where the map holds nothing (no
// skirt reaches: a border of the mesh, the map's edge) the black is never averaged in and the
// island's border keeps its brightness. Texels off the mesh have no stretch;
// they blur with the mesh's mean stretch (SkinDiffusionMesh::uvScale).
//
// Cost: the blurs dominate and grow with the map's area (skin_diffusion_test prints their GPU time;
// docs/performance.md has the figures). Memory: seven size² images (the irradiance, the
// stretch at half the bytes, the draw's 16-bit depth, four for the blurs): 46 MiB at 1024²,
// 184 MiB at 2048². One pass holds one mesh's maps: one pass object per skin mesh.
//
// Shadows: the hair shadows (render/passes/hair_shadow_pass.hpp) attenuate the first light in the
// irradiance, so the blurs soften their edges by the profile's widths, red most: texture-space
// soft shadows ([dEL07] §14.4.4).
//
// Not implemented: "pre-scatter" albedo, and the blurring of the stretch map itself.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/luts/skin_profile.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/passes/skin_diffusion_kernel.hpp"
#include "render/passes/skin_diffusion_mesh.hpp"
#include "render/passes/surface_shadow_pass.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

struct SkinDiffusionSettings {
  /// Texels per side of the texture-space maps: 1024 by default, 2048 for the high-quality look
  /// (4× the blur time). A multiple of 8 from kMinSize to kMaxSize, within the device's limits.
  std::uint32_t size = 1024;
  /// The Gaussians, their weights and the millimetres per world unit.
  SkinProfile profile;

  static constexpr std::uint32_t kMinSize = 16;
  static constexpr std::uint32_t kMaxSize = 8192;
};

/// An error naming the bad field: a size outside [kMinSize, kMaxSize] or not a multiple of 8 (the
/// blurs' workgroups), or a profile that validate(SkinProfile) rejects.
[[nodiscard]] Result<void> validate(const SkinDiffusionSettings& settings);

/// What lights one mesh instance's irradiance.
struct SkinIrradianceInput {
  glm::mat4 model{1.0f};                     ///< object → world; world units are the profile's (metres by default)
  std::span<const DirectionalLight> lights;  ///< the first SkinDiffusionPass::kMaxLights are used
  glm::vec3 ambient{0.0f};                   ///< linear RGB irradiance added everywhere
  /// Whether the surfaces' shadow map holds this frame's surfaces, to shadow light 0 with (the
  /// renderer declares the map's read).
  bool surfaceShadows = false;
};

class SkinDiffusionPass {
public:
  static constexpr std::size_t kMaxLights = 4;  ///< kSkinIrradianceMaxLights in the shaders
  static constexpr vk::Format kIrradianceFormat = vk::Format::eR16G16B16A16Sfloat;
  static constexpr vk::Format kStretchFormat = vk::Format::eR16G16Sfloat;
  /// Which of the mesh's triangles and seam skirts owns a texel (skin_uv_seams.hpp).
  static constexpr vk::Format kSeamDepthFormat = vk::Format::eD16Unorm;

  /// Makes the maps (cleared to 0) and pipelines. `shadows` (which must outlive the pass)
  /// attenuates the first light, with its maps as they are now (create the pass after
  /// HairShadowPass::setGrooms); none: no hair shadows. `surfaceShadows` (likewise) shadows it
  /// where SkinIrradianceInput::surfaceShadows says; none: no surface shadows. Errors: invalid
  /// settings, a size past the device's image or framebuffer limits, a device that cannot render
  /// to, store to or linearly filter the formats, or a Vulkan failure.
  [[nodiscard]] static Result<SkinDiffusionPass> create(const Device& device,
                                                        const SkinDiffusionSettings& settings = {},
                                                        const HairShadowPass* shadows = nullptr,
                                                        const SurfaceShadowPass* surfaceShadows = nullptr);

  /// Re-reads the hair shadow maps' descriptors (after their slots changed). Between frames.
  void refreshShadows();

  SkinDiffusionPass(SkinDiffusionPass&&) noexcept = default;
  SkinDiffusionPass& operator=(SkinDiffusionPass&&) noexcept = default;

  /// The normal map that tilts N in the irradiance (tangent space, +Y up, as MaterialData's);
  /// nullopt for the interpolated normals. Between frames. Errors: texels that do not match the
  /// size, or a Vulkan failure.
  [[nodiscard]] Result<void> setNormalMap(const std::optional<TextureData>& normalMap);

  /// Draws `mesh` at its uvs into the irradiance and stretch maps, leaving them ready for the
  /// blurs (the irradiance GENERAL, the stretch SHADER_READ_ONLY). The uniforms travel in the
  /// command buffer (vkCmdUpdateBuffer), so recording never waits; but one pass object serves one
  /// frame in flight at a time. Outside rendering.
  void recordIrradiance(const vk::raii::CommandBuffer& commands, const SkinDiffusionMesh& mesh,
                        const SkinIrradianceInput& input);
  /// The twelve blurs of the irradiance map into diffusedIrradiance(), which is then
  /// SHADER_READ_ONLY, visible to fragment and compute shaders. Outside rendering.
  void recordBlurs(const vk::raii::CommandBuffer& commands) const;
  /// What `record` reads of other passes (the hair shadows) and leaves for them
  /// (diffusedIrradiance(), made visible by its own barrier), for a frame graph; the maps only
  /// it uses are its own business.
  void declare(FrameGraph::Builder& pass) const;
  /// What a shader sampling diffusedIrradiance() at `stages` reads, for a frame graph.
  void declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const;
  /// recordIrradiance, then recordBlurs.
  void record(const vk::raii::CommandBuffer& commands, const SkinDiffusionMesh& mesh,
              const SkinIrradianceInput& input) {
    recordIrradiance(commands, mesh, input);
    recordBlurs(commands);
  }

  /// The diffused irradiance: rgb linear irradiance, a the least of the RGB kernels' covered
  /// share (0 off the islands' reach). SHADER_READ_ONLY; sample it with sampler().
  const vk::raii::ImageView& diffusedIrradiance() const { return accumulated_.view(); }
  /// Bilinear, clamped to the edge.
  const vk::raii::Sampler& sampler() const { return sampler_; }
  const SkinDiffusionSettings& settings() const { return settings_; }
  /// The blurs in the order they run, with their widths and weights.
  const std::array<SkinDiffusionStage, kSkinGaussianCount>& stages() const { return stages_; }

  /// Replaces the irradiance and stretch maps with texels (row-major, size² each, see
  /// SkinDiffusionMaps), for tests and tools that feed the blurs directly; waits for the GPU.
  /// Texels off the mesh then blur with skinUncoveredStretch(stretch). Errors: counts that are
  /// not size², values that are not finite, or a Vulkan failure.
  [[nodiscard]] Result<void> setMaps(std::span<const glm::vec4> irradiance, std::span<const glm::vec2> stretch);
  /// The maps read back (waits for the GPU), row-major, half floats widened. Call between frames.
  [[nodiscard]] Result<std::vector<glm::vec4>> readIrradiance() const;
  [[nodiscard]] Result<std::vector<glm::vec2>> readStretch() const;
  [[nodiscard]] Result<std::vector<glm::vec4>> readDiffusedIrradiance() const;

private:
  SkinDiffusionPass() = default;
  /// What blur i along v does with the sums (kAccumulate* in shaders/skin_diffusion_blur.comp).
  enum class Accumulate : int { kNone = 0, kFirst = 1, kAdd = 2, kResolve = 3 };
  Accumulate accumulation(std::size_t stage) const {
    return stage == 0 ? Accumulate::kFirst : stage + 1 == stages_.size() ? Accumulate::kResolve : Accumulate::kAdd;
  }
  void createResources();

  const Device* device_ = nullptr;
  SkinDiffusionSettings settings_;
  const HairShadowPass* shadows_ = nullptr;
  std::unique_ptr<HairShadowPass> noShadows_;  ///< the empty maps bound when created without shadows
  const SurfaceShadowPass* surfaceShadows_ = nullptr;
  std::unique_ptr<SurfaceShadowPass> noSurfaceShadows_;  ///< the map bound, never read, when created without one
  std::array<SkinDiffusionStage, kSkinGaussianCount> stages_{};
  double uncoveredStretch_ = 1.0;  ///< mm per texel for texels off the mesh

  Image irradiance_;   ///< rgb E·c, a c; GENERAL between frames (the blurs load it)
  Image stretch_;      ///< mm per texel along u, v
  Image seamDepth_;    ///< the irradiance draw's depth: 0 on the mesh, the distance to a seam on its skirts
  Image across_;       ///< a Gaussian's blur along u
  Image blurred_;      ///< the last Gaussian completed: the next one's input
  Image accumulated_;  ///< Σ w·blur(E·c); after the resolve, the diffused irradiance
  Image coverage_;     ///< Σ w·blur(c), per RGB
  vk::raii::Sampler sampler_{nullptr};

  Buffer uniforms_;
  Image flatNormal_;
  Image normalMap_;
  bool hasNormalMap_ = false;
  vk::raii::Sampler normalSampler_{nullptr};

  vk::raii::DescriptorSetLayout irradianceLayout_{nullptr};
  vk::raii::DescriptorSetLayout meshVerticesLayout_{nullptr};  ///< set 1, SkinDiffusionMesh::verticesSet()
  vk::raii::DescriptorSetLayout blurLayout_{nullptr};
  Pipeline irradiancePipeline_;
  /// [dense taps][Accumulate]: the variants the stages use (the others stay null).
  std::array<std::array<Pipeline, 4>, 2> blurPipelines_;
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet irradianceSet_{nullptr};
  vk::raii::DescriptorSet firstAcross_{nullptr};  ///< irradiance → across (the first Gaussian)
  vk::raii::DescriptorSet laterAcross_{nullptr};  ///< blurred → across
  vk::raii::DescriptorSet down_{nullptr};         ///< across → blurred, and the sums
};

}  // namespace mane::render
