#include "physics/wind.hpp"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "physics/split_mix64.hpp"

namespace mane::physics {
namespace {

// A level in [−1, 1] for gust cell `cell`, the same on every platform: SplitMix64 of seed and
// cell (its output mixes every input bit, so neighbouring cells are independent).
float gustLevel(std::uint64_t seed, std::int64_t cell) {
  SplitMix64 random(seed ^ (static_cast<std::uint64_t>(cell) * 0x9E3779B97F4A7C15ull));
  return random.nextFloat(-1.0f, 1.0f);
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Result<void> validateWind(const WindSettings& settings) {
  if (!finite(settings.direction) || glm::dot(settings.direction, settings.direction) <= 0.0f)
    return fail("wind direction must be finite and non-zero");
  if (!(settings.speed >= 0.0f) || !std::isfinite(settings.speed)) return fail("wind speed must be finite and ≥ 0");
  if (!(settings.gustAmplitude >= 0.0f) || !std::isfinite(settings.gustAmplitude))
    return fail("wind gustAmplitude must be finite and ≥ 0");
  if (!(settings.gustPeriod > 0.0f) || !std::isfinite(settings.gustPeriod))
    return fail("wind gustPeriod must be finite and > 0");
  if (!(settings.dragPerSecond >= 0.0f) || !std::isfinite(settings.dragPerSecond))
    return fail("wind dragPerSecond must be finite and ≥ 0");
  return {};
}

WindField::WindField(const WindSettings& settings)
    : settings_(settings), direction_(glm::normalize(settings.direction)) {}

float WindField::gust(double time) const {
  const double cells = time / settings_.gustPeriod;
  const double floor = std::floor(cells);  // exact: floor is correctly rounded by IEEE 754
  const auto cell = static_cast<std::int64_t>(floor);
  const auto t = static_cast<float>(cells - floor);
  const float smooth = t * t * (3.0f - 2.0f * t);  // smoothstep: C¹ joins between cells
  const float a = gustLevel(settings_.seed, cell);
  const float b = gustLevel(settings_.seed, cell + 1);
  return a + (b - a) * smooth;
}

glm::vec3 WindField::velocityAt(const glm::vec3& position, double time) const {
  if (settings_.speed == 0.0f && settings_.gustAmplitude == 0.0f) return glm::vec3(0.0f);
  // Air at `position` passed the origin's plane d/speed seconds ago (frozen turbulence).
  const float along = glm::dot(position, direction_);
  const double travel = settings_.speed > 0.0f ? double(along) / settings_.speed : 0.0;
  const float speed = settings_.speed + settings_.gustAmplitude * gust(time - travel);
  return direction_ * (speed > 0.0f ? speed : 0.0f);
}

glm::vec3 windAcceleration(const glm::vec3& airVelocity, const glm::vec3& particleVelocity,
                           const glm::vec3& segmentAxis, float dragPerSecond) {
  const glm::vec3 relative = airVelocity - particleVelocity;
  const glm::vec3 normal = relative - segmentAxis * glm::dot(relative, segmentAxis);
  return normal * dragPerSecond;
}

}  // namespace mane::physics
