#pragma once
// Dense hair strands drawn as camera-facing ribbons (shaders/hair.vert, shaders/hair.frag,
// shaders/hair_uniforms.glsl), coloured with the radiance HairLightingPass shaded at their
// vertices (render/passes/hair_lighting_pass.hpp).
//
// Input. The strands come as storage buffers in the layout of StrandInterpolationPass
// (render/passes/strand_interpolation_pass.hpp): per vertex a vec4 position (xyz metres, w = t along
// the strand, 0 root .. 1 tip), a vec4 unit tangent (xyz, root → tip) and a vec4 radiance (rgb,
// HairLightingPass::radiance()), strand-major, Nd vertices per strand. Any buffers with
// STORAGE_BUFFER usage in that layout work (tests make their own). The positions and tangents
// also need UNIFORM_TEXEL_BUFFER usage, and the radiance VERTEX_BUFFER usage: see "Lines".
//
// Ribbon expansion (vertex pulling). One indexed draw of two triangles per segment and no vertex
// buffers: hair.vert finds its strand vertex and side from the index (2 per strand vertex,
// so lavapipe's vertex cache shades each once where a plain draw of 6 corners per segment shades
// every strand vertex 12 times), reads its position and tangent, and pushes it sideways along
// s = normalize(t × ωe) (ωe: towards the eye), perpendicular to the strand and to the view, by half
// the strand width. Both segments that share a vertex compute the same offset there, so the ribbon
// has no cracks at the joints. The width is metres (HairGroomSettings::width, tapered linearly to
// tipWidthScale at t = 1).
//
// Anti-aliasing: with one sample per pixel, analytic coverage; with MSAA, coverage-scaled alpha.
// Neither uses alpha-to-coverage.
//  - One sample (HairPassSettings::samples e1): each fragment computes the share of its pixel the
//    strand covers (shaders/hair_coverage.glsl): the pixel square projected across the strand's
//    screen-space band, integrated over the band's width. The ribbon is drawn a pixel's reach
//    (half the pixel's projected extent, at most half its diagonal) wider on each side, so that
//    every pixel it touches has a fragment. A 0.3-pixel strand leaves the share of each pixel it
//    crosses that it covers, its sum along a row its exact area, and its edges are smooth at
//    any slope: what 4× MSAA approximates with four samples, at one.
//  - MSAA (4×): a ribbon narrower than minimumPixelWidth on screen (measured by projecting the
//    half-width offset) is widened to that width, and its alpha is scaled by true width / drawn
//    width, so it neither vanishes between samples nor turns into a full pixel; the edges of
//    wider ribbons are anti-aliased by the samples, in quarter-pixel steps.
//  Why not alpha-to-coverage: at 1× it degenerates to on/off per pixel (a 0.3-pixel strand is a
//  full pixel or nothing); at 4× it quantises alpha to quarters, and the alpha → sample-mask
//  mapping is implementation-defined (lavapipe keeps sample i when α > i/4, a ceiling that
//  biases thin strands up to +¼ pixel of coverage).
//
// Lines. Where every strand is at most the minimum width on screen, a line along each strand
// covers the same pixels with half the primitives (one per segment, not two triangles), which
// lavapipe's single-threaded geometry stage draws much faster. With MSAA the line is the minimum
// width; with analytic coverage, the minimum width and a pixel's diagonal (drawnLineWidth), and
// its fragments measure their distance from it along its normal, which the vertex starting the
// line carries (flat). A vertex wider on screen than the minimum is drawn by a line as if it
// were the minimum width: it loses the difference. The
// choice is made on the GPU every frame by `record` (shaders/hair_primitive.comp), from the widths
// the vertex shader computes, summed over the vertices: lines when they leave at most 1 % of the
// summed width uncovered, ribbons otherwise. A groom at or under the minimum width everywhere
// loses nothing; nalu's, whose nearest roots are up to about 1.2 pixels wide, loses well under
// 1 %. `draw` records both draws as indirect draws and the choice gives one of them no instance,
// so the frame needs no read-back. Lines are drawn only where their area is exact: rectangular
// lines (strictLines), at width 1 or with the wideLines feature within its range. The compute
// step that measures the widths also writes every vertex's clip position and coverage, which the
// line draw takes as vertex attributes (shaders/hair_line.vert) with the radiance: lavapipe runs
// vertex shaders on one thread (docs/lavapipe.md#vertex-shading-is-single-threaded), where pulling
// the strands from storage buffers a second time is expensive. That step reads the strands through texel
// buffers: lavapipe (Mesa 22.3) loads a storage buffer lane by lane in a loop, where a texel fetch
// gathers all lanes at once (docs/lavapipe.md#texel-buffers-gather-storage-buffers-loop).
//
// Hidden strands. Long hair falls behind the head and shoulders, and out of the frame: in nalu
// about half of the dense vertices. The Renderer knows opaque depth before the hair is shaded
// and drawn (the skin's, from its G-buffer pass, where the skin is deferred; else that of the
// surfaces and furs, as it splits the main pass around the hair), and reduces it to the
// farthest depth per 8 × 8 pixel tile (HairOcclusionPass). `record` then tests every segment: it is
// hidden when its pixel box on screen (its ends and the ribbon's edges, half the line width and
// a pixel for rounding more each way) lies off the screen, or only over tiles whose farthest opaque
// depth is nearer than the segment's nearest depth, less its whole depth range (samples of a
// multisampled line may lie past its ends). Those segments get no indices: the draws' index
// buffer is written every frame from the visible segments alone, strand by strand in drawing
// order (a prefix sum in a fixed order, so the frame is deterministic), and a vertex both of whose
// segments are hidden is not shaded (shadeList(), for HairLightingPass). Nothing seen changes: a
// hidden segment's fragments would all fail the depth test (tests/world/hidden_hair_test.cpp
// compares the frames with and without, byte for byte), and nalu's frame on lavapipe is faster
// (docs/performance.md#whole-frame). Moving hidden vertices beyond the far plane instead,
// leaving the indices alone, would change the frame under 4× MSAA: lavapipe then clips the whole
// line draw, which it rasterizes differently from the unclipped one.
//
// Compositing: sorted, back to front, per strand. Each strand is blended with premultiplied-alpha
// "over", depth-tested against the opaque scene (LESS_OR_EQUAL) without depth writes, in the order
// setDrawOrder gives (the Renderer sorts strands every frame by the distance of their guide's
// middle from the eye: render/hair_order.hpp). Why sorting and not an order-independent method: on
// lavapipe it costs nothing on the GPU (the index buffer is written in that order anyway; the sort
// is of guides, thousands, on the CPU), where weighted blended OIT (McGuire & Bavoil, JCGT 2013)
// needs two more colour targets and a full-screen composite (docs/lavapipe.md#full-screen-passes)
// and still only approximates the front-to-back weighting by a depth heuristic; a per-pixel linked
// list (TressFX's PPLL) needs atomics and memory per fragment. What sorting gets right and wrong:
//  - Coverage: the accumulated alpha 1 − Π(1 − α_i) does not depend on the order at all.
//  - Colour: exact where strands are separated in depth as whole strands (layers of hair, a
//    fringe in front of a face). Where two strands cross in depth along their lengths, the
//    one sorted later is drawn over the other along its whole length: the residual error is
//    the mix of lighting of such overlaps, within one groom, whose strands share a material.
//  - Without depth writes, hair does not occlude hair in the depth buffer: a later pass that
//    depth-tested against it would see only the opaque scene (no pass does).
//
// Colour: the radiance of the segment's two end vertices, interpolated linearly along it (it is
// constant across the width: see hair_lighting_pass.hpp), times the coverage alpha.
//
// Level of detail (render/strand_lod.hpp): `update` takes the share f of the strands to draw,
// which the Renderer finds from the groom's strand width on screen at its centre. The first
// step leaves out every strand whose rank is not below f as hidden (neither shaded nor drawn),
// and hairRibbon (shaders/hair_uniforms.glsl) draws the rest 1 / f times as wide.
//
// Per-strand looks (setStrandLooks, render/strand_looks.hpp): each strand's root width and tip
// width scale are the groom's times the strand's factors, and its coverage alpha is scaled by
// its opacity factor (opacity is the fraction of the ribbon the fibre covers). Without looks
// every factor is 1.
//
// Units: metres, radians, pixels where named.

