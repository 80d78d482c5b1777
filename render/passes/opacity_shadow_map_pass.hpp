#pragma once
// Hair self-shadowing from one directional light: opacity shadow maps (Kim & Neumann 2001) and
// deep opacity maps (Yuksel & Keyser 2008). The hair and skin passes read the result through
// shaders/opacity_shadow.glsl, which turns a world position into a transmittance
// exp(−κ·opacity) (Kim & Neumann 2001, eq. 1).
//
// Light frame. The light looks along −L (L: unit direction towards the light) at the hair's
// bounding sphere (centre C, radius R, metres). An orthographic projection maps the sphere's
// square cross-section onto the map (texel size s = 2R/resolution metres) and the depth
// d = R − (p − C)·L ∈ [0, 2R] (metres from the plane that touches the sphere on the light's side)
// onto z = d/2R ∈ [0, 1]. Points outside the sphere are outside the map: the caller's sphere
// must contain every hair vertex (boundingSphere() computes one that does).
//
// What "opacity" means. A strand is a chain of thin cylinders of radius r; every cylinder a ray
// from a point towards the light crosses adds α (the groom's opacity per crossing) to the ray's
// opacity, and the transmittance is exp(−κ·opacity). A map texel holds the expected opacity of
// the rays through its footprint, i.e. the opacity density: a strand segment of projected length
// ℓ (metres) inside a texel covers the area 2r·ℓ of the texel's s², so it deposits α·2r·ℓ/s².
// The rasterizer meets this by giving each line fragment the weight α·2r/s times the length of
// line the fragment stands for, in texels (1 for rectangular lines, strictLines; ℓ/max(|Δx|,|Δy|)
// for lines with one fragment per major-axis column). This keeps the map independent of its
// resolution; render/passes/opacity_shadow_map_reference.hpp computes the same quantity by casting rays.
//
// Modes (OpacityShadowMode):
//  - kOpacityShadowMap: 16 slices, slice k (0..15) holding the opacity of all hair with depth
//    d ≤ d_k = (k + 1)·2R/16 (Kim & Neumann 2001 §3: maps at planes evenly spaced across the
//    hair's depth range; the plane d = 0 is implicit and empty). Stored as 4 RGBA16F layers
//    (slice k = layer k/4, channel k%4), built by ONE draw of all segments into 4 colour targets
//    with additive blending: each fragment adds its weight to every slice at or beyond its depth
//    (far faster on lavapipe than a draw per slice, docs/lavapipe.md#calibration). The lookup
//    interpolates linearly in depth between slices (Kim & Neumann 2001 §3.3) and bilinearly
//    across texels.
//  - kDeepOpacityMap: a depth pass stores the nearest hair depth z0 per texel; then 4 layers
//    follow the hair's shape (Yuksel & Keyser 2008 §3): layer k (0..2) holds the opacity of hair
//    with z0 ≤ d ≤ z0 + (k + 1)·Δ, layer 3 all hair in the texel's column (the last layer reaches
//    to infinity, Yuksel & Keyser 2008 §3.2). One RGBA16F layer plus a D32 depth image. The lookup
//    interpolates linearly from 0 at z0 through the layer boundaries, per texel; the last layer's
//    hair is spread evenly from z0 + 3Δ to the far side of the sphere (so points behind the hair
//    get all of it); then bilinearly across the 4 nearest texels (each with its own z0).
//    Deep maps suit hair that forms a layer along each light ray (hair on a head); in a deep,
//    diffuse volume the 16 slices do better (tests/render/opacity_shadow_map_test.cpp).
//  - kDepthShadowMap: the deep mode's depth pass alone (z0 per texel), as a classic binary shadow
//    map, the cost baseline for the two above. The lookup gives transmittance 1 where
//    z ≤ z0 + b and 0 behind, with the bias b = 2 texels' worth of depth (2/resolution in z, so
//    that hair sloped up to 2:1 away from the map plane does not shadow itself within the 2×2
//    footprint), blended over the 4 nearest texels with bilinear weights (2×2 PCF). It holds no
//    opacity: the opacity image is a 1×1 layer of zeros, kept only so the descriptors stay valid.
// Builders (OpacityShadowBuilder), for kOpacityShadowMap:
//  - kGraphics: the one-draw pass above (line list; the vertex shader pulls both ends of its
//    segment from the position buffer, so no index buffer is needed).
//  - kCompute: one thread per segment walks the segment's columns along its major axis and covers
//    in each the texels the graphics pass's lines cover (rectangular lines: the 1–2 texels whose
//    centres lie within half a texel of the line; otherwise one), adding the fragment weight in
//    16.16 fixed point with one 32-bit atomicAdd to the first slice at or beyond its depth only;
//    a second dispatch turns these per-slice increments into the accumulated slices (a prefix
//    sum over 16 values per texel) and writes the image the graphics builder writes. Chosen over
//    per-texel loops over binned segments because it needs no binning pass and no per-bin
//    lists, costs one atomic per fragment instead of 16 blended channels, and integer atomics
//    make the map bit-identical run to run (lavapipe's float atomics are not enabled by Device).
//
// fp16: every blend rounds the running sum to 11 significant bits, so keep the opacities where
// transmittance matters (κ·opacity ≲ 10) within a few tens; the compute builder rounds once.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/frame_graph.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

