#include "physics/interpolation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "physics/detail/parallel_tasks.hpp"
#include "physics/detail/portable_math.hpp"
#include "physics/split_mix64.hpp"

namespace mane::physics {

namespace {

constexpr std::size_t kMaxNeighbours = 8;  // nearest guide roots kept per guide
constexpr std::size_t kMaxVertices = kMaxStrandVertices;
// Closest distance between two guide roots that may span a frame or a triangle, metres.
constexpr double kMinPartnerDistance = 1e-6;
// A frame's partners must subtend at least this sine at the guide root (about 11.5°), so that
// the frame's normal is well conditioned.
constexpr double kMinFrameSine = 0.2;
// A barycentric triangle's corner at the home guide must be at least this sine (about 5.7°).
constexpr double kMinTriangleSine = 0.1;
constexpr int kTriangleAttempts = 8;

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The exact operations the header's formula names, written out so the compiler cannot
// reassociate them differently from the documented order.
float dot(const glm::vec3& a, const glm::vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

glm::vec3 cross(const glm::vec3& a, const glm::vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

glm::vec3 normalize(const glm::vec3& a) {
  const float length = std::sqrt(dot(a, a));
  return {a.x / length, a.y / length, a.z / length};
}

// The header's hash: Wellons' lowbias32, an integer mixer with exact operations only.
std::uint32_t lowbias32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// The header's cosSinTurns: cos and sin of 2π·w, from a Taylor series on a quarter turn.
std::pair<float, float> cosSinTurns(float w) {
  w = w - std::floor(w);
  const float y = 4.0f * w;
  const float k = std::floor(y + 0.5f);
  const float x = (y - k) * 1.57079637f;
  const float x2 = x * x;
  const float sine =
      x * (1.0f + x2 * (-0.166666672f + x2 * (0.00833333377f + x2 * (-0.000198412701f + x2 * 2.75573188e-06f))));
  const float cosine = 1.0f + x2 * (-0.5f + x2 * (0.0416666679f + x2 * (-0.00138888892f + x2 * 2.48015876e-05f)));
  switch (static_cast<int>(k) & 3) {
    case 0: return {cosine, sine};
    case 1: return {-sine, cosine};
    case 2: return {-cosine, -sine};
    default: return {sine, -cosine};
  }
}

struct Frame {
  glm::vec3 e1{1.0f, 0.0f, 0.0f};
  glm::vec3 e2{0.0f, 1.0f, 0.0f};
  glm::vec3 n{0.0f, 0.0f, 1.0f};
};

// Step 1 of the header's formula: the frame of guide `p` from its root and its partners' roots.
Frame frameOf(const glm::vec3& root, const glm::vec3& rootA, const glm::vec3& rootB) {
  Frame f;
  f.e1 = normalize(rootA - root);
  f.n = normalize(cross(f.e1, rootB - root));
  f.e2 = cross(f.n, f.e1);
  return f;
}

double distanceSquared(const glm::vec3& a, const glm::vec3& b) {
  const double x = static_cast<double>(a.x) - b.x;
  const double y = static_cast<double>(a.y) - b.y;
  const double z = static_cast<double>(a.z) - b.z;
  return x * x + y * y + z * z;
}

// Sine of the angle at `o` between the directions to `a` and `b` (0 when degenerate).
double sineAt(const glm::vec3& o, const glm::vec3& a, const glm::vec3& b) {
  const double ax = static_cast<double>(a.x) - o.x, ay = static_cast<double>(a.y) - o.y,
               az = static_cast<double>(a.z) - o.z;
  const double bx = static_cast<double>(b.x) - o.x, by = static_cast<double>(b.y) - o.y,
               bz = static_cast<double>(b.z) - o.z;
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  const double la = std::sqrt(ax * ax + ay * ay + az * az);
  const double lb = std::sqrt(bx * bx + by * by + bz * bz);
  if (!(la > kMinPartnerDistance && lb > kMinPartnerDistance)) return 0.0;
  return std::sqrt(cx * cx + cy * cy + cz * cz) / (la * lb);
}

// The nearest other guide roots of every guide, nearest first (ties by index), at most
// kMaxNeighbours each. A sweep over the roots sorted by x: each guide scans outwards until the
// x distance alone exceeds its current worst neighbour. Deterministic: the k smallest entries
// under the total order (distance², index) do not depend on the scan order.
struct Neighbours {
  std::vector<std::array<std::uint32_t, kMaxNeighbours>> index;
  std::vector<std::uint32_t> count;
};

Neighbours nearestRoots(std::span<const glm::vec3> roots) {
  const std::size_t n = roots.size();
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return roots[a].x < roots[b].x || (roots[a].x == roots[b].x && a < b);
  });

  Neighbours result;
  result.index.resize(n);
  result.count.assign(n, 0);
  for (std::size_t pos = 0; pos < n; ++pos) {
    const std::uint32_t self = order[pos];
    std::array<std::pair<double, std::uint32_t>, kMaxNeighbours> best;
    std::size_t have = 0;
    const auto consider = [&](std::uint32_t other) {
      const std::pair<double, std::uint32_t> entry{distanceSquared(roots[self], roots[other]), other};
      if (have == kMaxNeighbours && !(entry < best[have - 1])) return;
      std::size_t at = have < kMaxNeighbours ? have++ : have - 1;
      while (at > 0 && entry < best[at - 1]) {
        best[at] = best[at - 1];
        --at;
      }
      best[at] = entry;
    };
    const auto beyond = [&](std::uint32_t other) {
      const double dx = static_cast<double>(roots[other].x) - roots[self].x;
      return have == kMaxNeighbours && dx * dx > best[have - 1].first;
    };
    for (std::size_t q = pos + 1; q < n && !beyond(order[q]); ++q) consider(order[q]);
    for (std::size_t q = pos; q-- > 0 && !beyond(order[q]);) consider(order[q]);
    for (std::size_t k = 0; k < have; ++k) result.index[self][k] = best[k].second;
    result.count[self] = static_cast<std::uint32_t>(have);
  }
  return result;
}

// A uniform random index in [0, n) (Lemire's multiply-shift; the bias for n ≤ 8 is < 2⁻²⁹).
std::uint32_t randomIndex(SplitMix64& rng, std::uint32_t n) {
  return static_cast<std::uint32_t>(((rng.next() >> 32) * n) >> 32);
}

// A uniform random point in the unit disc (z = 0) or ball, by rejection (no trigonometry).
glm::vec3 randomInDisc(SplitMix64& rng) {
  for (;;) {
    const glm::vec3 p{rng.nextFloat(-1.0f, 1.0f), rng.nextFloat(-1.0f, 1.0f), 0.0f};
    if (p.x * p.x + p.y * p.y <= 1.0f) return p;
  }
}

glm::vec3 randomInBall(SplitMix64& rng) {
  for (;;) {
    const glm::vec3 p{rng.nextFloat(-1.0f, 1.0f), rng.nextFloat(-1.0f, 1.0f), rng.nextFloat(-1.0f, 1.0f)};
    if (p.x * p.x + p.y * p.y + p.z * p.z <= 1.0f) return p;
  }
}

}  // namespace

float clumpProfileScale(float rootRadius, float profile) {
  const double rho = std::clamp(static_cast<double>(rootRadius), 0.0, 1.0);
  const double p = profile;
  if (rho == 0.0) return static_cast<float>(1.0 / std::sqrt(p + 1.0));  // the limit of ρ'/ρ
  const double outside = 1.0 - rho * rho;
  if (outside <= 0.0) return 1.0f;
  const double inside = 1.0 - detail::exponential(detail::logarithm(outside) / (p + 1.0));
  return static_cast<float>(std::sqrt(inside) / rho);
}

Result<DenseStrandLayout> buildDenseStrandLayout(std::span<const std::vector<glm::vec3>> restGuides,
                                                const DenseGroomSettings& settings) {
  const auto bad = [](const char* field, const char* expected) {
    return fail(std::string("Dense groom settings: ") + field + " must be " + expected + ".");
  };
  if (settings.strandCount < 1 || settings.strandCount > std::numeric_limits<std::uint32_t>::max())
    return bad("strandCount", "at least 1 and below 2^32");
  if (settings.verticesPerStrand == 1 || settings.verticesPerStrand > kMaxVertices)
    return bad("verticesPerStrand", "0 (as the guides) or in [2, 4096]");
  if (!(settings.rootSpread >= 0.0f && settings.rootSpread <= 4.0f)) return bad("rootSpread", "in [0, 4]");
  if (!(settings.lengthVariation >= 0.0f && settings.lengthVariation < 1.0f))
    return bad("lengthVariation", "in [0, 1)");
  if (!(settings.clump >= 0.0f && settings.clump <= 1.0f)) return bad("clump", "in [0, 1]");
  if (!(settings.clumpVariation >= 0.0f && settings.clumpVariation <= 1.0f)) return bad("clumpVariation", "in [0, 1]");
  if (!(settings.clumpProfile >= 0.0f && settings.clumpProfile <= 8.0f)) return bad("clumpProfile", "in [0, 8]");
  if (!(settings.tipJitter >= 0.0f && std::isfinite(settings.tipJitter)))
    return bad("tipJitter", "a non-negative number of metres");
  if (!(settings.curlRadius >= 0.0f && settings.curlRadius <= 0.05f)) return bad("curlRadius", "in [0, 0.05] metres");
  if (!(settings.curlPeriod >= 0.001f && settings.curlPeriod <= 10.0f))
    return bad("curlPeriod", "in [0.001, 10] metres");
  if (!(settings.curlVariation >= 0.0f && settings.curlVariation <= 1.0f)) return bad("curlVariation", "in [0, 1]");
  if (!(settings.frizz >= 0.0f && settings.frizz <= 0.01f)) return bad("frizz", "in [0, 0.01] metres");
  if (settings.neighbourCandidates < 2 || settings.neighbourCandidates > kMaxNeighbours)
    return bad("neighbourCandidates", "in [2, 8]");
  if (!(settings.minBlendCosine >= -1.0f && settings.minBlendCosine <= 1.0f))
    return bad("minBlendCosine", "in [-1, 1]");
  if (settings.blend != GuideBlend::kSingle && settings.blend != GuideBlend::kBarycentric)
    return bad("blend", "kSingle or kBarycentric");
  if (settings.curve != StrandCurve::kLinear && settings.curve != StrandCurve::kCatmullRom)
    return bad("curve", "kLinear or kCatmullRom");

  if (restGuides.empty()) return fail("Dense groom: the guide groom is empty; at least one guide strand is needed.");
  if (restGuides.size() > std::numeric_limits<std::uint32_t>::max() - 1)
    return fail("Dense groom: too many guides (" + std::to_string(restGuides.size()) + ").");
  const std::size_t guideVertices = restGuides[0].size();
  for (std::size_t g = 0; g < restGuides.size(); ++g) {
    if (restGuides[g].size() < 2)
      return fail("Dense groom: guide " + std::to_string(g) + " has " + std::to_string(restGuides[g].size()) +
                  " point(s); a guide needs at least 2.");
    if (restGuides[g].size() != guideVertices)
      return fail("Dense groom: guide " + std::to_string(g) + " has " + std::to_string(restGuides[g].size()) +
                  " points but guide 0 has " + std::to_string(guideVertices) +
                  "; resample the guides to one point count first.");
    for (std::size_t v = 0; v < guideVertices; ++v)
      if (!isFinite(restGuides[g][v]))
        return fail("Dense groom: guide " + std::to_string(g) + ", vertex " + std::to_string(v) +
                    " is not finite (NaN or infinite).");
  }
  if (guideVertices > kMaxVertices) return fail("Dense groom: guides have more than 4096 points.");

  const std::size_t guideCount = restGuides.size();
  DenseStrandLayout layout;
  layout.guideCount = static_cast<std::uint32_t>(guideCount);
  layout.guideVertexCount = static_cast<std::uint32_t>(guideVertices);
  layout.vertexCount =
      static_cast<std::uint32_t>(settings.verticesPerStrand == 0 ? guideVertices : settings.verticesPerStrand);
  layout.curve = settings.curve;

  std::vector<glm::vec3> roots(guideCount);
  for (std::size_t g = 0; g < guideCount; ++g) roots[g] = restGuides[g][0];
  const Neighbours neighbours = nearestRoots(roots);

  // Frame partners: A = the nearest root at a usable distance, B = the next nearest that spans a
  // well-conditioned plane with it; ordered so that n points along the guide's first segment
  // (out of the scalp). Spread radius: the distance to the nearest usable neighbour.
  layout.guideFrames.resize(guideCount);
  std::vector<float> spreadRadius(guideCount, 0.0f);
  for (std::size_t g = 0; g < guideCount; ++g) {
    const auto self = static_cast<std::uint32_t>(g);
    layout.guideFrames[g] = {self, self};
    std::size_t a = kMaxNeighbours;
    for (std::size_t k = 0; k < neighbours.count[g]; ++k) {
      const std::uint32_t other = neighbours.index[g][k];
      if (a == kMaxNeighbours) {
        if (distanceSquared(roots[g], roots[other]) > kMinPartnerDistance * kMinPartnerDistance) {
          a = k;
          spreadRadius[g] = static_cast<float>(std::sqrt(distanceSquared(roots[g], roots[other])));
        }
        continue;
      }
      const std::uint32_t partnerA = neighbours.index[g][a];
      if (sineAt(roots[g], roots[partnerA], roots[other]) < kMinFrameSine) continue;
      const Frame f = frameOf(roots[g], roots[partnerA], roots[other]);
      if (dot(f.n, restGuides[g][1] - restGuides[g][0]) >= 0.0f)
        layout.guideFrames[g] = {partnerA, other};
      else
        layout.guideFrames[g] = {other, partnerA};
      break;
    }
  }

  // The barycentric partners of each guide: those of its nearest neighbourCandidates roots whose
  // guides leave the scalp the way it does (their first segments), so that guides combed apart,
  // which may fall side by side further down, are not blended.
  Neighbours blendPartners;
  blendPartners.index.resize(guideCount);
  blendPartners.count.assign(guideCount, 0);
  if (settings.blend == GuideBlend::kBarycentric) {
    std::vector<glm::vec3> directions(guideCount);
    for (std::size_t g = 0; g < guideCount; ++g) {
      const glm::vec3 first = restGuides[g][1] - restGuides[g][0];
      directions[g] = dot(first, first) > 0.0f ? normalize(first) : glm::vec3(0.0f);
    }
    for (std::size_t g = 0; g < guideCount; ++g) {
      const auto candidates =
          std::min<std::uint32_t>(neighbours.count[g], static_cast<std::uint32_t>(settings.neighbourCandidates));
      for (std::uint32_t k = 0; k < candidates; ++k) {
        const std::uint32_t other = neighbours.index[g][k];
        if (settings.minBlendCosine <= -1.0f || dot(directions[g], directions[other]) >= settings.minBlendCosine)
          blendPartners.index[g][blendPartners.count[g]++] = other;
      }
    }
  }

  // Each guide's length at rest: a strand's curl turns once per curlPeriod of it.
  std::vector<float> guideLength(guideCount, 0.0f);
  for (std::size_t g = 0; g < guideCount; ++g)
    for (std::size_t v = 0; v + 1 < guideVertices; ++v)
      guideLength[g] += static_cast<float>(std::sqrt(distanceSquared(restGuides[g][v], restGuides[g][v + 1])));

  const std::size_t denseVertices = layout.vertexCount;
  const float guideSpan = static_cast<float>(guideVertices - 1);
  const float denseSpan = static_cast<float>(denseVertices - 1);
  layout.strands.resize(settings.strandCount);
  for (std::size_t s = 0; s < settings.strandCount; ++s) {
    // One independent stream per strand: strand s's layout does not depend on strandCount.
    SplitMix64 rng(SplitMix64(settings.seed + 0xD1B54A32D192ED03ull * static_cast<std::uint64_t>(s)).next());
    DenseStrand& strand = layout.strands[s];
    // Consecutive strands share a home guide: interpolation reuses the guide's frame and cache lines.
    const auto home = static_cast<std::uint32_t>(static_cast<std::uint64_t>(s) * guideCount / settings.strandCount);
    strand.guides[0] = home;

    strand.lengthScale = 1.0f - settings.lengthVariation * rng.nextFloat();
    float scale = strand.lengthScale * guideSpan / denseSpan;
    // Rounding must not push the last dense vertex past the guide's tip.
    while (denseSpan * scale > guideSpan) scale = std::nextafter(scale, 0.0f);
    strand.vertexScale = scale;
    strand.clump = std::clamp(settings.clump + settings.clumpVariation * rng.nextFloat(-1.0f, 1.0f), 0.0f, 1.0f);
    strand.tipJitter = settings.tipJitter * randomInBall(rng);

    bool barycentric = false;
    float rootRadius = 0.0f;  // the share of the clump's radius the root lies at (see clumpProfileScale)
    if (settings.blend == GuideBlend::kBarycentric) {
      const std::array<std::uint32_t, kMaxNeighbours>& partners = blendPartners.index[home];
      const std::uint32_t candidates = blendPartners.count[home];
      for (int attempt = 0; candidates >= 2 && attempt < kTriangleAttempts && !barycentric; ++attempt) {
        const std::uint32_t i = randomIndex(rng, candidates);
        std::uint32_t j = randomIndex(rng, candidates - 1);
        if (j >= i) ++j;
        const std::uint32_t a = partners[i];
        const std::uint32_t b = partners[j];
        if (sineAt(roots[home], roots[a], roots[b]) < kMinTriangleSine) continue;
        // A uniform point of the triangle (fold the unit square's upper half back). The
        // coordinates are multiples of 2⁻²⁴, so 1 − u − v is exact and the weights sum to 1.
        float u = rng.nextFloat();
        float v = rng.nextFloat();
        if (u + v > 1.0f) {
          u = 1.0f - u;
          v = 1.0f - v;
        }
        strand.guides[1] = a;
        strand.guides[2] = b;
        strand.weights[0] = (1.0f - u) - v;
        strand.weights[1] = u;
        strand.weights[2] = v;
        strand.guideCount = 3;
        barycentric = true;
        rootRadius = u + v;
      }
    }
    if (!barycentric) {
      strand.guideCount = 1;
      strand.guides[1] = strand.guides[2] = 0;
      strand.weights[0] = 1.0f;
      strand.weights[1] = strand.weights[2] = 0.0f;
      const glm::vec3 inDisc = randomInDisc(rng);
      strand.rootOffset = (settings.rootSpread * spreadRadius[home]) * inDisc;
      rootRadius = std::sqrt(inDisc.x * inDisc.x + inDisc.y * inDisc.y);
    }
    if (settings.clumpProfile > 0.0f)
      strand.clump = 1.0f - (1.0f - strand.clump) * clumpProfileScale(rootRadius, settings.clumpProfile);
    // Drawn last, so that a groom without curl keeps the layout it had before curl existed.
    if (settings.curlRadius > 0.0f) {
      strand.curlRadius = settings.curlRadius * (1.0f + settings.curlVariation * rng.nextFloat(-1.0f, 1.0f));
      strand.curlTurns = strand.lengthScale * guideLength[home] / settings.curlPeriod;
      strand.curlPhase = rng.nextFloat();
    }
    strand.frizz = settings.frizz;
  }
  return layout;
}

namespace {

// The header's vertex beyond a guide's end `end`, from the vertices `next` and (on guides of three
// or more) `third` inwards from it.
glm::vec3 beyondEnd(const glm::vec3& end, const glm::vec3& next, const glm::vec3* third) {
  if (third == nullptr) return end + (end - next);
  return 3.0f * (end - next) + *third;
}

// The header's weights of the four guide vertices around a dense vertex at fraction f of its
// segment: (1 − f, f) on the straight segment, (a, b, c, d) on the curve. They depend on f only,
// so a dense vertex computes them once for all its guides.
struct CurveWeights {
  float a = 0.0f, b = 0.0f, c = 0.0f, d = 0.0f;
};

template <StrandCurve Curve>
CurveWeights curveWeights(float f) {
  if constexpr (Curve == StrandCurve::kLinear) {
    return {0.0f, 1.0f - f, f, 0.0f};
  } else {
    const float f2 = f * f;
    const float f3 = f2 * f;
    return {0.5f * ((2.0f * f2 - f3) - f), 0.5f * ((3.0f * f3 - 5.0f * f2) + 2.0f),
            0.5f * ((4.0f * f2 - 3.0f * f3) + f), 0.5f * (f3 - f2)};
  }
}

// The point at segment v along one guide with the weights `w`, by the header's formula for the
// curve. `last` = Ng − 1.
template <StrandCurve Curve>
glm::vec3 alongGuide(const glm::vec3* guide, std::uint32_t v, std::uint32_t last, const CurveWeights& w) {
  if constexpr (Curve == StrandCurve::kLinear) {
    return w.b * guide[v] + w.c * guide[v + 1];
  } else {
    const glm::vec3 p0 = v > 0 ? guide[v - 1] : beyondEnd(guide[0], guide[1], last > 1 ? &guide[2] : nullptr);
    const glm::vec3 p3 =
        v + 1 < last ? guide[v + 2] : beyondEnd(guide[last], guide[last - 1], last > 1 ? &guide[last - 2] : nullptr);
    return ((w.a * p0 + w.b * guide[v]) + w.c * guide[v + 1]) + w.d * p3;
  }
}

// The curl's side carried down a strand: the primary guide's point, way and side at the last
// vertex (the header's x', d', a').
struct CurlSide {
  glm::vec3 x{0.0f}, d{0.0f}, a{0.0f};
};

// The header's v − (2·dot(v1, v) / c1)·v1: v reflected in the plane normal to v1 (c1 = dot(v1, v1)).
glm::vec3 reflect(const glm::vec3& v, const glm::vec3& v1, float c1) {
  return v - ((2.0f * dot(v1, v)) / c1) * v1;
}

// The header's W + F, the curl and frizz of dense vertex i (`vertex` = s·Nd + i) at t, fraction f
// of segment v of the primary guide `primary` (Ng − 1 = `last`), whose point there is `l0`;
// `side` holds vertex i − 1's and takes vertex i's.
glm::vec3 curlAndFrizz(const DenseStrand& strand, const Frame& frame, const glm::vec3* primary, std::uint32_t v,
                       std::uint32_t last, float f, float t, const glm::vec3& l0, std::uint32_t i, std::uint32_t vertex,
                       CurlSide& side) {
  const auto wayAt = [&](std::uint32_t k) { return primary[std::min(k + 1, last)] - primary[std::max(k, 1u) - 1]; };
  const glm::vec3 along = (1.0f - f) * wayAt(v) + f * wayAt(v + 1);
  const glm::vec3 d = dot(along, along) > 0.0f ? normalize(along) : frame.n;
  glm::vec3 a;
  if (i == 0) {
    const glm::vec3 across = cross(d, frame.n);
    a = dot(across, across) > 0.0f ? normalize(across) : frame.e1;
  } else {
    const glm::vec3 v1 = l0 - side.x;
    const float c1 = dot(v1, v1);
    const glm::vec3 aL = c1 > 0.0f ? reflect(side.a, v1, c1) : side.a;
    const glm::vec3 dL = c1 > 0.0f ? reflect(side.d, v1, c1) : side.d;
    const glm::vec3 v2 = d - dL;
    const float c2 = dot(v2, v2);
    const glm::vec3 r = c2 > 0.0f ? reflect(aL, v2, c2) : aL;
    const glm::vec3 across = r - dot(r, d) * d;
    a = dot(across, across) > 0.0f ? normalize(across) : side.a;
  }
  side = {l0, d, a};
  const glm::vec3 b = cross(d, a);
  const auto [co, si] = cosSinTurns(strand.curlPhase + strand.curlTurns * t);
  const float radius = strand.curlRadius * std::min(4.0f * t, 1.0f);
  const glm::vec3 curl = (co * radius) * a + (si * radius) * b;
  float x[3];
  for (std::uint32_t k = 0; k < 3; ++k)
    x[k] = static_cast<float>(lowbias32(3u * vertex + k) >> 8) * 1.1920929e-07f - 1.0f;
  const glm::vec3 frizz = (strand.frizz * t) * ((x[0] * frame.e1 + x[1] * frame.e2) + x[2] * frame.n);
  return curl + frizz;
}

// Step 2 of the header's formula for one strand with K guides. K and the curve are template
// parameters only so that the compiler unrolls the guide loop and drops the other curve; the
// operations are those of the formula, in order. `first` is the strand's first vertex, s·Nd.
template <std::uint32_t K, StrandCurve Curve>
void interpolateStrand(const DenseStrand& strand, const glm::vec3* const* g, std::uint32_t lastSegment, const float* t,
                       std::size_t nd, const Frame& frame, std::uint32_t first, glm::vec3* p) {
  const std::uint32_t last = lastSegment + 1;
  const glm::vec3 o = strand.rootOffset;
  const glm::vec3 j = strand.tipJitter;
  const glm::vec3 offset = (o.x * frame.e1 + o.y * frame.e2) + o.z * frame.n;
  const glm::vec3 jitter = (j.x * frame.e1 + j.y * frame.e2) + j.z * frame.n;
  const bool curled = strand.curlRadius > 0.0f || strand.frizz > 0.0f;
  CurlSide side;
  for (std::size_t i = 0; i < nd; ++i) {
    const float u = static_cast<float>(i) * strand.vertexScale;
    const std::uint32_t v = std::min(static_cast<std::uint32_t>(u), lastSegment);
    const float f = u - static_cast<float>(v);
    const CurveWeights w = curveWeights<Curve>(f);
    const glm::vec3 l0 = alongGuide<Curve>(g[0], v, last, w);
    glm::vec3 b = strand.weights[0] * l0;
    for (std::uint32_t k = 1; k < K; ++k) b = b + strand.weights[k] * alongGuide<Curve>(g[k], v, last, w);
    const float h = strand.clump * t[i];
    const float q = 1.0f - h;
    p[i] = (b + h * (l0 - b)) + q * (offset + t[i] * jitter);
    if (curled) {
      const auto index = static_cast<std::uint32_t>(i);
      p[i] = p[i] + curlAndFrizz(strand, frame, g[0], v, last, f, t[i], l0, index, first + index, side);
    }
  }
}

template <StrandCurve Curve>
void interpolateStrand(const DenseStrand& strand, const glm::vec3* const* g, std::uint32_t lastSegment, const float* t,
                       std::size_t nd, const Frame& frame, std::uint32_t first, glm::vec3* p) {
  switch (strand.guideCount) {
    case 1: interpolateStrand<1, Curve>(strand, g, lastSegment, t, nd, frame, first, p); break;
    case 2: interpolateStrand<2, Curve>(strand, g, lastSegment, t, nd, frame, first, p); break;
    default: interpolateStrand<3, Curve>(strand, g, lastSegment, t, nd, frame, first, p); break;
  }
}

// Steps 1–3 of the header's formula for dense strands [first, end).
void interpolateRange(std::span<const glm::vec3> guides, const DenseStrandLayout& layout, std::span<glm::vec3> out,
                      std::span<glm::vec3> tangents, std::size_t first, std::size_t end) {
  const std::size_t ng = layout.guideVertexCount;
  const std::size_t nd = layout.vertexCount;
  const auto lastSegment = static_cast<std::uint32_t>(ng - 2);
  // t depends on the vertex only: computed once, with the formula's division.
  float t[kMaxVertices];
  for (std::size_t i = 0; i < nd; ++i) t[i] = static_cast<float>(i) / static_cast<float>(nd - 1);

  Frame frame;
  std::uint32_t framePrimary = std::numeric_limits<std::uint32_t>::max();  // guide `frame` belongs to
  for (std::size_t s = first; s < end; ++s) {
    const DenseStrand& strand = layout.strands[s];
    const std::uint32_t primary = strand.guides[0];
    const GuideFrameRef ref = layout.guideFrames[primary];
    if (primary != framePrimary) {  // the same operations for every strand: reuse is exact
      frame = Frame{};
      if (ref.partnerA != primary || ref.partnerB != primary)
        frame = frameOf(guides[primary * ng], guides[ref.partnerA * ng], guides[ref.partnerB * ng]);
      framePrimary = primary;
    }
    const glm::vec3* g[3] = {nullptr, nullptr, nullptr};
    for (std::uint32_t k = 0; k < strand.guideCount; ++k) g[k] = guides.data() + strand.guides[k] * ng;
    glm::vec3* p = out.data() + s * nd;
    // Vertex indices wrap modulo 2^32 in the frizz's hash, as the shader's do.
    const auto first = static_cast<std::uint32_t>(s * nd);
    if (layout.curve == StrandCurve::kLinear)
      interpolateStrand<StrandCurve::kLinear>(strand, g, lastSegment, t, nd, frame, first, p);
    else
      interpolateStrand<StrandCurve::kCatmullRom>(strand, g, lastSegment, t, nd, frame, first, p);

    if (tangents.empty()) continue;
    glm::vec3* tangent = tangents.data() + s * nd;
    for (std::size_t i = 0; i < nd; ++i) {
      const glm::vec3 delta = p[i + 1 < nd ? i + 1 : i] - p[i > 0 ? i - 1 : i];
      tangent[i] = dot(delta, delta) > 0.0f ? normalize(delta) : glm::vec3(0.0f);
    }
  }
}

}  // namespace

Result<void> interpolateDenseStrands(std::span<const glm::vec3> guidePositions, const DenseStrandLayout& layout,
                                     std::span<glm::vec3> positions, std::span<glm::vec3> tangents, const TaskRunner& tasks) {
  const auto denseGroomError = [](const Error& error) { return fail("Dense groom: " + error.message); };
  if (auto valid = validateStrandLayout(layout); !valid) return denseGroomError(valid.error());
  if (positions.size() != layout.vertexTotal())
    return fail("Dense groom: the output holds " + std::to_string(positions.size()) + " positions; the layout needs " +
                std::to_string(layout.vertexTotal()) + ".");
  if (!tangents.empty() && tangents.size() != layout.vertexTotal())
    return fail("Dense groom: the tangent output holds " + std::to_string(tangents.size()) +
                " vectors; the layout needs " + std::to_string(layout.vertexTotal()) + " (or none).");
  if (auto valid =
          validateGuidePositions(guidePositions, layout.guideCount, layout.guideVertexCount, layout.guideFrames);
      !valid)
    return denseGroomError(valid.error());

  // A fixed partition into contiguous ranges of whole dense strands, one per task; every
  // strand's arithmetic is independent of the partition, so the output does not depend on it.
  const std::size_t count = layout.strands.size();
  const std::uint32_t taskCount = detail::taskCountFor(tasks, count);
  auto task = [&](std::uint32_t t) {
    interpolateRange(guidePositions, layout, positions, tangents, detail::taskRangeBegin(count, taskCount, t),
                     detail::taskRangeBegin(count, taskCount, t + 1));
  };
  if (auto ran = detail::runTasks(tasks, taskCount, task); !ran) return fail("Dense groom: " + ran.error().message);
  return {};
}

Result<void> interpolateDenseStrands(std::span<const glm::vec3> guidePositions, const DenseStrandLayout& layout,
                                     std::span<glm::vec3> positions, std::span<glm::vec3> tangents, unsigned threads) {
  return interpolateDenseStrands(guidePositions, layout, positions, tangents, builtInTaskRunner(threads));
}

Result<DenseStrandInterpolator> DenseStrandInterpolator::create(const InterpolationSettings& settings) {
  if (auto valid = validateTaskRunner(settings.tasks, "InterpolationSettings.tasks"); !valid)
    return std::unexpected(valid.error());
  auto layout = buildDenseStrandLayout(settings.restGuides, settings.groom);
  if (!layout) {
    // buildDenseStrandLayout checks the groom settings first, in messages of their own.
    const bool groom = layout.error().message.starts_with("Dense groom settings");
    return fail(std::string(groom ? "InterpolationSettings.groom: " : "InterpolationSettings.restGuides: ") +
                layout.error().message);
  }
  return DenseStrandInterpolator(std::move(*layout), settings.tasks);
}

Result<void> DenseStrandInterpolator::interpolate(std::span<const glm::vec3> guidePositions,
                                                  std::span<glm::vec3> positions, std::span<glm::vec3> tangents) const {
  return interpolateDenseStrands(guidePositions, layout_, positions, tangents, tasks_);
}

Result<void> DenseStrandInterpolator::setTaskRunner(TaskRunner tasks) {
  if (auto valid = validateTaskRunner(tasks, "DenseStrandInterpolator::setTaskRunner: the runner"); !valid) return valid;
  tasks_ = std::move(tasks);
  return {};
}

}  // namespace mane::physics
