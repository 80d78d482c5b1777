#pragma once
// The dense-strand layout: which simulated guide strands every rendered (dense) strand follows,
// with its weights and offsets. physics builds it and evaluates it on the CPU
// (physics/interpolation.hpp, which also gives the formula); render uploads it as it is and
// evaluates the same formula on the GPU (render/passes/strand_interpolation_pass.hpp). Both take these
// types, so their elements have the bytes of the std430 buffers the shader reads
// (shaders/strand_interpolation.comp).
//
// Units: metres. Plain data: it may be built, stored, edited or uploaded; the validators below
// state the rules every consumer relies on.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane {

/// Most vertices per guide strand and per dense strand.
inline constexpr std::uint32_t kMaxStrandVertices = 4096;

/// Per guide: the two neighbouring guides whose roots span its local frame (a std430 uvec2).
/// Both equal the guide itself when it has no usable neighbours: its frame is then the fixed axes
/// (1,0,0), (0,1,0), (0,0,1).
struct GuideFrameRef {
  std::uint32_t partnerA = 0;  ///< e1 points from this guide's root to partner A's root
  std::uint32_t partnerB = 0;  ///< spans the tangent plane together with partner A
};
static_assert(sizeof(GuideFrameRef) == 8, "GuideFrameRef is a std430 uvec2");

/// One dense strand: an 80-byte std430 element, read by the shader as uvec4 (guides, guideCount),
/// vec4 (weights, vertexScale), vec4 (rootOffset, clump), vec4 (tipJitter, lengthScale),
/// vec4 (curlRadius, curlTurns, curlPhase, frizz).
struct DenseStrand {
  std::uint32_t guides[3] = {0, 0, 0};    ///< guide indices; entries k ≥ guideCount are unused
  std::uint32_t guideCount = 1;           ///< K: 1 (single) to 3 (barycentric)
  float weights[3] = {1.0f, 0.0f, 0.0f};  ///< w[k]; the first K sum to 1 (within 1e-5)
  float vertexScale = 1.0f;               ///< guide vertices per dense vertex (length scale)
  glm::vec3 rootOffset{0.0f};             ///< o, metres, in the primary guide's frame (e1, e2, n)
  float clump = 0.0f;                     ///< c in [0, 1]: 1 puts the tip on the primary guide
  glm::vec3 tipJitter{0.0f};              ///< j, metres, in the primary guide's frame
  float lengthScale = 1.0f;               ///< the strand's length relative to its guides (information)
  float curlRadius = 0.0f;                ///< metres ≥ 0: the helix the strand winds round its guides
  float curlTurns = 0.0f;                 ///< turns of the helix from root to tip, ≥ 0
  float curlPhase = 0.0f;                 ///< where the helix starts, in turns, [0, 1)
  float frizz = 0.0f;                     ///< metres ≥ 0: the largest random offset of a vertex, at the tip
};
static_assert(sizeof(DenseStrand) == 80, "DenseStrand is an 80-byte std430 element");

/// How a dense vertex between two guide vertices is placed along each guide.
enum class StrandCurve : std::uint32_t {
  kLinear = 0,      ///< on the straight segment: the guides' turns stay as sharp in the dense strands
  kCatmullRom = 1,  ///< on the uniform Catmull-Rom spline through the guide vertices: the turns round off
};

/// Everything interpolation needs, built once from the guides' rest shape.
struct DenseStrandLayout {
  std::uint32_t guideCount = 0;            ///< guides the layout was built for
  std::uint32_t guideVertexCount = 0;      ///< Ng, vertices per guide, in [2, kMaxStrandVertices]
  std::uint32_t vertexCount = 0;           ///< Nd, vertices per dense strand, in [2, kMaxStrandVertices]
  std::vector<GuideFrameRef> guideFrames;  ///< one per guide
  std::vector<DenseStrand> strands;        ///< one per dense strand
  StrandCurve curve = StrandCurve::kCatmullRom;  ///< how dense vertices follow each guide

  /// Number of dense vertices the interpolated output holds: strands × Nd.
  [[nodiscard]] std::size_t vertexTotal() const noexcept { return strands.size() * vertexCount; }
};

/// Checks a layout: not empty, vertex counts in range, a known curve, one frame per guide, guide
/// indices and frame partners in range, weights finite and summing to 1 within 1e-5, offsets
/// finite, clump in [0, 1], vertexScale keeping every dense vertex on its guides, curl radius,
/// turns and frizz finite and ≥ 0, curl phase in [0, 1). The message
/// names the first bad guide or dense strand and starts in lower case, for the caller to put its
/// own subject before.
[[nodiscard]] Result<void> validateStrandLayout(const DenseStrandLayout& layout);

/// Checks one frame's guide positions (metres, guide after guide, root first) for a layout of
/// `guideCount` guides of `guideVertexCount` vertices whose frames are `guideFrames` (a valid
/// layout's): the count is guideCount × guideVertexCount, every point is finite, and no guide's
/// root lies on one line with its frame partners' roots (its frame's normal would be zero).
/// Messages as validateStrandLayout's.
[[nodiscard]] Result<void> validateGuidePositions(std::span<const glm::vec3> guidePositions, std::uint32_t guideCount,
                                                  std::uint32_t guideVertexCount,
                                                  std::span<const GuideFrameRef> guideFrames);

}  // namespace mane