enum class OpacityShadowMode : std::uint32_t {
  kOpacityShadowMap = 0,  ///< 16 slices evenly spaced across the bounding sphere (Kim & Neumann 2001)
  kDeepOpacityMap = 1,    ///< first-hair depth + 4 layers following it (Yuksel & Keyser 2008)
  kDepthShadowMap = 2,    ///< first-hair depth only: a binary shadow map (the cost baseline)
};

enum class OpacityShadowBuilder : std::uint32_t {
  kGraphics,  ///< one draw into 4 RGBA16F targets with additive blending
  kCompute,   ///< per-segment fixed-point atomics + a prefix-sum resolve (kOpacityShadowMap only)
};

/// A sphere containing all the hair, metres.
struct BoundingSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

/// The smallest-effort enclosing sphere of `positions` (xyz, metres; w ignored): centred on their
/// bounding box, radius the largest distance from it plus 0.1 % so that hair on the sphere stays
/// inside the clip volume. Fails on an empty span or non-finite positions.
[[nodiscard]] Result<BoundingSphere> boundingSphere(std::span<const glm::vec4> positions);
/// The same for xyz points (guides, say).
[[nodiscard]] Result<BoundingSphere> boundingSphere(std::span<const glm::vec3> positions);

/// The orthographic frame of a light shining along −towardLight (unit) over `sphere`: x, y across
/// the sphere's cross-section in [−1, 1], z = (R − (p − C)·L)/2R in [0, 1], 0 on the light's side,
/// so a depth z lies z·2R metres behind the sphere's light-side plane.
[[nodiscard]] glm::mat4 orthographicLightFrame(glm::vec3 towardLight, const BoundingSphere& sphere);

struct OpacityShadowSettings {
  OpacityShadowMode mode = OpacityShadowMode::kOpacityShadowMap;
  OpacityShadowBuilder builder = OpacityShadowBuilder::kGraphics;
  std::uint32_t resolution = 512;  ///< texels per side, 16 to 4096
  float strandRadius = 4e-5f;      ///< r, metres (human hair: 20–60 µm)
  float strandOpacity = 1.0f;      ///< α, opacity added per strand crossing
  float extinction = 1.0f;         ///< κ, transmittance = exp(−κ·opacity); used by the lookup
  /// Deep opacity maps: Δ, the depth of each of layers 0..2 as a fraction of the bounding
  /// sphere's diameter, in (0, 1]. The default 1/8 spans 3/8 of the diameter with 3 layers twice
  /// as deep as the 16 slices; the 4th holds the rest.
  float layerSpacing = 0.125f;
};

/// The strands the map is built from: strand-major vec4 positions (xyz metres, w ignored), as
/// StrandInterpolationPass::positions() holds them. The buffer needs STORAGE_BUFFER usage (the
/// passes read it as a storage buffer), and UNIFORM_TEXEL_BUFFER usage as well for the compute
/// builder (its splat reads it as a texel buffer), and must outlive the map.
struct OpacityShadowStrands {
  const Buffer* positions = nullptr;
  std::uint32_t strandCount = 0;
  std::uint32_t verticesPerStrand = 0;  ///< Nd ≥ 2; segments are (i, i + 1) within a strand
};

