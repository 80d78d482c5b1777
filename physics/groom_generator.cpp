#include "physics/groom_generator.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace mane::physics {

namespace {

glm::vec3 cross(const glm::vec3& a, const glm::vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

float dot(const glm::vec3& a, const glm::vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

glm::vec3 normalized(const glm::vec3& v) {
  return v / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

// A uniformly distributed direction with y ≥ minY: rejection sampling in the cube (uniform in
// the ball, then projected), which needs no trigonometry.
glm::vec3 randomCapDirection(SplitMix64& rng, float minY) {
  for (;;) {
    const glm::vec3 p{rng.nextFloat(-1.0f, 1.0f), rng.nextFloat(-1.0f, 1.0f), rng.nextFloat(-1.0f, 1.0f)};
    const float r2 = p.x * p.x + p.y * p.y + p.z * p.z;
    if (r2 > 1.0f || r2 < 0.01f) continue;
    const glm::vec3 n = p / std::sqrt(r2);
    if (n.y >= minY) return n;
  }
}

// tan(u) by its Taylor series to u⁷ (relative error below 0.4 % for |u| ≤ π/4); exact
// arithmetic only, so the curl geometry is identical on every platform.
float tanSeries(float u) {
  const float u2 = u * u;
  return u * (1.0f + u2 * (1.0f / 3.0f + u2 * (2.0f / 15.0f + u2 * (17.0f / 315.0f))));
}

}  // namespace

namespace {

// The settings' ranges (shared by both generators), naming the field.
Result<void> validateGroomSettings(const GroomSettings& settings) {
  const auto bad = [](const char* field, const char* expected) {
    return fail(std::string("Groom settings: ") + field + " must be " + expected + ".");
  };
  if (settings.strandCount < 1) return bad("strandCount", "at least 1");
  if (settings.particlesPerStrand < 2) return bad("particlesPerStrand", "at least 2");
  if (!(settings.strandLength > 0.0f && std::isfinite(settings.strandLength)))
    return bad("strandLength", "a positive number of metres");
  if (!(settings.lengthJitter >= 0.0f && settings.lengthJitter < 1.0f)) return bad("lengthJitter", "in [0, 1)");
  if (!(settings.scalpRadius > 0.0f && std::isfinite(settings.scalpRadius)))
    return bad("scalpRadius", "a positive number of metres");
  if (!(std::isfinite(settings.scalpCentre.x) && std::isfinite(settings.scalpCentre.y) &&
        std::isfinite(settings.scalpCentre.z)))
    return bad("scalpCentre", "finite");
  if (!(settings.capMinNormalY >= -1.0f && settings.capMinNormalY <= 0.99f))
    return bad("capMinNormalY", "in [-1, 0.99] (a cap with room for roots)");
  if (!(settings.curlRadius >= 0.0f && std::isfinite(settings.curlRadius)))
    return bad("curlRadius", "a non-negative number of metres");
  if (!(std::abs(settings.curlAnglePerSegment) <= 1.5708f))
    return bad("curlAnglePerSegment", "within [-pi/2, pi/2] radians");
  if (!(std::isfinite(settings.comb.x) && std::isfinite(settings.comb.y) && std::isfinite(settings.comb.z)))
    return bad("comb", "finite");
  if (!(std::isfinite(settings.partingComb) && std::isfinite(settings.partingX) &&
        std::isfinite(settings.partingBackZ)))
    return bad("partingComb, partingX and partingBackZ", "finite");
  return {};
}

// One strand from `root` along the unit `scalpNormal`, combed (GroomSettings::comb): length
// jittered, optionally a helix whose per-segment rotation is (cosStep, sinStep), starting at a
// random phase.
std::vector<glm::vec3> growStrand(SplitMix64& rng, const GroomSettings& settings, const glm::vec3& root,
                                  const glm::vec3& scalpNormal, float cosStep, float sinStep) {
  // n + c_t: its component along n is 1, so the strand always leaves the scalp outwards. Without
  // a comb the normal as given, bit for bit.
  const glm::vec3 comb = combAt(settings, root);
  const glm::vec3 along = comb - dot(comb, scalpNormal) * scalpNormal;
  const glm::vec3 normal = comb == glm::vec3(0.0f) ? scalpNormal : normalized(scalpNormal + along);
  const float length = settings.strandLength * (1.0f + settings.lengthJitter * rng.nextFloat(-1.0f, 1.0f));
  const float spacing = length / static_cast<float>(settings.particlesPerStrand - 1);

  // A frame (u, v) around the growth axis, and a random starting phase on the circle.
  const glm::vec3 helper = std::abs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = normalized(cross(normal, helper));
  const glm::vec3 v = cross(normal, u);
  float c = 1.0f;
  float s = 0.0f;
  for (;;) {
    const float a = rng.nextFloat(-1.0f, 1.0f);
    const float b = rng.nextFloat(-1.0f, 1.0f);
    const float r2 = a * a + b * b;
    if (r2 > 1.0f || r2 < 0.01f) continue;
    const float r = std::sqrt(r2);
    c = a / r;
    s = b / r;
    break;
  }
  const float c0 = c;
  const float s0 = s;

  std::vector<glm::vec3> strand;
  strand.reserve(settings.particlesPerStrand);
  for (std::size_t i = 0; i < settings.particlesPerStrand; ++i) {
    glm::vec3 p = root + normal * (spacing * static_cast<float>(i));
    if (settings.curlRadius > 0.0f) p += (u * (c - c0) + v * (s - s0)) * settings.curlRadius;
    strand.push_back(p);
    const float nextC = c * cosStep - s * sinStep;
    const float nextS = s * cosStep + c * sinStep;
    c = nextC;
    s = nextS;
  }
  return strand;
}

// The per-segment helix rotation as an exact rational point on the unit circle:
// (cos θ, sin θ) = ((1 − t²)/(1 + t²), 2t/(1 + t²)) with t = tan(θ/2).
std::pair<float, float> helixStep(const GroomSettings& settings) {
  const float t = tanSeries(0.5f * settings.curlAnglePerSegment);
  return {(1.0f - t * t) / (1.0f + t * t), (2.0f * t) / (1.0f + t * t)};
}

}  // namespace

glm::vec3 combAt(const GroomSettings& settings, const glm::vec3& root) noexcept {
  if (settings.partingComb == 0.0f) return settings.comb;
  const float strength = std::clamp((root.z - settings.partingBackZ) / kPartingFade, 0.0f, 1.0f);
  const float side = root.x < settings.partingX ? -1.0f : 1.0f;
  return settings.comb + glm::vec3(side * strength * settings.partingComb, 0.0f, 0.0f);
}

Result<std::vector<std::vector<glm::vec3>>> generateGroom(const GroomSettings& settings) {
  if (auto valid = validateGroomSettings(settings); !valid) return std::unexpected(valid.error());
  const auto [cosStep, sinStep] = helixStep(settings);
  SplitMix64 rng(settings.seed);
  std::vector<std::vector<glm::vec3>> strands(settings.strandCount);
  for (std::vector<glm::vec3>& strand : strands) {
    const glm::vec3 normal = randomCapDirection(rng, settings.capMinNormalY);
    strand = growStrand(rng, settings, settings.scalpCentre + normal * settings.scalpRadius, normal, cosStep, sinStep);
  }
  return strands;
}

Result<std::vector<std::vector<glm::vec3>>> generateGroomOnMesh(const GroomSettings& settings,
                                                                std::span<const glm::vec3> positions,
                                                                std::span<const std::uint32_t> indices,
                                                                std::span<const std::uint32_t> scalpTriangles,
                                                                std::span<const float> density) {
  if (auto valid = validateGroomSettings(settings); !valid) return std::unexpected(valid.error());
  if (scalpTriangles.empty()) return fail("Groom on mesh: the scalp region has no triangles.");
  if (!density.empty() && density.size() != scalpTriangles.size())
    return fail("Groom on mesh: " + std::to_string(density.size()) + " densities for " +
                std::to_string(scalpTriangles.size()) + " scalp triangles.");
  for (std::size_t slot = 0; slot < density.size(); ++slot)
    if (!(density[slot] >= 0.0f && std::isfinite(density[slot])))
      return fail("Groom on mesh: scalp triangle " + std::to_string(scalpTriangles[slot]) +
                  "'s density is not a finite number >= 0.");
  // Cumulative areas times densities (in double, so thousands of tiny triangles add up exactly
  // enough) for sampling a triangle with probability proportional to them.
  std::vector<double> cumulative;
  cumulative.reserve(scalpTriangles.size());
  double total = 0.0;
  for (std::size_t slot = 0; slot < scalpTriangles.size(); ++slot) {
    const std::uint32_t t = scalpTriangles[slot];
    if (std::size_t(t) * 3 + 2 >= indices.size())
      return fail("Groom on mesh: scalp triangle " + std::to_string(t) + " is not a triangle of the mesh (it has " +
                  std::to_string(indices.size() / 3) + ").");
    for (int k = 0; k < 3; ++k)
      if (indices[std::size_t(t) * 3 + k] >= positions.size())
        return fail("Groom on mesh: triangle " + std::to_string(t) + " uses vertex " +
                    std::to_string(indices[std::size_t(t) * 3 + k]) + " of " + std::to_string(positions.size()) + ".");
    const glm::vec3& a = positions[indices[std::size_t(t) * 3]];
    const glm::vec3 n =
        cross(positions[indices[std::size_t(t) * 3 + 1]] - a, positions[indices[std::size_t(t) * 3 + 2]] - a);
    total += 0.5 * std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z) *
             (density.empty() ? 1.0 : double(density[slot]));
    cumulative.push_back(total);
  }
  if (!(total > 0.0) || !std::isfinite(total)) return fail("Groom on mesh: the scalp region has no area.");

  const auto [cosStep, sinStep] = helixStep(settings);
  SplitMix64 rng(settings.seed);
  std::vector<std::vector<glm::vec3>> strands(settings.strandCount);
  for (std::vector<glm::vec3>& strand : strands) {
    // A triangle by area, then a uniform point in it: (1 − √r1, √r1·(1 − r2), √r1·r2)
    // (Osada et al. 2002, "Shape Distributions", §4.2). Zero-area triangles are never picked.
    const double pick = double(rng.nextFloat()) * total;
    const std::size_t k =
        std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
    const std::uint32_t t = scalpTriangles[std::min(k, scalpTriangles.size() - 1)];
    const glm::vec3& a = positions[indices[std::size_t(t) * 3]];
    const glm::vec3& b = positions[indices[std::size_t(t) * 3 + 1]];
    const glm::vec3& c = positions[indices[std::size_t(t) * 3 + 2]];
    const float r1 = std::sqrt(rng.nextFloat()), r2 = rng.nextFloat();
    const glm::vec3 root = a * (1.0f - r1) + b * (r1 * (1.0f - r2)) + c * (r1 * r2);
    strand = growStrand(rng, settings, root, normalized(cross(b - a, c - a)), cosStep, sinStep);
  }
  return strands;
}

Result<std::vector<std::vector<glm::vec3>>> generateGroomFromRoots(const GroomSettings& settings,
                                                                   std::span<const glm::vec3> roots,
                                                                   std::span<const glm::vec3> normals) {
  GroomSettings checked = settings;
  checked.strandCount = std::max<std::size_t>(roots.size(), 1);
  if (auto valid = validateGroomSettings(checked); !valid) return std::unexpected(valid.error());
  if (roots.empty()) return fail("Groom from roots: no roots.");
  if (normals.size() != roots.size())
    return fail("Groom from roots: " + std::to_string(normals.size()) + " normals for " + std::to_string(roots.size()) +
                " roots.");
  for (std::size_t r = 0; r < roots.size(); ++r) {
    const glm::vec3& p = roots[r];
    const glm::vec3& n = normals[r];
    const float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !(std::abs(length - 1.0f) <= 1e-3f))
      return fail("Groom from roots: root " + std::to_string(r) +
                  " has a position that is not finite or a normal that is not of unit length.");
  }
  const auto [cosStep, sinStep] = helixStep(settings);
  SplitMix64 rng(settings.seed);
  std::vector<std::vector<glm::vec3>> strands(roots.size());
  for (std::size_t r = 0; r < roots.size(); ++r)
    strands[r] = growStrand(rng, settings, roots[r], normals[r], cosStep, sinStep);
  return strands;
}

}  // namespace mane::physics
