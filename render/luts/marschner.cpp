#include "render/luts/marschner.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace mane::render {

namespace {

constexpr double kPi = std::numbers::pi;

double safeSqrt(double x) {
  return std::sqrt(std::max(x, 0.0));
}

// log I0(x) for x ≥ 0. The power series Σ (x²/4)^k/(k!)² converges for every x but its terms
// overflow and lose digits for large x; beyond 20 the asymptotic series of e^−x I0(x) (Abramowitz &
// Stegun 9.7.1) with four terms is accurate to about 1e-7 relative.
double logBesselI0(double x) {
  if (x < 20.0) {
    const double q = 0.25 * x * x;
    double term = 1.0, sum = 1.0;
    for (int k = 1; k < 80 && term > 1e-17 * sum; ++k) {
      term *= q / (double(k) * double(k));
      sum += term;
    }
    return std::log(sum);
  }
  const double y = 1.0 / (8.0 * x);
  // Coefficients ((2k−1)!!)² / k!: 1, 1, 9/2, 225/6, 11025/24.
  const double series = 1.0 + y * (1.0 + y * (4.5 + y * (37.5 + y * 459.375)));
  return x - 0.5 * std::log(2.0 * kPi * x) + std::log(series);
}

// The Gaussian detector D of [dE11 eq. 11]: a normal density of standard deviation `sigma` wrapped
// onto the circle. With x reduced to [−π, π], the images left out (|k| ≥ 2) lie ≥ 3π away and
// carry erfc(3π/(σ√2)) of the mass: < 1e-8 for the σ ≤ π/2 that validate() allows.
double wrappedGaussian(double x, double sigma) {
  x = std::remainder(x, 2.0 * kPi);
  const double norm = 1.0 / (std::sqrt(2.0 * kPi) * sigma);
  const double s2 = 2.0 * sigma * sigma;
  return norm * (std::exp(-x * x / s2) + std::exp(-(x - 2.0 * kPi) * (x - 2.0 * kPi) / s2) +
                 std::exp(-(x + 2.0 * kPi) * (x + 2.0 * kPi) / s2));
}

// What one node of the h integral contributes: attenuations and exit azimuths of the three paths.
struct PathNode {
  double weight;    // ½ dh of the folded ±h pair: the midpoint weight × cos γi
  double aR;        // A_R
  glm::dvec3 aTT;   // A_TT
  glm::dvec3 aTRT;  // A_TRT
  double phi[3];    // Φ_p(h)
};

template <class Visit>
void forEachPathNode(const HairShadingParams& params, double cosThetaR, Visit&& visit) {
  const double eta = params.refractiveIndex;
  cosThetaR = std::clamp(cosThetaR, 0.0, 1.0);
  const double sin2ThetaR = 1.0 - cosThetaR * cosThetaR;
  // sin γt = h/η' = h cosθr / sqrt(η² − sin²θr): finite as θr → π/2, where γt → 0.
  const double inverseEtaPrime = cosThetaR / std::sqrt(eta * eta - sin2ThetaR);
  const double cosThetaT = safeSqrt(1.0 - sin2ThetaR / (eta * eta));
  const glm::dvec3 sigma(params.absorption);
  const double step = 0.5 * kPi / kAzimuthalNodes;
  for (std::uint32_t j = 0; j < kAzimuthalNodes; ++j) {
    const double gammaI = (j + 0.5) * step;
    const double h = std::sin(gammaI);
    const double cosGammaI = std::cos(gammaI);
    const double sinGammaT = h * inverseEtaPrime;
    const double gammaT = std::asin(std::min(sinGammaT, 1.0));
    const double cosGammaT = safeSqrt(1.0 - sinGammaT * sinGammaT);
    const double f = fresnelDielectric(eta, cosThetaR * cosGammaI);
    const glm::dvec3 t = glm::exp(-sigma * (2.0 * cosGammaT / cosThetaT));
    const double g = 1.0 - f;
    // ½ ∫_{−1}^{1} dh with the ±h pair folded: ∫_0^1 dh = ∫_0^{π/2} cos γi dγi; the ½ stays with D.
    PathNode node{.weight = step * cosGammaI * 0.5,
                  .aR = f,
                  .aTT = g * g * t,
                  .aTRT = g * g * f * t * t,
                  .phi = {-2.0 * gammaI, 2.0 * gammaT - 2.0 * gammaI + kPi, 4.0 * gammaT - 2.0 * gammaI + 2.0 * kPi}};
    visit(node);
  }
}

}  // namespace