/// What the lookup needs, laid out as `OpacityShadow` in shaders/opacity_shadow.glsl (std140 and
/// std430 alike: a mat4 and two vec4s, 96 bytes). Put it in a uniform block or push constants.
struct OpacityShadowUniforms {
  glm::mat4 lightFromWorld{1.0f};  ///< world → (x, y ∈ [−1, 1] across the map, z = d/2R ∈ [0, 1])
  /// x: slices or layers (16, 4, or 1 depth); y: their spacing in z (1/16, Δ), or the depth
  /// shadow map's bias (2/resolution); z: κ; w: mode (0, 1, 2: OpacityShadowMode).
  glm::vec4 depth{0.0f};
  /// x: resolution; y: 1/resolution; z: 2R (metres); w: texel size s = 2R/resolution (metres).
  glm::vec4 texels{0.0f};
};
static_assert(sizeof(OpacityShadowUniforms) == 96);

class OpacityShadowMapPass {
public:
  static constexpr std::uint32_t kSlices = 16;     ///< opacity shadow map slices
  static constexpr std::uint32_t kDeepLayers = 4;  ///< deep opacity map layers
  static constexpr vk::Format kOpacityFormat = vk::Format::eR16G16B16A16Sfloat;
  static constexpr vk::Format kDepthFormat = vk::Format::eD32Sfloat;

  /// Builds the images and pipelines. Fails, naming the setting, on a resolution outside
  /// [16, min(4096, device limit)], a radius, opacity or extinction that is not positive and
  /// finite, a layer spacing outside (0, 1], kCompute with another mode than kOpacityShadowMap, no
  /// strands, fewer
  /// than 2 vertices per strand, a buffer smaller than the strands, or more segments than one
  /// dispatch or draw holds.
  [[nodiscard]] static Result<std::unique_ptr<OpacityShadowMapPass>> create(const Device& device,
                                                                            const OpacityShadowStrands& strands,
                                                                            const OpacityShadowSettings& settings = {});

  OpacityShadowMapPass(const OpacityShadowMapPass&) = delete;
  OpacityShadowMapPass& operator=(const OpacityShadowMapPass&) = delete;

  /// Sets the light and the hair's bounding sphere for the next record(). Fails, changing
  /// nothing, when `towardLight` is not unit length (within 1e-3) or not finite, or the sphere's
  /// radius is not positive and finite.
  [[nodiscard]] Result<void> setLight(glm::vec3 towardLight, const BoundingSphere& hair);
  /// Sets the strands' radius (OpacityShadowSettings::strandRadius, metres) for the next
  /// record(), for strands that stand for a width known only per frame. Fails, changing
  /// nothing, on a radius that is not positive and finite.
  [[nodiscard]] Result<void> setStrandRadius(float radius);

  /// What the build reads (the positions) and writes (the map and the first depth, which it
  /// leaves in SHADER_READ_ONLY layout for fragment and compute shaders and copies), for a frame
  /// graph.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the build; the barrier before it comes from a frame graph (declare). Call
  /// setLight first.
  void execute(const vk::raii::CommandBuffer& commands) const;
  /// Records the build alone (tests, benchmarks): after every earlier command, such as the
  /// interpolation or the upload of the positions.
  void record(const vk::raii::CommandBuffer& commands) const;
  /// What a shader reading the map at `stages` uses, for a frame graph.
  void declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const;

