#pragma once
// Plain data of a hair groom as the renderer takes it: the dense-strand layout (mirroring
// physics/interpolation.hpp's types byte for byte, since render does not include physics), the
// look of the ribbons, and the Marschner preset. No Vulkan here: scenes fill these in.

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace mane::render {

/// Per guide: the two guides whose roots span its frame (mirrors physics::GuideFrameRef; a
/// std430 uvec2). Both equal the guide itself when it has no usable neighbours: its frame is
/// then the fixed axes (1,0,0), (0,1,0), (0,0,1).
struct GuideFrameRef {
  std::uint32_t partnerA = 0;  ///< e1 points from the guide's root to partner A's root
  std::uint32_t partnerB = 0;  ///< spans the tangent plane together with partner A
};
static_assert(sizeof(GuideFrameRef) == 8, "GuideFrameRef is a std430 uvec2");

/// One dense strand (mirrors physics::DenseStrand field for field): a 64-byte std430 element,
/// read by the shader as uvec4 (guides, guideCount), vec4 (weights, vertexScale),
/// vec4 (rootOffset, clump), vec4 (tipJitter, lengthScale).
struct DenseStrand {
  std::uint32_t guides[3] = {0, 0, 0};    ///< guide indices; entries k ≥ guideCount are unused
  std::uint32_t guideCount = 1;           ///< K: 1 (single) to 3 (barycentric)
  float weights[3] = {1.0f, 0.0f, 0.0f};  ///< w[k]; the first K sum to 1 (within 1e-5)
  float vertexScale = 1.0f;               ///< guide vertices per dense vertex (length scale)
  glm::vec3 rootOffset{0.0f};             ///< o, metres, in the primary guide's frame (e1, e2, n)
  float clump = 0.0f;                     ///< c in [0, 1]: 1 puts the tip on the primary guide
  glm::vec3 tipJitter{0.0f};              ///< j, metres, in the primary guide's frame
  float lengthScale = 1.0f;               ///< the strand's length relative to its guides (unused)
};
static_assert(sizeof(DenseStrand) == 64, "DenseStrand is a 64-byte std430 element");

/// A dense groom layout, viewed (mirrors physics::DenseGroomLayout). `create` copies it.
struct DenseStrandLayout {
  std::uint32_t guideCount = 0;                ///< guides
  std::uint32_t guideVertexCount = 0;          ///< Ng, vertices per guide, in [2, 4096]
  std::uint32_t vertexCount = 0;               ///< Nd, vertices per dense strand, in [2, 4096]
  std::span<const GuideFrameRef> guideFrames;  ///< one per guide
  std::span<const DenseStrand> strands;        ///< one per dense strand
};

/// Per-groom look of the ribbons: plain data, may change every frame.
struct HairGroomSettings {
  /// Strand width at the root, metres (> 0). Human hair is 50–100 µm; grooms with fewer, thicker
  /// strands than a real head (Nalu: 4,095) use wider ones.
  float width = 1e-4f;
  /// Width at the tip over width at the root, in [0, 1]; linear in t along the strand.
  float tipWidthScale = 1.0f;
  /// Alpha of a strand at least minimumPixelWidth wide on screen, in [0, 1].
  float opacity = 1.0f;
  /// Narrowest ribbon drawn, pixels (≥ 0.25); narrower strands are widened to it and their alpha
  /// scaled by true / drawn width. 1 pixel: every strand crosses a pixel centre (or, at 4×
  /// MSAA, one sample of each x offset) per row it spans.
  float minimumPixelWidth = 1.0f;
  /// κ of the hair shadows: light through hair of opacity o keeps exp(−κ·o) (> 0; see
  /// render/passes/opacity_shadow_map.hpp, where each strand crossing adds `opacity`).
  float shadowExtinction = 1.0f;
};

/// Which Marschner parameters a groom is shaded with (render/luts/marschner.hpp presets).
enum class HairLook : std::uint32_t {
  kBlonde = 0,  ///< low melanin: the TT and TRT highlights show
  kDark = 1,    ///< high melanin: mainly the R highlight
};

/// How a scene's hair shadows itself and the surfaces: the first light of the frame casts the
/// shadows of every groom (render/passes/opacity_shadow_map.hpp); the other lights cast none.
enum class HairShadowMode : std::uint32_t {
  kOff = 0,
  kOpacityShadowMap = 1,  ///< 16 slices across the hair's bounding sphere (Kim & Neumann 2001)
  kDeepOpacityMap = 2,    ///< first-hair depth + 4 layers following it (Yuksel & Keyser 2008)
};

struct HairShadowSettings {
  HairShadowMode mode = HairShadowMode::kOpacityShadowMap;
  std::uint32_t resolution = 512;  ///< texels per side of each groom's map, 16 to 4096
};

/// A groom the renderer draws: dense strands interpolated on the GPU from the guides, which
/// come every frame through Renderer::updateHair. The spans must stay valid during setScene.
struct HairGroomData {
  DenseStrandLayout layout;
  HairLook look = HairLook::kBlonde;
  HairGroomSettings settings;
};

}  // namespace mane::render
