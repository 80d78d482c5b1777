#include "scenes/groom_repair.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "scenes/groom_loader.hpp"

namespace mane::scenes {
namespace {

bool isFinite(const glm::vec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

/// The median of `values` (the upper one of an even count); 0 when there are none.
float median(std::vector<float> values) {
  if (values.empty()) return 0.0f;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

/// Keeps the elements of `values` whose `keep` flag is set, in order.
template <class T>
void keepWhere(std::vector<T>& values, const std::vector<bool>& keep) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!keep[i]) continue;
    if (kept != i) values[kept] = std::move(values[i]);  // not onto itself: a self-moved vector may empty
    ++kept;
  }
  values.resize(kept);
}

/// Per-strand attribute arrays are empty when the file has none; else one entry per strand.
template <class T>
void keepStrandsWhere(std::vector<T>& perStrand, const std::vector<bool>& keep) {
  if (!perStrand.empty()) keepWhere(perStrand, keep);
}

/// The first point of the strand's longest segment.
std::size_t longestSegment(const std::vector<glm::vec3>& points) {
  std::size_t longest = 0;
  float length = -1.0f;
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
    if (const float d = glm::distance(points[i], points[i + 1]); d > length) {
      length = d;
      longest = i;
    }
  return longest;
}

/// The mean of `a` and `b`, halved before adding so that two finite values near the float
/// limit give a finite mean (the same value as (a + b) / 2 wherever that does not overflow).
template <class T>
T midpoint(const T& a, const T& b) {
  return a * 0.5f + b * 0.5f;
}

/// Inserts the mean of `values[at]` and `values[at + 1]` between them.
template <class T>
void insertMidpoint(std::vector<T>& values, std::size_t at) {
  const T middle = midpoint(values[at], values[at + 1]);
  values.insert(values.begin() + static_cast<std::ptrdiff_t>(at + 1), middle);
}

/// Whether `middle` cuts the segment a–b into two that are neither repeated points nor
/// zero-length segments. A segment at float resolution (a few units in the last place, or
/// subnormal coordinates) has no such point: its rounded midpoint is one of its ends.
bool splits(const glm::vec3& a, const glm::vec3& middle, const glm::vec3& b, float zeroLength) {
  return middle != a && middle != b && glm::distance(a, middle) >= zeroLength && glm::distance(middle, b) >= zeroLength;
}

const char* reasonPhrase(StrandFlaw flaw) {
  switch (flaw) {
    case StrandFlaw::kRepeatedPoint: return "with a repeated point";
    case StrandFlaw::kZeroLengthSegment: return "with a zero-length segment";
    case StrandFlaw::kNonFinitePoint: return "with a non-finite point";
    case StrandFlaw::kTooFewPoints: return "with fewer than two distinct points";
    case StrandFlaw::kAbsurdLength: return "of absurd length";
  }
  return "flawed";
}

constexpr std::array kRepairedFlaws{StrandFlaw::kRepeatedPoint, StrandFlaw::kZeroLengthSegment};
constexpr std::array kDroppedFlaws{StrandFlaw::kNonFinitePoint, StrandFlaw::kTooFewPoints, StrandFlaw::kAbsurdLength};

/// "2 with a repeated point: 17, 40; 1 with …" for the repairs whose flaw is in `flaws`.
template <std::size_t N>
std::string reasons(const std::vector<StrandRepair>& repairs, const std::array<StrandFlaw, N>& flaws,
                    std::size_t listed) {
  std::string text;
  for (StrandFlaw flaw : flaws) {
    std::size_t count = 0;
    std::string indices;
    for (const StrandRepair& repair : repairs) {
      if (repair.flaw != flaw) continue;
      if (count < listed) indices += (count == 0 ? "" : ", ") + std::to_string(repair.strand);
      ++count;
    }
    if (count == 0) continue;
    if (count > listed) indices += " and " + std::to_string(count - listed) + " more";
    text += (text.empty() ? "" : "; ") + std::to_string(count) + " " + reasonPhrase(flaw) + ": " + indices;
  }
  return text;
}

}  // namespace

bool dropsStrand(StrandFlaw flaw) {
  return flaw != StrandFlaw::kRepeatedPoint && flaw != StrandFlaw::kZeroLengthSegment;
}

std::size_t GroomRepairReport::droppedCount() const {
  return static_cast<std::size_t>(
      std::count_if(repairs.begin(), repairs.end(), [](const StrandRepair& r) { return dropsStrand(r.flaw); }));
}

std::string GroomRepairReport::summary(std::size_t listed) const {
  std::string text = std::to_string(strandsRead) + " strands read: ";
  if (clean()) return text + "none flawed";
  const std::size_t repaired = repairedCount();
  const std::size_t dropped = droppedCount();
  if (repaired > 0) text += std::to_string(repaired) + " repaired (" + reasons(repairs, kRepairedFlaws, listed) + ")";
  if (dropped > 0)
    text += (repaired > 0 ? ", " : "") + std::to_string(dropped) + " dropped (" +
            reasons(repairs, kDroppedFlaws, listed) + ")";
  return text;
}