glm::vec3 absorptionFromMelanin(float eumelanin, float pheomelanin) {
  return eumelanin * glm::vec3(0.419f, 0.697f, 1.37f) + pheomelanin * glm::vec3(0.187f, 0.4f, 1.05f);
}

HairShadingParams darkHairParams() {
  HairShadingParams params;
  params.absorption = absorptionFromMelanin(8.0f, 0.0f);
  return params;
}

HairShadingParams blondeHairParams() {
  HairShadingParams params;
  params.absorption = absorptionFromMelanin(0.3f, 0.1f);
  return params;
}

Result<void> validate(const HairShadingParams& params) {
  const auto finite = [](float x) { return std::isfinite(x); };
  for (int c = 0; c < 3; ++c)
    if (!finite(params.absorption[c]) || params.absorption[c] < 0.0f)
      return fail("hair shading: absorption[" + std::to_string(c) + "] = " + std::to_string(params.absorption[c]) +
                  "; expected a finite value ≥ 0 (1/fibre radius)");
  if (!finite(params.refractiveIndex) || params.refractiveIndex <= 1.0f || params.refractiveIndex > 3.0f)
    return fail("hair shading: refractive index " + std::to_string(params.refractiveIndex) + "; expected (1, 3]");
  const char* names[] = {"R", "TT", "TRT"};
  for (int p = 0; p < 3; ++p) {
    const HairLobeShape& lobe = params.lobe(HairLobe(p));
    if (!finite(lobe.width) || lobe.width <= 0.0f || lobe.width > 0.5f * float(kPi))
      return fail(std::string("hair shading: lobe ") + names[p] + " width " + std::to_string(lobe.width) +
                  " rad; expected (0, π/2]");
    if (!finite(lobe.shift) || std::abs(lobe.shift) > 0.25f * float(kPi))
      return fail(std::string("hair shading: lobe ") + names[p] + " shift " + std::to_string(lobe.shift) +
                  " rad; expected [−π/4, π/4]");
  }
  if (!finite(params.azimuthalWidth) || params.azimuthalWidth <= 0.0f || params.azimuthalWidth > 0.5f * float(kPi))
    return fail("hair shading: azimuthal width " + std::to_string(params.azimuthalWidth) + " rad; expected (0, π/2]");
  return {};
}

