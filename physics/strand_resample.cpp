#include "physics/strand_resample.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/vec3.hpp>

namespace mane::physics {
namespace {

std::string describe(const glm::vec3& p) {
  // snprintf rather than "(" + std::to_string(…): g++ 12 reports a false -Wrestrict on the
  // latter (GCC bug 105329).
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", static_cast<double>(p.x), static_cast<double>(p.y),
                static_cast<double>(p.z));
  return text;
}

}  // namespace

Result<std::vector<glm::vec3>> resampleStrand(std::span<const glm::vec3> points, std::size_t count) {
  if (count < 2)
    return fail("Strand resampling: asked for " + std::to_string(count) +
                " points; a strand needs at least 2 (its root and its tip).");
  if (points.size() < 2)
    return fail("Strand resampling: the strand has " + std::to_string(points.size()) +
                " point(s); at least 2 are needed to define a curve.");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::vec3& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return fail("Strand resampling: point " + std::to_string(i) + " is " + describe(p) + ", not a finite position.");
  }

  // Cumulative arc length at each input point, in double: float sums of many short segments
  // drift by about n·2⁻²⁴ relative, which would show as unequal spacing on long strands.
  std::vector<double> arc(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(points[i]) - glm::dvec3(points[i - 1]);
    arc[i] = arc[i - 1] + std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  }
  const double total = arc.back();
  if (!(total > 0.0))
    return fail("Strand resampling: the strand has zero length (all " + std::to_string(points.size()) +
                " points coincide at " + describe(points.front()) + ").");
  if (!std::isfinite(total)) return fail("Strand resampling: the strand's length overflows double precision.");

  std::vector<glm::vec3> result;
  result.reserve(count);
  result.push_back(points.front());
  std::size_t segment = 1;  // the input segment [segment − 1, segment] holding the target
  const double steps = static_cast<double>(count - 1);
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const double target = total * (static_cast<double>(k) / steps);
    // target < total = arc.back(), so this stops inside the polyline.
    while (segment + 1 < points.size() && arc[segment] < target) ++segment;
    const double length = arc[segment] - arc[segment - 1];
    const double t = length > 0.0 ? (target - arc[segment - 1]) / length : 0.0;
    const glm::dvec3 a(points[segment - 1]);
    const glm::dvec3 b(points[segment]);
    result.push_back(glm::vec3(a + (b - a) * t));
  }
  result.push_back(points.back());
  return result;
}

Result<std::vector<std::vector<glm::vec3>>> resampleGroom(std::span<const std::vector<glm::vec3>> strands,
                                                          std::size_t count) {
  if (strands.empty()) return fail("Strand resampling: the groom is empty (no strands).");
  std::vector<std::vector<glm::vec3>> result;
  result.reserve(strands.size());
  for (std::size_t s = 0; s < strands.size(); ++s) {
    auto resampled = resampleStrand(strands[s], count);
    if (!resampled) return fail("Groom strand " + std::to_string(s) + ": " + resampled.error().message);
    result.push_back(std::move(*resampled));
  }
  return result;
}

}  // namespace mane::physics
