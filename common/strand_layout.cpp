#include "common/strand_layout.hpp"

#include <cmath>
#include <string>

namespace mane {

namespace {

// How far the first K weights of a dense strand may sum from 1.
constexpr float kWeightTolerance = 1e-5f;

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string where(std::size_t strand) {
  return "dense strand " + std::to_string(strand);
}

}  // namespace

Result<void> validateStrandLayout(const DenseStrandLayout& layout) {
  if (layout.guideCount == 0 || layout.strands.empty())
    return fail("the layout is empty (" + std::to_string(layout.guideCount) + " guides, " +
                std::to_string(layout.strands.size()) + " dense strands).");
  if (layout.guideVertexCount < 2 || layout.vertexCount < 2 || layout.guideVertexCount > kMaxStrandVertices ||
      layout.vertexCount > kMaxStrandVertices)
    return fail("guides and dense strands need 2 to 4096 vertices each (layout has " +
                std::to_string(layout.guideVertexCount) + " and " + std::to_string(layout.vertexCount) + ").");
  if (layout.curve != StrandCurve::kLinear && layout.curve != StrandCurve::kCatmullRom)
    return fail("the layout's curve (" + std::to_string(static_cast<std::uint32_t>(layout.curve)) +
                ") is neither linear (0) nor Catmull-Rom (1).");
  if (layout.guideFrames.size() != layout.guideCount)
    return fail("the layout has " + std::to_string(layout.guideFrames.size()) + " guide frames for " +
                std::to_string(layout.guideCount) + " guides.");
  for (std::size_t g = 0; g < layout.guideFrames.size(); ++g)
    if (layout.guideFrames[g].partnerA >= layout.guideCount || layout.guideFrames[g].partnerB >= layout.guideCount)
      return fail("guide " + std::to_string(g) + "'s frame partners are out of range (" +
                  std::to_string(layout.guideCount) + " guides).");

  const float guideSpan = static_cast<float>(layout.guideVertexCount - 1);
  const float denseSpan = static_cast<float>(layout.vertexCount - 1);
  for (std::size_t s = 0; s < layout.strands.size(); ++s) {
    const DenseStrand& strand = layout.strands[s];
    if (strand.guideCount < 1 || strand.guideCount > 3)
      return fail(where(s) + " has " + std::to_string(strand.guideCount) + " guides; 1 to 3 are allowed.");
    float sum = 0.0f;
    for (std::uint32_t k = 0; k < strand.guideCount; ++k) {
      if (strand.guides[k] >= layout.guideCount)
        return fail(where(s) + ": guide index " + std::to_string(strand.guides[k]) + " is out of range (" +
                    std::to_string(layout.guideCount) + " guides).");
      if (!std::isfinite(strand.weights[k]))
        return fail(where(s) + ": weight " + std::to_string(k) + " is not finite.");
      sum += strand.weights[k];
    }
    if (!(std::abs(sum - 1.0f) <= kWeightTolerance))
      return fail(where(s) + ": weights sum to " + std::to_string(sum) + ", not 1 (tolerance 1e-5).");
    if (!isFinite(strand.rootOffset) || !isFinite(strand.tipJitter))
      return fail(where(s) + ": root offset or tip jitter is not finite.");
    if (!(strand.clump >= 0.0f && strand.clump <= 1.0f))
      return fail(where(s) + ": clump " + std::to_string(strand.clump) + " is outside [0, 1].");
    if (!(strand.curlRadius >= 0.0f && std::isfinite(strand.curlRadius) && strand.curlTurns >= 0.0f &&
          std::isfinite(strand.curlTurns) && strand.curlPhase >= 0.0f && strand.curlPhase < 1.0f &&
          strand.frizz >= 0.0f && std::isfinite(strand.frizz)))
      return fail(where(s) + ": curl (radius " + std::to_string(strand.curlRadius) + ", turns " +
                  std::to_string(strand.curlTurns) + ", phase " + std::to_string(strand.curlPhase) + ") or frizz " +
                  std::to_string(strand.frizz) + " is out of range.");
    if (!(strand.vertexScale >= 0.0f && denseSpan * strand.vertexScale <= guideSpan))
      return fail(where(s) + ": vertexScale " + std::to_string(strand.vertexScale) +
                  " is negative, not finite, or reaches past the guides' tips.");
  }
  return {};
}

Result<void> validateGuidePositions(std::span<const glm::vec3> guidePositions, std::uint32_t guideCount,
                                    std::uint32_t guideVertexCount, std::span<const GuideFrameRef> guideFrames) {
  const std::size_t ng = guideVertexCount;
  const std::size_t expected = std::size_t(guideCount) * ng;
  if (guidePositions.size() != expected)
    return fail("expected " + std::to_string(guideCount) + " guides × " + std::to_string(ng) +
                " vertices = " + std::to_string(expected) + " guide positions, got " +
                std::to_string(guidePositions.size()) + " (mismatched guide or particle count).");
  for (std::size_t i = 0; i < guidePositions.size(); ++i)
    if (!isFinite(guidePositions[i]))
      return fail("guide " + std::to_string(i / ng) + ", vertex " + std::to_string(i % ng) +
                  " is not finite (NaN or infinite).");
  // The frame's normal is cross(A − root, B − root); a zero one would be normalised by zero.
  for (std::size_t g = 0; g < guideFrames.size(); ++g) {
    const GuideFrameRef ref = guideFrames[g];
    if (ref.partnerA == g && ref.partnerB == g) continue;
    const glm::vec3 root = guidePositions[g * ng];
    const glm::vec3 a = guidePositions[ref.partnerA * ng] - root;
    const glm::vec3 b = guidePositions[ref.partnerB * ng] - root;
    const glm::vec3 normal{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    const float lengthA = a.x * a.x + a.y * a.y + a.z * a.z;
    const float lengthNormal = normal.x * normal.x + normal.y * normal.y + normal.z * normal.z;
    if (!(lengthA > 0.0f && lengthNormal > 0.0f))
      return fail("guide " + std::to_string(g) + "'s root is collinear with its frame partners " +
                  std::to_string(ref.partnerA) + " and " + std::to_string(ref.partnerB) + " (collapsed scalp).");
  }
  return {};
}

}  // namespace mane
