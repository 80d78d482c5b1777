#pragma once
// How a groom's strands look where its files say so, resolved against the scene, then carried
// from the guide strands to the dense strands the renderer draws (render::HairStrandLook: factors
// of the groom's render::HairGroomSettings).
//
// What a file says, per strand:
// - `.hair` (Cem Yuksel's HAIR format): its thickness, transparency and colour arrays, or where
//   it has none its header's defaults. Width: the thickness at the root, in file units scaled to
//   metres as the points are (the attached mesh's scale); taper: tip thickness / root thickness,
//   in [0, 1] (the renderer narrows strands linearly, root to tip). Opacity: 1 − the mean
//   transparency along the strand. Colour: the mean colour along the strand.
// - `.tfx` (AMD TressFX): its per-strand thickness, a factor of the groom's width (TressFX's own
//   meaning of it).
// A field the scene's `render` block gives (width, tip_width_scale, opacity, colour) holds for
// every strand; the file's fills in the others; where neither says, the strand looks as the
// groom's settings alone make it. A thickness of 0 or less reads as "no width given" (what a
// writer with none leaves in the header); a width that is not finite or over
// kMaxFileStrandWidth is unusable (wrong units, most likely): the groom's width stands in, and
// the World notes it. Colours and transparencies are clamped to [0, 1].
//
// Dense strands: a dense strand follows one guide or blends up to three (common/strand_layout.hpp),
// and takes its look the same way: its guides' looks blended with its weights (one guide: that
// guide's look exactly).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "common/strand_layout.hpp"
#include "render/hair_data.hpp"
#include "scenes/groom_loader.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {

/// Widest strand a groom file may give, metres: the widest a scene's `render.width` may be.
inline constexpr float kMaxFileStrandWidth = 0.01f;

/// The looks of a groom's guide strands, one per guide in the groom's order.
struct GuideLooks {
  std::vector<render::HairStrandLook> guides;
  /// Strands whose file width was unusable (not finite, or over kMaxFileStrandWidth once in
  /// metres), drawn at the groom's width instead; the first such width, metres, for the note.
  std::size_t unusableWidths = 0;
  float firstUnusableWidth = 0.0f;

  /// A note for the World's notes when some file widths were unusable; empty otherwise.
  [[nodiscard]] std::string note() const;
};

/// Appends the looks of `file`'s strands (one per strand, in order) for a groom drawn as
/// `rendering` says, its file units `metresPerUnit` metres.
void appendFileLooks(const StrandSet& file, const GroomRendering& rendering, float metresPerUnit, GuideLooks& looks);

/// Appends `count` looks of strands no file describes (procedural guides): as the scene says.
void appendSceneLooks(std::size_t count, const GroomRendering& rendering, GuideLooks& looks);

/// The look of every dense strand of `layout`, blended from its guides' `guideLooks` (one per
/// guide of the layout) with its weights; empty where every guide's look is plain (all factors
/// 1), so that such a groom is drawn exactly as its settings alone draw it.
[[nodiscard]] std::vector<render::HairStrandLook> denseStrandLooks(const DenseStrandLayout& layout,
                                                                   std::span<const render::HairStrandLook> guideLooks);

}  // namespace mane::scenes
