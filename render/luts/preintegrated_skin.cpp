#include "render/luts/preintegrated_skin.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "render/luts/skin_specular.hpp"

namespace mane::render {

namespace {

constexpr double kPi = std::numbers::pi;

// Numerator and denominator of equation (1) for one Gaussian (unweighted).
struct Moments {
  double lit = 0.0;    // ∫ max(cos(θ + x), 0) G dx
  double total = 0.0;  // ∫ G dx
};

// Equation (1)'s integrals for the Gaussian of variance `variance` over the part of [−X, X]
// it reaches, by the rule of the file comment. Mirrored by shaders/preintegrated_skin.comp.
Moments integrateGaussian(double variance, double nDotL, double theta, double curvature, double halfRange) {
  const double reach = 0.5 * kProfileReach * std::sqrt(variance) * curvature;  // sin of half the arc
  const double limit = reach >= 1.0 ? halfRange : std::min(halfRange, 2.0 * std::asin(reach));
  // Breaks: −limit, the kinks of max(cos(θ + x), 0) at x = (k + ½)π − θ, the peak at 0, +limit.
  std::array<double, 16> breaks{};
  std::size_t count = 0;
  breaks[count++] = -limit;
  const auto kinkAt = [&](int k) { return (k + 0.5) * kPi - theta; };
  const int first = static_cast<int>(std::ceil((-limit + theta) / kPi - 0.5));
  const int last = static_cast<int>(std::floor((limit + theta) / kPi - 0.5));
  bool zeroPlaced = false;
  for (int k = first; k <= last && count + 2 < breaks.size(); ++k) {
    const double kink = kinkAt(k);
    if (!zeroPlaced && kink >= 0.0) {
      breaks[count++] = 0.0;
      zeroPlaced = true;
    }
    if (kink > -limit && kink < limit) breaks[count++] = kink;
  }
  if (!zeroPlaced) breaks[count++] = 0.0;
  breaks[count++] = limit;

  Moments m;
  const double sinTheta = std::sqrt(std::max(1.0 - nDotL * nDotL, 0.0));
  const double inverseCurvature = 1.0 / curvature;
  for (std::size_t piece = 0; piece + 1 < count; ++piece) {
    const double a = breaks[piece], b = breaks[piece + 1];
    if (b <= a) continue;
    const double middle = 0.5 * (a + b), half = 0.5 * (b - a);
    for (const QuadratureNode& node : skinQuadratureRule()) {
      const double x = middle + half * node.position;
      const double chord = 2.0 * std::sin(0.5 * x) * inverseCurvature;  // mm
      const double g = half * node.weight * skinGaussian(variance, chord);
      m.lit += std::max(nDotL * std::cos(x) - sinTheta * std::sin(x), 0.0) * g;  // max(cos(θ + x), 0)
      m.total += g;
    }
  }
  return m;
}

}  // namespace

const std::array<QuadratureNode, kSkinQuadratureNodes>& skinQuadratureRule() {
  static const std::array<QuadratureNode, kSkinQuadratureNodes> rule = [] {
    const std::vector<QuadratureNode> nodes = gaussLegendre(kSkinQuadratureNodes);
    std::array<QuadratureNode, kSkinQuadratureNodes> fixed{};
    std::copy(nodes.begin(), nodes.end(), fixed.begin());
    return fixed;
  }();
  return rule;
}

double integrationHalfRange(SkinIntegrationRange range, double curvature) {
  // π(r + 1)/(2r) = (π/2)(1 + 1/r): finite at 1/r = 0.
  return range == SkinIntegrationRange::kPenner ? 0.5 * kPi : 0.5 * kPi * (1.0 + curvature);
}

std::array<glm::dvec3, 3> preintegratedAmbientBands(const SkinProfile& profile, SkinIntegrationRange range,
                                                    double curvature) {
  static const std::vector<QuadratureNode> nodes = gaussLegendre(32);
  constexpr double kLambert[3] = {std::numbers::pi, 2.0 * std::numbers::pi / 3.0, std::numbers::pi / 4.0};
  std::array<glm::dvec3, 3> bands{};
  for (const double side : {-1.0, 1.0})  // the halves either side of D's kink at μ = 0 for flat skin
    for (const QuadratureNode& node : nodes) {
      const double mu = side * 0.5 * (node.position + 1.0);
      const glm::dvec3 d = preintegratedDiffuse(profile, range, mu, curvature) * (0.5 * node.weight);
      const double legendre[3] = {1.0, mu, 0.5 * (3.0 * mu * mu - 1.0)};
      for (int l = 0; l < 3; ++l) bands[std::size_t(l)] += d * (2.0 * std::numbers::pi * legendre[l]);
    }
  for (int l = 0; l < 3; ++l) bands[std::size_t(l)] /= kLambert[l];
  return bands;
}

glm::dvec3 preintegratedDiffuse(const SkinProfile& profile, SkinIntegrationRange range, double nDotL,
                                double curvature) {
  nDotL = std::clamp(nDotL, -1.0, 1.0);
  // A flat surface: the kernel is a delta at x = 0.
  if (curvature <= 0.0) return glm::dvec3(std::max(nDotL, 0.0));
  const double theta = std::acos(nDotL);
  const double halfRange = integrationHalfRange(range, curvature);
  glm::dvec3 lit(0.0), total(0.0);
  for (const SkinGaussian& g : profile.gaussians) {
    if (g.weight == glm::dvec3(0.0)) continue;
    const Moments m = integrateGaussian(g.variance, nDotL, theta, curvature, halfRange);
    lit += g.weight * m.lit;
    total += g.weight * m.total;
  }
  return lit / total;
}

Result<void> validate(const PreintegratedSkinSettings& settings) {
  if (auto profile = validate(settings.profile); !profile) return profile;
  if (settings.size < 2 || settings.size > 4096)
    return fail("pre-integrated skin table: size " + std::to_string(settings.size) + ", expected 2 … 4096 texels");
  if (!std::isfinite(settings.maxCurvature) || settings.maxCurvature <= 0.0 || settings.maxCurvature > 10.0)
    return fail("pre-integrated skin table: maxCurvature " + std::to_string(settings.maxCurvature) +
                " mm⁻¹, expected a number in (0, 10]");
  return {};
}

PreintegratedSkinSample preintegratedSkinSample(const PreintegratedSkinSettings& settings, std::uint32_t i,
                                                std::uint32_t j) {
  const double s = double(i) / double(settings.size - 1);
  const double t = double(j) / double(settings.size - 1);
  return {
      .nDotL = 2.0 * s - 1.0, .curvature = t * settings.maxCurvature, .nDotH = s, .roughness = t * kMaxSkinRoughness};
}

glm::dvec4 preintegratedSkinTexel(const PreintegratedSkinSettings& settings, std::uint32_t i, std::uint32_t j) {
  const PreintegratedSkinSample p = preintegratedSkinSample(settings, i, j);
  const glm::dvec3 diffuse = preintegratedDiffuse(settings.profile, settings.range, p.nDotL, p.curvature);
  return {diffuse, encodeBeckmann(beckmannDistribution(p.nDotH, p.roughness))};
}

}  // namespace mane::render
