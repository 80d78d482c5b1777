#include "render/passes/opacity_shadow_map_reference.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

namespace mane::render {

namespace {

constexpr int kMaxCellsPerSide = 512;

// Quadratic B-spline with unit knot spacing (box ∗ tent), x in knots.
double quadraticBSpline(double x) {
  x = std::abs(x);
  if (x < 0.5) return 0.75 - x * x;
  if (x < 1.5) return 0.5 * (1.5 - x) * (1.5 - x);
  return 0.0;
}

}  // namespace

Result<OpacityReference> OpacityReference::create(const OpacityReferenceGroom& groom, glm::vec3 towardLight) {
  if (groom.strandCount == 0) return fail("Opacity reference: there are no strands.");
  if (groom.verticesPerStrand < 2)
    return fail("Opacity reference: strands need at least 2 vertices each, got " +
                std::to_string(groom.verticesPerStrand) + ".");
  const std::size_t vertices = std::size_t(groom.strandCount) * groom.verticesPerStrand;
  if (groom.positions.size() < vertices)
    return fail("Opacity reference: " + std::to_string(vertices) + " positions needed, " +
                std::to_string(groom.positions.size()) + " given.");
  if (!(std::isfinite(groom.strandRadius) && groom.strandRadius > 0.0f))
    return fail("Opacity reference: strand radius " + std::to_string(groom.strandRadius) +
                " m is not positive and finite.");
  if (!(std::isfinite(groom.strandOpacity) && groom.strandOpacity > 0.0f) ||
      !(std::isfinite(groom.extinction) && groom.extinction > 0.0f))
    return fail("Opacity reference: strand opacity and extinction must be positive and finite.");
  const double length = glm::length(glm::dvec3(towardLight));
  if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-3)
    return fail("Opacity reference: the light direction is not a finite unit vector (length " + std::to_string(length) +
                ").");

  OpacityReference result;
  result.light_ = glm::dvec3(towardLight) / length;
  const glm::dvec3 helper = std::abs(result.light_.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  result.e1_ = glm::normalize(glm::cross(helper, result.light_));
  result.e2_ = glm::cross(result.light_, result.e1_);
  result.radius_ = groom.strandRadius;
  result.opacity_ = groom.strandOpacity;
  result.extinction_ = groom.extinction;

  glm::dvec2 low(1e300), high(-1e300);
  for (std::size_t s = 0; s < groom.strandCount; ++s)
    for (std::size_t i = 0; i + 1 < groom.verticesPerStrand; ++i) {
      const glm::dvec3 a(glm::vec3(groom.positions[s * groom.verticesPerStrand + i]));
      const glm::dvec3 b(glm::vec3(groom.positions[s * groom.verticesPerStrand + i + 1]));
      if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z))
        return fail("Opacity reference: strand " + std::to_string(s) + " has a non-finite position.");
      Segment segment{.a = a, .axis = b - a, .start = result.project(a), .across = result.project(b - a)};
      segment.lengthSquared = glm::dot(segment.across, segment.across);
      low = glm::min(low, glm::min(segment.start, segment.start + segment.across));
      high = glm::max(high, glm::max(segment.start, segment.start + segment.across));
      result.segments_.push_back(segment);
    }

  // A uniform grid of cells half a segment wide, at most kMaxCellsPerSide per side.
  const double r = result.radius_;
  low -= glm::dvec2(r);
  high += glm::dvec2(r);
  double meanLength = 0.0;
  for (const Segment& segment : result.segments_) meanLength += std::sqrt(segment.lengthSquared);
  meanLength /= double(result.segments_.size());
  const double extent = std::max(high.x - low.x, high.y - low.y);
  result.cellSize_ = std::max({0.5 * meanLength, extent / kMaxCellsPerSide, 4.0 * r});
  result.gridOrigin_ = low;
  result.cellsX_ = std::max(1, int(std::ceil((high.x - low.x) / result.cellSize_)));
  result.cellsY_ = std::max(1, int(std::ceil((high.y - low.y) / result.cellSize_)));
  const auto cellRange = [&](const Segment& segment, int& x0, int& y0, int& x1, int& y1) {
    const glm::dvec2 lo = glm::min(segment.start, segment.start + segment.across) - glm::dvec2(r) - low;
    const glm::dvec2 hi = glm::max(segment.start, segment.start + segment.across) + glm::dvec2(r) - low;
    x0 = std::clamp(int(lo.x / result.cellSize_), 0, result.cellsX_ - 1);
    y0 = std::clamp(int(lo.y / result.cellSize_), 0, result.cellsY_ - 1);
    x1 = std::clamp(int(hi.x / result.cellSize_), 0, result.cellsX_ - 1);
    y1 = std::clamp(int(hi.y / result.cellSize_), 0, result.cellsY_ - 1);
  };
  std::vector<std::uint32_t> counts(std::size_t(result.cellsX_) * result.cellsY_ + 1, 0);
  for (const Segment& segment : result.segments_) {
    int x0, y0, x1, y1;
    cellRange(segment, x0, y0, x1, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) ++counts[std::size_t(y) * result.cellsX_ + x + 1];
  }
  for (std::size_t i = 1; i < counts.size(); ++i) counts[i] += counts[i - 1];
  result.cellStart_ = counts;
  result.cellSegments_.resize(counts.back());
  for (std::uint32_t index = 0; index < result.segments_.size(); ++index) {
    int x0, y0, x1, y1;
    cellRange(result.segments_[index], x0, y0, x1, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) result.cellSegments_[counts[std::size_t(y) * result.cellsX_ + x]++] = index;
  }
  return result;
}

