#pragma once
// Private to subdiv/: how the sides of ptex faces line up, so that a tessellator can give a
// point on a shared side one name (and so one vertex) whichever face it comes from.
//
// Points of a ptex face are addressed on an integer grid, (i, j) ∈ [0, kGrid]², u = i/kGrid,
// v = j/kGrid. Every side of every ptex face lies on a *line*: a cage edge (parameter 0 at
// its lower-numbered vertex, kLineLength at the other), or a *spoke* of an n-gon (the inner
// side between two of its sub-faces: 0 at the midpoint of the n-gon's edge, kLineLength at
// its centre). A quad's side covers a whole cage edge; an n-gon sub-face's outer sides cover
// half of one. All conversions are exact integer arithmetic.

#include <array>
#include <cstdint>
#include <vector>

#include "subdiv/cage.hpp"

namespace mane::subdiv::detail {

inline constexpr std::uint32_t kGridBits = 12;
inline constexpr std::int64_t kGrid = std::int64_t(1) << kGridBits;
inline constexpr std::int64_t kLineLength = 2 * kGrid;
/// Leaves of at least 4 grid cells keep every point integer on both sides of a line, since
/// an n-gon sub-face side maps to the line at half the scale of a quad's side, and leave room
/// for a leaf's centre.
inline constexpr int kMaxDepth = int(kGridBits) - 2;

/// A ptex side on its line: line parameter = offset + scale · (the grid coordinate that
/// varies along the side: i on sides 0 and 2, j on sides 1 and 3).
struct SideOnLine {
  std::uint32_t line = 0;
  std::int64_t offset = 0;
  std::int64_t scale = 0;

  [[nodiscard]] std::int64_t toLine(std::int64_t coordinate) const { return offset + scale * coordinate; }
  [[nodiscard]] std::int64_t fromLine(std::int64_t parameter) const { return (parameter - offset) / scale; }
};

/// The name of a point of the limit surface shared by all faces that touch it, plus a tag that
/// separates the faces on either side of a UV seam (0 where UVs are continuous).
struct PointName {
  std::uint64_t location = 0;
  std::uint32_t uvTag = 0;
};

/// The ptex sides of a cage, with the cage's UV seams.
class PtexSides {
public:
  /// `cage` must be valid (validateCage); ptex faces are numbered as in LimitSurface.
  explicit PtexSides(const Cage& cage);

  [[nodiscard]] std::size_t ptexFaceCount() const { return faces_.size(); }
  [[nodiscard]] std::size_t lineCount() const { return lines_.size(); }
  /// Sides 0..3 of a ptex face: v = 0, u = 1, v = 1, u = 0.
  [[nodiscard]] const SideOnLine& side(std::uint32_t ptexFace, int side) const { return faces_[ptexFace].sides[side]; }

  /// The shared name of grid point (i, j) of `ptexFace`.
  [[nodiscard]] PointName name(std::uint32_t ptexFace, std::int64_t i, std::int64_t j) const;

private:
  enum class LineKind : std::uint8_t { kEdge, kSpoke };
  struct Line {
    LineKind kind = LineKind::kEdge;
    std::uint32_t start = 0;  ///< edge: lower vertex; spoke: its cage edge's line
    std::uint32_t end = 0;    ///< edge: higher vertex; spoke: its n-gon's cage face
    bool uvSeam = false;      ///< edge: the two faces give an end different UVs
  };
  struct Face {
    std::array<SideOnLine, 4> sides;
    std::array<std::uint32_t, 4> cornerUvTags{};  ///< for corners that are cage vertices on a UV seam
    std::uint32_t cageFace = 0;
  };

  [[nodiscard]] PointName nameOnLine(const Face& face, std::uint32_t line, std::int64_t parameter) const;

  std::vector<Line> lines_;
  std::vector<Face> faces_;
};

}  // namespace mane::subdiv::detail
