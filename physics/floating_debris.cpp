#include "physics/floating_debris.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include <glm/matrix.hpp>

#include "physics/detail/hair_math.hpp"
#include "physics/detail/portable_math.hpp"
#include "physics/split_mix64.hpp"

namespace mane::physics {
namespace {

constexpr double kTwoPi = 6.283185307179586;

float distance(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = b - a;
  return std::sqrt(glm::dot(d, d));
}

// The obstacle's map back to the unit sphere, or nothing when it has none.
std::optional<glm::mat4> unitSphereFromWorld(const DebrisObstacle& obstacle) {
  const glm::mat4& m = obstacle.worldFromUnitSphere;
  if (!detail::isFinite(m)) return std::nullopt;
  const float determinant = glm::determinant(glm::mat3(m));
  if (!(std::abs(determinant) > 0.0f) || !std::isfinite(determinant)) return std::nullopt;
  return glm::inverse(m);
}

// `point` moved onto the obstacle's surface along the line from its centre if it lies inside;
// true when it did.
bool pushOut(const DebrisObstacle& obstacle, const glm::mat4& toSphere, glm::vec3& point) {
  const glm::vec3 q = detail::transformPoint(toSphere, point);
  const float squared = glm::dot(q, q);
  if (!(squared < 1.0f)) return false;
  // At the very centre any way out will do.
  const glm::vec3 out = squared > 0.0f ? q / std::sqrt(squared) : glm::vec3(1.0f, 0.0f, 0.0f);
  point = detail::transformPoint(obstacle.worldFromUnitSphere, out);
  return true;
}

}  // namespace

Result<FloatingDebris> FloatingDebris::create(const FloatingDebrisSettings& settings, const OceanWaves& ocean,
                                              double time, const DebrisObstacle* obstacle) {
  const auto bad = [](const char* field, const char* expected) {
    return fail(std::string("debris: ") + field + " must be " + expected + ".");
  };
  if (settings.pieces < 0 || settings.pieces > 4096) return bad("pieces", "0 to 4096");
  if (!(std::isfinite(settings.centre.x) && std::isfinite(settings.centre.y))) return bad("centre", "finite");
  if (!(std::isfinite(settings.radius) && settings.radius >= 0.0f)) return bad("radius", "finite and ≥ 0");
  if (!(std::isfinite(settings.size) && settings.size > 0.0f)) return bad("size", "finite and > 0");
  if (!(std::isfinite(settings.thickness) && settings.thickness > 0.0f)) return bad("thickness", "finite and > 0");
  if (!(settings.relativeDensity > 0.0f && settings.relativeDensity < 1.0f))
    return bad("relativeDensity", "between 0 and 1");
  if (!(std::isfinite(settings.dragPerSecond) && settings.dragPerSecond >= 0.0f))
    return bad("dragPerSecond", "finite and ≥ 0");
  if (settings.constraintIterations < 1) return bad("constraintIterations", "at least 1");
  std::optional<glm::mat4> toSphere;
  if (obstacle) {
    toSphere = unitSphereFromWorld(*obstacle);
    if (!toSphere) return fail("debris: the obstacle's map from the unit sphere is not finite and invertible.");
  }

  FloatingDebris debris(settings);
  SplitMix64 random(settings.seed);
  const auto count = static_cast<std::size_t>(settings.pieces);
  debris.positions_.reserve(3 * count);
  debris.restLengths_.reserve(3 * count);
  constexpr int kPlacements = 16;
  for (std::size_t piece = 0; piece < count; ++piece) {
    std::array<glm::vec3, 3> corners;
    for (int attempt = 0; attempt < kPlacements; ++attempt) {
      // Uniform over the disc: radius ∝ √u.
      const double r = settings.radius * std::sqrt(static_cast<double>(random.nextFloat()));
      const detail::SineCosine place = detail::sineCosine(kTwoPi * random.nextFloat());
      const glm::vec2 centre = settings.centre + glm::vec2(float(r * place.cosine), float(r * place.sine));
      const OceanSample water = ocean.surfaceAt(centre, time);
      // A triangle with corners at three angles about its centre, each at half to all of the size.
      const double turn = kTwoPi * random.nextFloat();
      for (int corner = 0; corner < 3; ++corner) {
        const double angle = turn + kTwoPi * corner / 3.0 + 0.6 * (random.nextFloat() - 0.5f);
        const float reach = settings.size * (0.3f + 0.28f * random.nextFloat());
        const detail::SineCosine a = detail::sineCosine(angle);
        const glm::vec2 offset(float(reach * a.cosine), float(reach * a.sine));
        const glm::vec3 n = water.normal;
        const float lift =
            -(n.x * offset.x + n.z * offset.y) / n.y + (0.5f - settings.relativeDensity) * settings.thickness;
        corners[corner] = water.position + glm::vec3(offset.x, lift, offset.y);
      }
      if (!toSphere) break;
      bool inside = false;
      for (glm::vec3 corner : corners) inside = pushOut(*obstacle, *toSphere, corner) || inside;
      if (!inside) break;
      if (attempt + 1 == kPlacements)
        for (glm::vec3& corner : corners) pushOut(*obstacle, *toSphere, corner);
    }
    debris.positions_.insert(debris.positions_.end(), corners.begin(), corners.end());
    const glm::vec3* p = debris.positions_.data() + 3 * piece;
    debris.restLengths_.push_back(distance(p[0], p[1]));
    debris.restLengths_.push_back(distance(p[1], p[2]));
    debris.restLengths_.push_back(distance(p[2], p[0]));
  }
  // They start still; the water's drag takes them up within a second.
  debris.previous_ = debris.positions_;
  return debris;
}

void FloatingDebris::step(const OceanWaves& ocean, double time, float dt, const DebrisObstacle* obstacle) {
  const FloatingDebrisSettings& s = settings_;
  const std::optional<glm::mat4> toSphere = obstacle ? unitSphereFromWorld(*obstacle) : std::nullopt;
  const float lift = kOceanGravity / s.relativeDensity;
  for (std::size_t piece = 0; piece * 3 < positions_.size(); ++piece) {
    glm::vec3* p = positions_.data() + 3 * piece;
    glm::vec3* previous = previous_.data() + 3 * piece;
    const glm::vec3 centroid = (p[0] + p[1] + p[2]) / 3.0f;
    const OceanSample water = ocean.surfaceAt({centroid.x, centroid.z}, time);
    const glm::vec3 n = water.normal;
    for (int corner = 0; corner < 3; ++corner) {
      const glm::vec3 offset = p[corner] - water.position;
      const float surface = water.position.y - (n.x * offset.x + n.z * offset.z) / n.y;
      const float share = std::clamp((surface - p[corner].y) / s.thickness + 0.5f, 0.0f, 1.0f);
      const glm::vec3 velocity = (p[corner] - previous[corner]) / dt;
      const glm::vec3 acceleration =
          glm::vec3(0.0f, share * lift - kOceanGravity, 0.0f) + (s.dragPerSecond * share) * (water.velocity - velocity);
      const glm::vec3 next = p[corner] + (p[corner] - previous[corner]) + acceleration * (dt * dt);
      previous[corner] = p[corner];
      p[corner] = next;
    }
    // Equal masses: each edge's error is shared equally by its two ends.
    const float* rest = restLengths_.data() + 3 * piece;
    for (int iteration = 0; iteration < s.constraintIterations; ++iteration) {
      for (int edge = 0; edge < 3; ++edge) {
        glm::vec3& a = p[edge];
        glm::vec3& b = p[(edge + 1) % 3];
        const glm::vec3 d = b - a;
        const float length = std::sqrt(glm::dot(d, d));
        if (length <= 0.0f) continue;
        const glm::vec3 correction = d * (0.5f * (length - rest[edge]) / length);
        a += correction;
        b -= correction;
      }
    }
    // Last, so that no corner ends the step inside it.
    if (toSphere)
      for (int corner = 0; corner < 3; ++corner) pushOut(*obstacle, *toSphere, p[corner]);
  }
}

}  // namespace mane::physics