glm::dvec2 OpacityReference::project(const glm::dvec3& p) const {
  return {glm::dot(p, e1_), glm::dot(p, e2_)};
}

double OpacityReference::rayOpacity(const glm::dvec3& point) const {
  const glm::dvec2 q = project(point);
  const glm::dvec2 cell = (q - gridOrigin_) / cellSize_;
  if (cell.x < 0.0 || cell.y < 0.0 || cell.x >= cellsX_ || cell.y >= cellsY_) return 0.0;
  const std::size_t index = std::size_t(int(cell.y)) * cellsX_ + std::size_t(int(cell.x));
  const double r2 = radius_ * radius_;
  int crossings = 0;
  for (std::uint32_t i = cellStart_[index]; i < cellStart_[index + 1]; ++i) {
    const Segment& s = segments_[cellSegments_[i]];
    const glm::dvec2 offset = q - s.start;
    double u = 0.0;
    if (s.lengthSquared > 1e-18 * r2) {
      u = glm::dot(offset, s.across) / s.lengthSquared;
      if (u < 0.0 || u >= 1.0) continue;
    }
    const glm::dvec2 gap = offset - u * s.across;
    if (glm::dot(gap, gap) > r2) continue;
    const glm::dvec3 closest = s.a + u * s.axis;
    if (glm::dot(closest - point, light_) > 0.0) ++crossings;
  }
  return opacity_ * crossings;
}

double OpacityReference::filteredOpacity(const glm::dvec3& point, double texelSize, int raysPerTexel) const {
  const int n = 3 * std::max(raysPerTexel, 1);  // rays per side over ±1.5 texels
  double sum = 0.0, weights = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = -1.5 + 3.0 * (i + 0.5) / n, v = -1.5 + 3.0 * (j + 0.5) / n;  // texels
      const double w = quadraticBSpline(u) * quadraticBSpline(v);
      sum += w * rayOpacity(point + texelSize * (u * e1_ + v * e2_));
      weights += w;
    }
  return sum / weights;
}

double OpacityReference::transmittance(double opacity) const {
  return std::exp(-extinction_ * opacity);
}

}  // namespace mane::render