#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include <glm/glm.hpp>

#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/hair_data.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// The dense strands to draw: buffers in the StrandInterpolationPass layout (see the file
/// comment). The buffers must hold strandCount × verticesPerStrand vec4s each and outlive the
/// draws that use them.
struct HairStrands {
  vk::Buffer positions;
  vk::Buffer tangents;
  vk::Buffer radiance;
  std::uint32_t strandCount = 0;
  std::uint32_t verticesPerStrand = 0;  ///< Nd ≥ 2
};

enum class HairPrimitive { kRibbons, kLines };

/// What `record` chose for the last frame it ran in, and why.
struct HairPrimitiveChoice {
  HairPrimitive primitive = HairPrimitive::kRibbons;
  std::uint32_t wideVertices = 0;  ///< dense vertices wider on screen than minimumPixelWidth
  /// The share of the strands' width on screen, summed over the vertices, that lines of the
  /// minimum width leave uncovered: Σ max(w − min, 0) / Σ w. Lines are drawn when it is ≤ 1 %.
  double uncoveredByLines = 0.0;
  /// Dense vertices both of whose segments are hidden (file comment, "Hidden strands"): behind the
  /// opaque scene (setOcclusion), off the screen, or on a strand the level of detail leaves out.
  std::uint32_t hiddenVertices = 0;
  /// The share of the strands the level of detail drew (`update`'s keptShare).
  float keptShare = 1.0f;
};

