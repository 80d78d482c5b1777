#pragma once
// Plain data of a hair groom as the renderer takes it: the dense-strand layout
// (common/strand_layout.hpp, the type physics builds), the look of the ribbons, and the Marschner
// preset. No Vulkan here: scenes fill these in.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "common/strand_layout.hpp"

namespace mane::render {

/// Per-groom look of the ribbons: plain data, may change every frame.
struct HairGroomSettings {
  /// Strand width at the root, metres (> 0). Human hair is 50–100 µm; grooms with fewer, thicker
  /// strands than a real head (Nalu: 4,095) use wider ones.
  float width = 1e-4f;
  /// Width at the tip over width at the root, in [0, 1]; linear in t along the strand.
  float tipWidthScale = 1.0f;
  /// Alpha of a strand at least minimumPixelWidth wide on screen, in [0, 1].
  float opacity = 1.0f;
  /// Pixels (≥ 0.25). With MSAA, the narrowest ribbon drawn: narrower strands are widened to it
  /// and their alpha scaled by true / drawn width; at 1 pixel every strand crosses one sample of
  /// each x offset per row it spans. With one sample per pixel strands keep their width (each
  /// pixel takes its covered share). Either way, a groom no wider than this on screen may be
  /// drawn as lines (render/passes/hair_pass.hpp, "Lines").
  float minimumPixelWidth = 1.0f;
  /// Strand level of detail, pixels (≥ 0; 0: every strand drawn): where the strands are
  /// narrower than this on screen at the groom's centre, only that share of them is drawn, each
  /// wider so that the groom keeps its coverage (render/strand_lod.hpp). At half a pixel the
  /// ponytail's 50,000 strands look as they do whole, for half the frame; at a pixel their sheen
  /// turns stringy.
  float lodPixelWidth = 0.5f;
  /// κ of the hair shadows: light through hair of opacity o keeps exp(−κ·o) (> 0; see
  /// render/passes/opacity_shadow_map_pass.hpp, where each strand crossing adds `opacity`).
  float shadowExtinction = 1.0f;
};

/// One dense strand's look relative to its groom's HairGroomSettings: factors, 1 leaving the
/// settings as they are, so that the groom-wide settings stay the knobs a scene or a viewer turns
/// and scale every strand alike. Groom files give strands their own widths, colours and
/// opacities this way (scenes/README.md says which file attribute becomes which factor). The
/// layout is the two vec4s per strand the hair shaders read (render/strand_looks.hpp).
struct HairStrandLook {
  float widthScale = 1.0f;     ///< × HairGroomSettings::width: the strand's root width; > 0
  float tipWidthScale = 1.0f;  ///< × HairGroomSettings::tipWidthScale; in [0, 1]
  float opacityScale = 1.0f;   ///< × HairGroomSettings::opacity; in [0, 1]
  float unused = 0.0f;
  /// Multiplies the light that crosses the fibre (the TT and TRT lobes and the ambient term);
  /// the reflection off its surface (R) keeps the light's colour. Each component in [0, 1].
  glm::vec3 colour{1.0f};
  float unused2 = 0.0f;
};
static_assert(sizeof(HairStrandLook) == 32, "two std430 vec4s per strand");

/// Which Marschner parameters a groom is shaded with (render/luts/marschner.hpp presets).
enum class HairLook : std::uint32_t {
  kBlonde = 0,  ///< low melanin: the TT and TRT highlights show
  kDark = 1,    ///< high melanin: mainly the R highlight
};

/// How a scene's hair shadows itself and the surfaces: the first light of the frame casts the
/// shadows of every groom (render/passes/opacity_shadow_map_pass.hpp); the other lights cast none.
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
/// come every frame through Renderer::updateHair.
struct HairGroomData {
  DenseStrandLayout layout;  ///< uploaded by setScene
  HairLook look = HairLook::kBlonde;
  HairGroomSettings settings;
  /// One per dense strand (layout.strands), or empty: every strand as `settings` say.
  std::vector<HairStrandLook> strandLooks;
};

}  // namespace mane::render
