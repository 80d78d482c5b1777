#pragma once
// Strands as a groom file stores them → strands the simulation can take, plus a report of what
// had to change. Grooms from the wild carry a few broken strands among thousands (an exporter's
// repeated vertex, a NaN); refusing the whole file for one of them helps nobody, so the loaders
// repair what can be repaired, drop what cannot, and say so once (`GroomRepairReport::summary`).
// A strict load refuses instead (groom_loader.hpp).
//
// The rules, strand by strand, in this order (one flaw is reported per strand, the first found):
// 1. A point with a NaN or infinite coordinate drops the strand. Truncating at it would keep a
//    strand of the wrong length whose remaining points came from the same broken export; a
//    missing guide among thousands is less visible than a wrong one.
// 2. A point equal to the point before it (a repeated point), or closer to it than
//    `kZeroLengthFraction` of the groom's median segment length (a zero-length segment), is
//    merged into it: the later point and its per-point attributes are removed (a zero-length
//    constraint would only divide by zero in the solver). The strand is then brought back to
//    its stored point count by splitting its longest segment at the midpoint, as often as
//    points were removed (attributes interpolated alike): its shape is kept, and a groom whose
//    strands share one count, as TressFX grooms do, keeps sharing it. The bound is
//    far below anything groomed: real fur (the TressFX bear) has segments down to ~1e-5 of its
//    median, a float's resolution at its coordinates, and those strands load untouched.
// 3. A strand left with fewer than two points is dropped (nothing to simulate or draw), and so
//    is one that cannot be brought back to its count because even its longest segment is too
//    short to halve into two segments over the zero-length bound (or, at float resolution, into
//    two at all): such a strand is as good as a single point.
// 4. A strand with a segment longer than `kAbsurdLengthFactor` × the groom's median segment
//    length, or a total length over `kAbsurdLengthFactor` × the groom's median strand length, is
//    dropped: such a strand is a stray point (a coordinate off by orders of magnitude), and one
//    strand metres long would stretch the groom's bounds, its collision grid and its shadows.
//    These medians are taken over the strands that pass rules 1–3 (rule 2's over the non-zero
//    segments of the strands that pass rule 1), so a few broken strands cannot move them.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mane::scenes {

struct StrandSet;

/// Segments shorter than this fraction of the groom's median segment count as zero-length.
inline constexpr float kZeroLengthFraction = 1e-6f;
/// Segments (or strands) longer than this multiple of the groom's median segment (strand)
/// length are absurd.
inline constexpr float kAbsurdLengthFactor = 100.0f;

/// What was wrong with one strand.
enum class StrandFlaw : std::uint8_t {
  kRepeatedPoint,      ///< repaired: a point equal to the one before it, merged
  kZeroLengthSegment,  ///< repaired: a point nearly at the one before it, merged
  kNonFinitePoint,     ///< dropped: a NaN or infinite coordinate
  kTooFewPoints,       ///< dropped: fewer than two points (stored or after merging), or too short to split (rule 3)
  kAbsurdLength,       ///< dropped: a segment or the whole strand far longer than the groom's median
};

/// Whether a strand with `flaw` was dropped (rather than repaired and kept).
[[nodiscard]] bool dropsStrand(StrandFlaw flaw);

/// One flawed strand.
struct StrandRepair {
  std::size_t strand = 0;  ///< index in the file (before any strand was dropped)
  std::size_t point = 0;   ///< the first offending point, index in the strand as stored
  StrandFlaw flaw = StrandFlaw::kRepeatedPoint;
  std::size_t pointsMerged = 0;  ///< points merged away by rule 2 (then put back by splitting, if kept)
};

/// What `repairStrands` changed in one groom.
struct GroomRepairReport {
  std::size_t strandsRead = 0;
  std::vector<StrandRepair> repairs;  ///< in strand order, one per flawed strand

  [[nodiscard]] bool clean() const { return repairs.empty(); }
  [[nodiscard]] std::size_t droppedCount() const;
  [[nodiscard]] std::size_t repairedCount() const { return repairs.size() - droppedCount(); }
  /// One line for people, e.g. "4,933 strands read: 2 repaired (repeated point: 17, 40), 1 dropped
  /// (non-finite point: 99)"; each reason lists its first `listed` strand indices, then how many more.
  [[nodiscard]] std::string summary(std::size_t listed = 5) const;
};

/// Applies the rules above to `set` in place (its strands and their attributes stay aligned) and
/// reports what changed. Every strand left has at least two finite points, no two consecutive
/// ones closer than the zero-length bound. May leave `set` with no strands; the caller decides
/// whether that is an error.
GroomRepairReport repairStrands(StrandSet& set);

}  // namespace mane::scenes
