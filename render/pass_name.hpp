#pragma once
// The name of a timed GPU pass (GpuTimer, PassTiming), as tables and logs print it. A strong
// type rather than a string, so that code that picks a pass out of a frame's timings names it
// by a constant below, and a misspelt name does not compile.

#include <compare>
#include <ostream>
#include <string_view>

namespace mane::render {

class PassName {
public:
  /// `name` must be a constant (a string literal): the pass name refers to it for its whole life.
  consteval explicit PassName(std::string_view name) : name_(name) {}

  [[nodiscard]] constexpr std::string_view name() const { return name_; }

  friend constexpr bool operator==(PassName a, PassName b) { return a.name_ == b.name_; }
  friend constexpr std::strong_ordering operator<=>(PassName a, PassName b) { return a.name_ <=> b.name_; }
  friend std::ostream& operator<<(std::ostream& out, PassName pass) { return out << pass.name_; }

  // The passes of the renderer's frame (render/renderer.hpp), in the order they can run.
  static const PassName kSkinning;           ///< skinned, morphing meshes deformed (compute)
  static const PassName kStrands;            ///< the grooms' strand interpolation (compute)
  static const PassName kHairDensity;        ///< the hair's density and what it leaves of the environment (compute)
  static const PassName kHairShadows;        ///< the hair and fur opacity shadow maps from light 0
  static const PassName kSurfaceShadows;     ///< light 0's depth map of every surface, for their soft shadows
  static const PassName kSkinDiffusion;      ///< texture-space skin: irradiance in uv space and its blurs
  static const PassName kTranslucencyDepth;  ///< light 0's depth map of the translucent surfaces
  static const PassName kOcean;  ///< the sea's grid displaced by the waves, its foam map faded and grown (compute)
  static const PassName kSkinGBuffer;        ///< the deferred skin's G-buffer, where hair follows it
  static const PassName kSurfaces;           ///< the opaque scene: its G-buffer, surfaces, discs and furs
  static const PassName kHairLighting;       ///< the hair's hiding, primitive choice and shading (compute)
  static const PassName kMainPass;           ///< deferred skin lighting, surfaces, furs and hair in one pass
  static const PassName kHair;               ///< the hair drawn over the opaque scene, when it has a pass of its own
  static const PassName kGlasses;            ///< spectacle lenses refracting the frame drawn so far
  static const PassName kPostDownsample;     ///< the post chain's quarter-size copy of the frame
  static const PassName kAutoGain;           ///< the post chain's adapted exposure
  static const PassName kGlow;               ///< the post chain's glow blurs
  static const PassName kGodRays;            ///< the post chain's light shafts
  static const PassName kPostOverlay;        ///< the post chain's overlay for the output pass
  static const PassName kOutput;             ///< tone mapping into the 8-bit output

private:
  std::string_view name_;
};

inline constexpr PassName PassName::kSkinning{"skinning"};
inline constexpr PassName PassName::kStrands{"strands"};
inline constexpr PassName PassName::kHairDensity{"hair density"};
inline constexpr PassName PassName::kHairShadows{"hair shadows"};
inline constexpr PassName PassName::kSkinDiffusion{"skin diffusion"};
inline constexpr PassName PassName::kTranslucencyDepth{"translucency depth"};
inline constexpr PassName PassName::kSurfaceShadows{"surface shadows"};
inline constexpr PassName PassName::kOcean{"ocean"};
inline constexpr PassName PassName::kSkinGBuffer{"skin g-buffer"};
inline constexpr PassName PassName::kSurfaces{"surfaces"};
inline constexpr PassName PassName::kHairLighting{"hair lighting"};
inline constexpr PassName PassName::kMainPass{"main pass"};
inline constexpr PassName PassName::kHair{"hair"};
inline constexpr PassName PassName::kGlasses{"glasses"};
inline constexpr PassName PassName::kPostDownsample{"post downsample"};
inline constexpr PassName PassName::kAutoGain{"auto gain"};
inline constexpr PassName PassName::kGlow{"glow"};
inline constexpr PassName PassName::kGodRays{"god rays"};
inline constexpr PassName PassName::kPostOverlay{"post overlay"};
inline constexpr PassName PassName::kOutput{"output"};

}  // namespace mane::render