/// The farthest depth of the opaque scene per square tile of the frame (HairOcclusionPass), which
/// `record` tests the strands against.
struct HairOcclusionTiles {
  glm::uvec2 tiles{1, 1};      ///< across and down, covering the view's extent
  std::uint32_t tileSize = 8;  ///< pixels
};

/// What the pass is drawn into.
struct HairPassSettings {
  vk::Format colorFormat = vk::Format::eR16G16B16A16Sfloat;
  /// Depth tested against (not written); eUndefined for no depth attachment.
  vk::Format depthFormat = vk::Format::eD32Sfloat;
  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
};

/// Where the frame is seen from: any world → clip matrix (Vulkan clip space, depth 0..1),
/// perspective or orthographic, and the viewport it maps to.
struct HairView {
  glm::mat4 viewProjection{1.0f};
  vk::Extent2D extent{};  ///< pixels of the viewport the draw covers
};

class HairPass {
public:
  /// Builds the pipeline for `settings`. Errors: a Vulkan failure.
  [[nodiscard]] static Result<std::unique_ptr<HairPass>> create(const Device& device, const HairPassSettings& settings);

  HairPass(const HairPass&) = delete;
  HairPass& operator=(const HairPass&) = delete;

  /// Points the pass at `strands`. Errors (nothing changed): null buffers, fewer than 2
  /// vertices per strand, more ribbon indices than one draw can count (2³² − 1), or more
  /// vertices than the device's texel buffers hold (maxTexelBufferElements).
  [[nodiscard]] Result<void> setStrands(const HairStrands& strands);

  /// Each strand's width, tip width and opacity factors, from `looks` in uploadStrandLooks' layout
  /// (render/strand_looks.hpp), which must outlive the pass. Between frames, after setStrands
  /// (which goes back to factors of 1). Errors (nothing changed): no strands yet, or a buffer
  /// smaller than two texels per strand.
  [[nodiscard]] Result<void> setStrandLooks(const Buffer& looks);

  /// The order to draw the strands in, first to last: a permutation of 0..strandCount − 1
  /// (back to front for correct "over" blending). Between frames only. Errors (nothing
  /// changed): a wrong length, an index out of range or repeated.
  [[nodiscard]] Result<void> setDrawOrder(std::span<const std::uint32_t> order);

  /// Writes the frame's view, the groom's settings and the share of its strands to draw
  /// (keptStrandShare, render/strand_lod.hpp; see "Level of detail"). Call between frames,
  /// never while a draw recorded earlier is still running (one uniform buffer). Errors (nothing
  /// written): a non-invertible or non-finite view, an empty extent, groom settings out of their
  /// documented ranges, or a share outside [kLeastKeptStrands, 1].
  [[nodiscard]] Result<void> update(const HairView& view, const HairGroomSettings& groom, float keptShare = 1.0f);

  /// `update` with the frame's perspective camera (Camera::projection at the extent's aspect).
  [[nodiscard]] Result<void> update(const FrameInput& frame, vk::Extent2D extent, const HairGroomSettings& groom,
                                    float keptShare = 1.0f);

  /// The opaque scene's depth to hide strands behind (see the file comment): `tileMaxDepth` holds
  /// tiles.x × tiles.y floats, row-major, and must outlive the frames recorded with it. Until
  /// then only the segments off the screen are hidden.
  void setOcclusion(const Buffer& tileMaxDepth, const HairOcclusionTiles& tiles);

  /// What the compute steps below read (the strands, the occlusion tiles) and write (the
  /// draws, their indices, the shade list, the lines' vertices), for a frame graph.
  void declare(FrameGraph::Builder& pass) const;
  /// Records the compute steps that choose this frame's primitive, ribbons or lines, and write
  /// the indices of the visible segments and the shade list (see the file comment), outside a
  /// rendering scope, after `update` and before `draw` and HairLightingPass's dispatch; the
  /// barriers before and after them come from a frame graph (declare), those between them are
  /// the pass's own. Nothing is recorded before setStrands.
  void execute(const vk::raii::CommandBuffer& commands) const;
  /// `execute` alone (tests, benchmarks): after every earlier command, and leaving what it wrote
  /// visible to the draw, to HairLightingPass and to the host (lastChoice).
  void record(const vk::raii::CommandBuffer& commands) const;