GroomRepairReport repairStrands(StrandSet& set) {
  std::vector<std::vector<glm::vec3>>& strands = set.strands;
  const std::size_t count = strands.size();
  GroomRepairReport report;
  report.strandsRead = count;
  std::vector<std::optional<StrandRepair>> found(count);
  std::vector<bool> keepStrand(count, true);
  const auto drop = [&](std::size_t s, std::size_t point, StrandFlaw flaw) {
    keepStrand[s] = false;
    const std::size_t merged = found[s] ? found[s]->pointsMerged : 0;
    if (found[s] && point > found[s]->point) point = found[s]->point;
    found[s] = StrandRepair{.strand = s, .point = point, .flaw = flaw, .pointsMerged = merged};
  };

  // Rule 1: non-finite points.
  for (std::size_t s = 0; s < count; ++s) {
    const auto bad = std::find_if_not(strands[s].begin(), strands[s].end(), isFinite);
    if (bad != strands[s].end()) drop(s, static_cast<std::size_t>(bad - strands[s].begin()), StrandFlaw::kNonFinitePoint);
  }

  // Rules 2 and 3: merge repeated and near-coincident points; points are marked, not yet removed,
  // so rule 4 can still name them by their stored index.
  std::vector<float> segmentLengths;
  for (std::size_t s = 0; s < count; ++s) {
    if (!keepStrand[s]) continue;
    for (std::size_t i = 1; i < strands[s].size(); ++i)
      if (const float d = glm::distance(strands[s][i], strands[s][i - 1]); d > 0.0f) segmentLengths.push_back(d);
  }
  const float zeroLength = kZeroLengthFraction * median(std::move(segmentLengths));
  std::vector<std::vector<bool>> keepPoint(count);
  for (std::size_t s = 0; s < count; ++s) {
    if (!keepStrand[s]) continue;
    const std::vector<glm::vec3>& points = strands[s];
    keepPoint[s].assign(points.size(), true);
    std::size_t last = 0;
    std::size_t merged = 0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      const bool repeated = points[i] == points[last];
      if (!repeated && glm::distance(points[i], points[last]) >= zeroLength) {
        last = i;
        continue;
      }
      keepPoint[s][i] = false;
      if (merged++ == 0)
        found[s] = StrandRepair{.strand = s,
                                .point = i,
                                .flaw = repeated ? StrandFlaw::kRepeatedPoint : StrandFlaw::kZeroLengthSegment};
    }
    if (found[s]) found[s]->pointsMerged = merged;
    if (points.size() - merged < 2) drop(s, found[s] ? found[s]->point : 0, StrandFlaw::kTooFewPoints);
  }

  // Rule 4: absurd lengths, against the medians of what is left.
  std::vector<float> kept;
  std::vector<float> strandLengths;
  const auto forEachSegment = [&](std::size_t s, auto&& visit) {
    std::size_t previous = 0;
    for (std::size_t i = 1; i < strands[s].size(); ++i) {
      if (!keepPoint[s][i]) continue;
      visit(i, glm::distance(strands[s][i], strands[s][previous]));
      previous = i;
    }
  };
  for (std::size_t s = 0; s < count; ++s) {
    if (!keepStrand[s]) continue;
    float total = 0.0f;
    forEachSegment(s, [&](std::size_t, float length) {
      kept.push_back(length);
      total += length;
    });
    strandLengths.push_back(total);
  }
  const float maxSegment = kAbsurdLengthFactor * median(std::move(kept));
  const float maxStrand = kAbsurdLengthFactor * median(std::move(strandLengths));
  for (std::size_t s = 0; s < count; ++s) {
    if (!keepStrand[s]) continue;
    std::optional<std::size_t> absurdAt;
    float total = 0.0f;
    forEachSegment(s, [&](std::size_t i, float length) {
      total += length;
      if (!absurdAt && (length > maxSegment || total > maxStrand)) absurdAt = i;
    });
    if (absurdAt) drop(s, *absurdAt, StrandFlaw::kAbsurdLength);
  }

  // Apply: merged points out of the strands and their per-point attributes, dropped strands out
  // of everything.
  for (std::size_t s = 0; s < count; ++s) {
    if (!keepStrand[s] || !found[s] || found[s]->pointsMerged == 0) continue;
    const std::size_t storedCount = strands[s].size();
    keepWhere(strands[s], keepPoint[s]);
    if (!set.thickness.empty()) keepWhere(set.thickness[s], keepPoint[s]);
    if (!set.transparency.empty()) keepWhere(set.transparency[s], keepPoint[s]);
    if (!set.colours.empty()) keepWhere(set.colours[s], keepPoint[s]);
    // Back to the stored count by splitting the longest segment, one point at a time: the shape
    // is kept, and a groom of strands with one count stays so (the renderer draws only those).
    while (strands[s].size() < storedCount) {
      const std::size_t at = longestSegment(strands[s]);
      if (!splits(strands[s][at], midpoint(strands[s][at], strands[s][at + 1]), strands[s][at + 1], zeroLength)) {
        // Even its longest segment cannot be halved: the whole strand is at the zero-length
        // bound, as good as a single point (rule 3).
        drop(s, found[s]->point, StrandFlaw::kTooFewPoints);
        break;
      }
      insertMidpoint(strands[s], at);
      if (!set.thickness.empty()) insertMidpoint(set.thickness[s], at);
      if (!set.transparency.empty()) insertMidpoint(set.transparency[s], at);
      if (!set.colours.empty()) insertMidpoint(set.colours[s], at);
    }
  }
  keepWhere(strands, keepStrand);
  keepStrandsWhere(set.thickness, keepStrand);
  keepStrandsWhere(set.transparency, keepStrand);
  keepStrandsWhere(set.colours, keepStrand);
  keepStrandsWhere(set.strandThickness, keepStrand);
  keepStrandsWhere(set.strandUvs, keepStrand);
  for (std::optional<StrandRepair>& repair : found)
    if (repair) report.repairs.push_back(*repair);
  return report;
}

}  // namespace mane::scenes