double fresnelDielectric(double eta, double cosIncidence) {
  cosIncidence = std::clamp(cosIncidence, -1.0, 1.0);
  if (cosIncidence < 0.0) {  // leaving the denser medium: the same formulas with 1/η
    eta = 1.0 / eta;
    cosIncidence = -cosIncidence;
  }
  const double sin2T = (1.0 - cosIncidence * cosIncidence) / (eta * eta);
  if (sin2T >= 1.0) return 1.0;
  const double cosT = std::sqrt(1.0 - sin2T);
  const double rs = (cosIncidence - eta * cosT) / (cosIncidence + eta * cosT);
  const double rp = (eta * cosIncidence - cosT) / (eta * cosIncidence + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

double bravaisPerpendicularIndex(double eta, double theta) {
  const double s = std::sin(theta);
  return std::sqrt(eta * eta - s * s) / std::cos(theta);
}

double bravaisParallelIndex(double eta, double theta) {
  const double s = std::sin(theta);
  return eta * eta * std::cos(theta) / std::sqrt(eta * eta - s * s);
}

double longitudinalLobe(double variance, double thetaI, double shiftedThetaR) {
  const double kappa = 1.0 / variance;
  const double a = kappa * std::cos(thetaI) * std::abs(std::cos(shiftedThetaR));
  const double b = kappa * std::sin(thetaI) * std::sin(shiftedThetaR);
  // κ/(2 sinh κ) in logs: log κ − κ − log(1 − e^−2κ), finite for the κ ~ 10⁴ of very smooth fibres.
  const double logNorm = std::log(kappa) - kappa - std::log1p(-std::exp(-2.0 * kappa));
  return std::exp(logNorm - b + logBesselI0(a));
}

LongitudinalLobes longitudinalScattering(const HairShadingParams& params, double thetaI, double thetaR) {
  const auto lobe = [&](const HairLobeShape& shape) {
    return longitudinalLobe(double(shape.width) * shape.width, thetaI, thetaR - 2.0 * double(shape.shift));
  };
  return {lobe(params.r), lobe(params.tt), lobe(params.trt)};
}

AzimuthalLobes azimuthalScattering(const HairShadingParams& params, double cosThetaR, double cosPhi) {
  const double phi = std::acos(std::clamp(cosPhi, -1.0, 1.0));
  const double sigma = params.azimuthalWidth;
  AzimuthalLobes n;
  forEachPathNode(params, cosThetaR, [&](const PathNode& node) {
    // The folded pair: +h exits at Φ_p, −h at −Φ_p (mod 2π).
    double d[3];
    for (int p = 0; p < 3; ++p)
      d[p] = node.weight * (wrappedGaussian(phi - node.phi[p], sigma) + wrappedGaussian(phi + node.phi[p], sigma));
    n.r += node.aR * d[0];
    n.tt += node.aTT * d[1];
    n.trt += node.aTRT * d[2];
  });
  return n;
}

AzimuthalLobes azimuthalAlbedo(const HairShadingParams& params, double cosThetaR) {
  AzimuthalLobes a;
  forEachPathNode(params, cosThetaR, [&](const PathNode& node) {
    // D integrates to 1 over φ for each of the two folded exits.
    a.r += 2.0 * node.weight * node.aR;
    a.tt += 2.0 * node.weight * node.aTT;
    a.trt += 2.0 * node.weight * node.aTRT;
  });
  return a;
}

HairAngles hairAngles(glm::dvec3 toLight, glm::dvec3 toEye, glm::dvec3 tangent) {
  HairAngles angles;
  const double sinI = std::clamp(glm::dot(toLight, tangent), -1.0, 1.0);
  const double sinR = std::clamp(glm::dot(toEye, tangent), -1.0, 1.0);
  angles.thetaI = std::asin(sinI);
  angles.thetaR = std::asin(sinR);
  angles.cosThetaR = std::sqrt(1.0 - sinR * sinR);
  const glm::dvec3 lightPerp = toLight - sinI * tangent;
  const glm::dvec3 eyePerp = toEye - sinR * tangent;
  const double norms = glm::dot(lightPerp, lightPerp) * glm::dot(eyePerp, eyePerp);
  angles.cosPhi = norms > 1e-24 ? std::clamp(glm::dot(lightPerp, eyePerp) / std::sqrt(norms), -1.0, 1.0) : 1.0;
  return angles;
}

glm::dvec3 hairScattering(const HairShadingParams& params, glm::dvec3 toLight, glm::dvec3 toEye, glm::dvec3 tangent) {
  const HairAngles angles = hairAngles(toLight, toEye, tangent);
  const LongitudinalLobes m = longitudinalScattering(params, angles.thetaI, angles.thetaR);
  const AzimuthalLobes n = azimuthalScattering(params, angles.cosThetaR, angles.cosPhi);
  return m.r * n.r + m.tt * n.tt + m.trt * n.trt;
}

}  // namespace mane::render