  /// What `draw` reads (the strands, the radiance, the draws and their indices, the lines'
  /// vertices), for the frame graph's pass that draws it.
  void declareDraw(FrameGraph::Builder& pass) const;
  /// After the frame, the host reads the choice (lastChoice): the draws' buffer, for a frame graph.
  void leaveChoiceReadable(FrameGraph& graph) const;
  /// Records the draw inside a dynamic rendering scope with the formats and sample count of
  /// HairPassSettings (viewport and scissor are set to the view's extent), after `execute` in the
  /// same submission. Nothing is drawn before setStrands. The strand buffers' writes must be
  /// visible to vertex-shader storage reads, and the radiance's to vertex attribute reads
  /// (declareDraw says so to a frame graph; StrandInterpolationPass::record and
  /// HairLightingPass::record leave them so).
  void draw(const vk::raii::CommandBuffer& commands) const;

  /// The choice of the last submission that ran `record`, once it has finished.
  [[nodiscard]] HairPrimitiveChoice lastChoice() const;

  /// The vertices a visible segment uses, written by `record`, for HairLightingPass to shade
  /// (HairLightingPass::setShadeList has the layout); every vertex until then.
  [[nodiscard]] const Buffer& shadeList() const { return shadeList_; }

  /// Indices of the ribbon draw: strands × (Nd − 1) × 6, three per triangle.
  [[nodiscard]] std::uint32_t ribbonIndexCount() const { return indexCount_; }

private:
  HairPass(const Device& device, const HairPassSettings& settings);
  /// The width of the lines standing in for strands at most `minimumPixelWidth` wide: that
  /// width, or with analytic coverage, wide enough to reach every pixel such a strand touches.
  float drawnLineWidth(float minimumPixelWidth) const;
  /// Whether lines `width` pixels wide have the area of a ribbon of that width on this device.
  bool linesDrawable(float width) const;
  void writeOcclusionUniforms();
  void bindStrandLooks(const Buffer& looks);

  const Device* device_;
  vk::Extent2D extent_{};
  bool analyticCoverage_;   ///< one sample per pixel: the shaders find each pixel's coverage
  float lineWidth_ = 1.0f;  ///< drawnLineWidth of the groom's minimumPixelWidth
  float keptShare_ = 1.0f;  ///< of the last update
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  Pipeline ribbonPipeline_;
  Pipeline linePipeline_;
  Pipeline countPipeline_;   ///< hair_primitive.comp counting the wide vertices
  Pipeline choosePipeline_;  ///< hair_primitive.comp enabling one of the two draws, counting the visible segments
  Pipeline indexPipeline_;   ///< hair_primitive.comp writing the visible segments' indices
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Buffer uniforms_;
  Buffer order_;               ///< uint per strand, host-visible
  Buffer indices_;             ///< per visible segment two ribbon triangles, then per visible segment a line
  Buffer draws_;               ///< PrimitiveDraws (hair_pass.cpp), host-visible
  Buffer shadeList_;           ///< HairLightingPass::setShadeList's layout
  Buffer visibleCounts_;       ///< uint per strand
  Buffer visibleBits_;         ///< a bit per segment, per strand
  Buffer firstSegments_;       ///< per strand in drawing order: the visible segments and shaded vertices before it
  Buffer noOcclusion_;         ///< one tile at the far plane
  Buffer lineClips_;           ///< vec4 per vertex: the line draw's clip positions, written by `record`
  Buffer lineWidths_;          ///< vec4 per vertex: and its width (hair_line.vert)
  vk::Buffer positions_;       ///< the strands' positions (setStrands)
  vk::Buffer tangents_;        ///< and tangents
  vk::Buffer radiance_;        ///< the strands' radiance, the line draw's third vertex attribute
  vk::Buffer occlusionTiles_;  ///< setOcclusion's tiles
  vk::raii::BufferView positionTexels_{nullptr};  ///< the strands' positions and tangents as RGBA32F texel buffers
  vk::raii::BufferView tangentTexels_{nullptr};
  Buffer everyStrandPlain_;                    ///< looks of factor 1, until setStrandLooks
  vk::raii::BufferView strandLookTexels_{nullptr};  ///< the strands' looks as RGBA32F texels
  HairOcclusionTiles occlusion_;
  std::uint32_t strandCount_ = 0;
  std::uint32_t indexCount_ = 0;
  std::uint32_t verticesPerStrand_ = 0;
};

}  // namespace mane::render
