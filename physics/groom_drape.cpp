#include "physics/groom_drape.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mane::physics {

namespace {

// The cosine between a surface's outward normal and the upward vertical below which a strand
// slides off it rather than lies on it: slopes up to about 73° from the horizontal hold hair.
constexpr float kSteepestRest = 0.3f;

// Steps the strand is walked in per (mean) segment.
constexpr int kStepsPerSegment = 8;
// Passes of the moving average that smooths the walked path.
constexpr int kSmoothingPasses = 4;

float dot(const glm::vec3& a, const glm::vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

float length(const glm::vec3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

// The colliders' distance gradient at `p` by central differences a millimetre wide, unit
// length (or zero where the field is flat there).
glm::vec3 outward(const ColliderSet& colliders, const glm::vec3& p) {
  constexpr float h = 5e-4f;
  const glm::vec3 g{
      signedDistance(colliders, p + glm::vec3(h, 0, 0)) - signedDistance(colliders, p - glm::vec3(h, 0, 0)),
      signedDistance(colliders, p + glm::vec3(0, h, 0)) - signedDistance(colliders, p - glm::vec3(0, h, 0)),
      signedDistance(colliders, p + glm::vec3(0, 0, h)) - signedDistance(colliders, p - glm::vec3(0, 0, h))};
  const float size = length(g);
  return size > 0.0f && std::isfinite(size) ? g / size : glm::vec3(0.0f);
}

// Moves the next point `q` of a segment from `p` of length `segment` to `clearance` from the
// colliders (only out of them unless `onLayer`), keeping the segment's length: a few rounds of
// move and re-projection onto the sphere around `p`.
glm::vec3 place(const ColliderSet& colliders, const glm::vec3& p, glm::vec3 q, float segment, float clearance,
                bool onLayer) {
  constexpr int kRounds = 4;
  for (int round = 0; round < kRounds; ++round) {
    const float distance = signedDistance(colliders, q);
    if (!(distance < clearance) && !(onLayer && distance > clearance)) break;
    q += (clearance - distance) * outward(colliders, q);
    const glm::vec3 along = q - p;
    const float size = length(along);
    if (!(size > 0.0f)) break;
    q = p + along * (segment / size);
  }
  return q;
}

// Whether a strand reaching `q` rests on the colliders there: they are within `reach` and lie
// under it (their outward gradient more than kSteepestRest along the upward vertical), so gravity
// would lay it on them.
bool resting(const ColliderSet& colliders, const glm::vec3& q, const glm::vec3& down, float reach) {
  if (!(signedDistance(colliders, q) < reach)) return false;
  return dot(outward(colliders, q), down) < -kSteepestRest;
}

// The point x on the line through `a` and `b`, beyond `a` towards `b`, with |x − centre| = distance,
// where |a − centre| ≤ distance ≤ |b − centre| (so it lies between them).
glm::vec3 pointAtDistance(const glm::vec3& centre, const glm::vec3& a, const glm::vec3& b, float distance) {
  const glm::vec3 d = b - a;
  const glm::vec3 f = a - centre;
  const float qa = dot(d, d), qb = 2.0f * dot(f, d), qc = dot(f, f) - distance * distance;
  const float discriminant = std::max(qb * qb - 4.0f * qa * qc, 0.0f);
  const float t = qa > 0.0f ? std::clamp((-qb + std::sqrt(discriminant)) / (2.0f * qa), 0.0f, 1.0f) : 1.0f;
  const glm::vec3 x = a + t * d;
  // Rounding aside, exactly `distance` from the centre: the chord is the rest length.
  const float reached = length(x - centre);
  return reached > 0.0f ? centre + (x - centre) * (distance / reached) : x;
}

// Smooths a walked path (root kept) by kSmoothingPasses passes of a moving average over
// kStepsPerSegment steps, then moves its points back out of the colliders to `clearance`.
void smooth(std::vector<glm::vec3>& path, const ColliderSet& colliders, float clearance) {
  const std::size_t half = kStepsPerSegment / 2;
  std::vector<glm::vec3> averaged(path.size());
  for (int pass = 0; pass < kSmoothingPasses; ++pass) {
    averaged[0] = path[0];
    for (std::size_t k = 1; k < path.size(); ++k) {
      // A window that shrinks towards the ends, so the root's direction stays.
      const std::size_t reach = std::min({half, k, path.size() - 1 - k});
      glm::vec3 sum(0.0f);
      for (std::size_t j = k - reach; j <= k + reach; ++j) sum += path[j];
      averaged[k] = sum / float(2 * reach + 1);
    }
    path.swap(averaged);
  }
  if (colliders.empty()) return;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const float distance = signedDistance(colliders, path[k]);
    if (distance < clearance) path[k] += (clearance - distance) * outward(colliders, path[k]);
  }
}

}  // namespace

Result<void> drapeGuides(std::vector<std::vector<glm::vec3>>& guides, const ColliderSet& colliders,
                         const DrapeSettings& settings) {
  const float downLength = length(settings.down);
  if (!(downLength > 0.0f && std::isfinite(downLength)))
    return fail("Drape settings: down must be a finite, non-zero direction.");
  if (!(settings.droop >= 0.0f && settings.droop <= 1000.0f))
    return fail("Drape settings: droop must be in [0, 1000] per metre.");
  if (!(settings.layer >= 0.0f && std::isfinite(settings.layer)))
    return fail("Drape settings: layer must be a non-negative number of metres.");
  if (!(settings.combedLength >= 0.0f && std::isfinite(settings.combedLength)))
    return fail("Drape settings: combedLength must be a non-negative number of metres.");
  for (std::size_t g = 0; g < guides.size(); ++g)
    for (std::size_t i = 1; i < guides[g].size(); ++i) {
      const float segment = length(guides[g][i] - guides[g][i - 1]);
      if (!(segment > 0.0f && std::isfinite(segment)))
        return fail("Drape: guide " + std::to_string(g) + "'s segment " + std::to_string(i) +
                    " has no length or is not finite.");
    }

  const glm::vec3 down = settings.down / downLength;
  const float clearance = settings.layer + colliders.thickness;
  for (std::vector<glm::vec3>& guide : guides) {
    if (guide.size() < 2) continue;
    std::vector<float> segments(guide.size());
    float total = 0.0f;
    for (std::size_t i = 1; i < guide.size(); ++i) {
      segments[i] = length(guide[i] - guide[i - 1]);
      total += segments[i];
    }
    // The strand is walked in steps a fraction of its mean segment, so that the colliders'
    // curvature and the droop turn it gradually; the path is smoothed over about a segment, so
    // that no turn is sharper than the strand's segments can bend, and its particles are placed
    // on it, each its rest segment length (as a chord) from the one before. The path runs half
    // as long again as the strand: its chords are shorter than its arc.
    const std::size_t steps = 3 * std::size_t(kStepsPerSegment) * (guide.size() - 1) / 2 + 1;
    const float step = total / float(kStepsPerSegment * (guide.size() - 1));
    std::vector<glm::vec3> path{guide[0]};
    glm::vec3 direction = (guide[1] - guide[0]) / segments[1];
    for (std::size_t taken = 0; taken < steps; ++taken) {
      const bool combed = float(taken) * step < settings.combedLength;
      const glm::vec3 at = path.back();
      glm::vec3 next = at + step * direction;
      if (!colliders.empty())
        next = place(colliders, at, next, step, clearance, combed || resting(colliders, next, down, clearance + step));
      path.push_back(next);
      const float stepLength = length(next - at);
      const glm::vec3 laid = stepLength > 0.0f ? (next - at) / stepLength : direction;
      const glm::vec3 turned = laid + (combed ? 0.0f : settings.droop * step) * down;
      const float turnedLength = length(turned);
      if (turnedLength > 0.0f) direction = turned / turnedLength;
    }
    smooth(path, colliders, clearance);

    std::size_t i = 1;
    for (std::size_t k = 1; k < path.size() && i < guide.size(); ++k)
      // Particles whose chord from the last one ends on this step: on the step's line at that distance.
      while (i < guide.size() && length(path[k] - guide[i - 1]) >= segments[i]) {
        guide[i] = pointAtDistance(guide[i - 1], path[k - 1], path[k], segments[i]);
        ++i;
      }
    // A path that winds back keeps its chords short: the strand's rest goes straight on from it.
    for (; i < guide.size(); ++i) {
      const glm::vec3 next = guide[i - 1] + segments[i] * direction;
      guide[i] = colliders.empty() ? next : place(colliders, guide[i - 1], next, segments[i], clearance, false);
    }
  }
  return {};
}

}  // namespace mane::physics