  /// The uniforms shaders/opacity_shadow.glsl reads, for the light of the last setLight.
  [[nodiscard]] const OpacityShadowUniforms& uniforms() const { return uniforms_; }
  /// The opacity map: a 2D array (4 layers of 4 slices, 1 layer of 4 deep layers, or for depth
  /// shadow maps 1 texel of zeros), RGBA16F; bind as sampler2DArray with sampler().
  [[nodiscard]] const vk::raii::ImageView& opacityView() const { return opacity_.view; }
  /// Nearest hair depth z0 per texel (deep opacity and depth shadow maps; a 1×1 image holding 1
  /// otherwise), D32:
  /// bind as sampler2D with firstDepthSampler() (the lookup reads it with texelFetch).
  [[nodiscard]] const vk::raii::ImageView& firstDepthView() const { return firstDepth_.view; }
  /// For opacityView(): linear filtering, clamped to a transparent black border (no hair outside).
  [[nodiscard]] const vk::raii::Sampler& sampler() const { return sampler_; }
  /// For firstDepthView(): nearest filtering (depth formats need not filter linearly).
  [[nodiscard]] const vk::raii::Sampler& firstDepthSampler() const { return nearest_; }

  /// The depth of slice k's far boundary, metres from the sphere's light-side plane: (k + 1)·2R/16.
  [[nodiscard]] float sliceBoundary(std::uint32_t slice) const;
  /// A world point's depth from the light, metres from the sphere's light-side plane.
  [[nodiscard]] float depthOf(glm::vec3 world) const;

  /// For tests and tools, after the recorded commands finished: the map's values, texel after
  /// texel (row-major, row 0 first), 16 slices or 4 layers per texel, as floats.
  [[nodiscard]] std::vector<float> readOpacity() const;
  /// For tests and tools: z0 per texel (deep opacity and depth shadow maps), normalised depth
  /// d/2R, 1 = no hair.
  [[nodiscard]] std::vector<float> readFirstDepth() const;
  /// For tests and tools, after the recorded commands finished: the lookup of
  /// shaders/opacity_shadow.glsl at world points (metres), run on the device by
  /// shaders/opacity_shadow_probe.comp; per point x the opacity, y the transmittance.
  [[nodiscard]] std::vector<glm::vec2> probe(std::span<const glm::vec3> points) const;

  [[nodiscard]] const OpacityShadowSettings& settings() const { return settings_; }
  [[nodiscard]] std::uint32_t segmentCount() const { return segmentCount_; }

private:
  struct ArrayImage {
    vk::raii::Image image{nullptr};
    Allocation allocation;
    vk::raii::ImageView view{nullptr};
    std::vector<vk::raii::ImageView> layerViews;  ///< one per layer (colour attachments)
    vk::Extent2D extent{};
    std::uint32_t layers = 1;
  };

  OpacityShadowMapPass(const Device& device, const OpacityShadowStrands& strands,
                       const OpacityShadowSettings& settings);
  GraphResource opacityImage() const;
  GraphResource firstDepthImage() const;
  /// Every hair segment drawn as a line with `pipeline` (one of the graphics pipelines).
  void drawSegments(const vk::raii::CommandBuffer& commands, const Pipeline& pipeline) const;
  void recordGraphics(const vk::raii::CommandBuffer& commands) const;
  void recordFirstDepth(const vk::raii::CommandBuffer& commands) const;
  void recordDeep(const vk::raii::CommandBuffer& commands) const;
  void recordCompute(const vk::raii::CommandBuffer& commands) const;

  const Device* device_;
  OpacityShadowSettings settings_;
  vk::Buffer positions_;
  std::uint32_t strandCount_;
  std::uint32_t verticesPerStrand_;
  std::uint32_t segmentCount_;
  bool strictLines_;
  BoundingSphere sphere_{};
  glm::vec3 towardLight_{0.0f, 0.0f, 1.0f};
  bool lightSet_ = false;
  OpacityShadowUniforms uniforms_;

  ArrayImage opacity_;
  ArrayImage firstDepth_;
  Buffer increments_;                             ///< kCompute: 16 fixed-point slice increments per texel
  vk::raii::BufferView positionTexels_{nullptr};  ///< kCompute: the positions as RGBA32F texels
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::Sampler nearest_{nullptr};
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Pipeline depthPipeline_;    ///< kDeepOpacityMap, kDepthShadowMap: nearest depth
  Pipeline opacityPipeline_;  ///< graphics: slices or deep layers
  Pipeline splatPipeline_;    ///< kCompute: per-segment increments
  Pipeline resolvePipeline_;  ///< kCompute: prefix sums into the image
};

}  // namespace mane::render
