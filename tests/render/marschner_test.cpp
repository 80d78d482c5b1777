// Marschner hair shading (render/luts/marschner.hpp) and its GPU lookup tables
// (render/luts/marschner_lut.hpp). The references are independent of the code under test:
//  - closed forms: Fresnel at normal incidence and at Brewster's angle, Bravais' indices against
//    a 3D refraction projected on the normal plane and against the 3D parallel reflectance, the
//    longitudinal lobe's normalisation ∫ M cosθ dθ = 1 (d'Eon et al. 2011 eq. 7);
//  - a white furnace (d'Eon et al. 2011 eq. 5, pbrt-v3's hair tests): the directional albedo
//    ∫ S dωi integrated by brute-force quadrature over the sphere must not exceed 1, and must
//    fall as the fibre absorbs more;
//  - absorption physics: dark and blonde fibres differ only in σa, so their TT and TRT ratios
//    are bounded by exp(chord · Δσa) with the chord bounds of a circle;
//  - GPU against CPU: the baked tables, read back and filtered bilinearly as a sampler does at
//    mip 0, against the CPU model at 10,000 random direction pairs.

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/luts/gauss_legendre.hpp"
#include "render/luts/marschner.hpp"
#include "render/luts/marschner_lut.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEta = 1.55;
const glm::dvec3 kTangent(0.0, 0.0, 1.0);

double degrees(double d) {
  return d * kPi / 180.0;
}
float degreesF(double d) {
  return static_cast<float>(degrees(d));
}

// A unit vector at longitudinal angle θ (from the plane normal to kTangent) and azimuth φ.
glm::dvec3 direction(double theta, double phi) {
  return {std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), std::sin(theta)};
}

struct Quadrature {
  std::vector<double> nodes, weights;
};

// Composite 8-point Gauss-Legendre over θ ∈ [−π/2, π/2] in `panels` panels.
Quadrature thetaRule(int panels) {
  const std::vector<QuadratureNode> base = gaussLegendre(8);
  Quadrature q;
  const double width = kPi / panels;
  for (int k = 0; k < panels; ++k)
    for (const QuadratureNode& node : base) {
      q.nodes.push_back(-0.5 * kPi + width * (k + 0.5 + 0.5 * node.position));
      q.weights.push_back(0.5 * width * node.weight);
    }
  return q;
}

// The white furnace: ∫ S(ωi, ωr) dωi over the sphere, dω = cosθ dθ dφ, for the eye at longitudinal
// angle θr. θ by composite Gauss-Legendre; φ by the midpoint rule, which for a smooth periodic
// integrand converges geometrically (the Gaussian detector of width β_N aliases by
// ~exp(−(n β_N)²/2) with n nodes).
glm::dvec3 directionalAlbedo(const HairShadingParams& params, double thetaR, int thetaPanels, int phiNodes) {
  const Quadrature theta = thetaRule(thetaPanels);
  const glm::dvec3 toEye = direction(thetaR, 0.0);
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < theta.nodes.size(); ++i)
    for (int j = 0; j < phiNodes; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / phiNodes;
      const double weight = theta.weights[i] * std::cos(theta.nodes[i]) * 2.0 * kPi / phiNodes;
      sum += weight * hairScattering(params, direction(theta.nodes[i], phi), toEye, kTangent);
    }
  return sum;
}

// Textbook Fresnel amplitudes for light from air onto index η at incidence cos θ.
double reflectancePerpendicular(double eta, double cosTheta) {
  const double cosT = std::sqrt(1.0 - (1.0 - cosTheta * cosTheta) / (eta * eta));
  const double r = (cosTheta - eta * cosT) / (cosTheta + eta * cosT);
  return r * r;
}
double reflectanceParallel(double eta, double cosTheta) {
  const double cosT = std::sqrt(1.0 - (1.0 - cosTheta * cosTheta) / (eta * eta));
  const double r = (eta * cosTheta - cosT) / (eta * cosTheta + cosT);
  return r * r;
}

// ---------------------------------------------------------------------------------------------
// Closed forms

TEST(MarschnerModel, FresnelMatchesClosedForms) {
  // Normal incidence: ((η − 1)/(η + 1))² = 0.046520569... for keratin.
  const double normal = (kEta - 1.0) * (kEta - 1.0) / ((kEta + 1.0) * (kEta + 1.0));
  EXPECT_NEAR(fresnelDielectric(kEta, 1.0), normal, 1e-15);
  EXPECT_NEAR(normal, 0.0465205690119185, 1e-15);
  // Brewster's angle tan θB = η: the parallel part vanishes, R = ½((η² − 1)/(η² + 1))².
  const double cosBrewster = 1.0 / std::sqrt(1.0 + kEta * kEta);
  const double s = (kEta * kEta - 1.0) / (kEta * kEta + 1.0);
  EXPECT_NEAR(fresnelDielectric(kEta, cosBrewster), 0.5 * s * s, 1e-14);
  // Grazing incidence reflects everything; from inside, beyond the critical angle asin(1/η), too.
  EXPECT_NEAR(fresnelDielectric(kEta, 0.0), 1.0, 1e-15);
  EXPECT_EQ(fresnelDielectric(kEta, -std::cos(std::asin(1.0 / kEta) + 0.01)), 1.0);
}

TEST(MarschnerModel, BravaisIndicesMatchTheirDefinitions) {
  for (double thetaDegrees : {0.0, 10.0, 30.0, 50.0, 70.0, 85.0}) {
    const double theta = degrees(thetaDegrees);
    const double etaPrime = bravaisPerpendicularIndex(kEta, theta);
    const double etaSecond = bravaisParallelIndex(kEta, theta);
    // η'(θ): refract a 3D ray at a cylinder (vector Snell's law) and project both directions on
    // the normal plane; their angles to the projected normal obey sin γi = η' sin γt.
    for (double gammaDegrees : {10.0, 40.0, 70.0}) {
      const double gamma = degrees(gammaDegrees);
      const glm::dvec3 normal(1.0, 0.0, 0.0);  // surface normal, in the normal plane (x, y)
      const glm::dvec3 incoming = -glm::dvec3(std::cos(theta) * std::cos(gamma), std::cos(theta) * std::sin(gamma),
                                              std::sin(theta));  // travelling into the fibre
      const double cosI = -glm::dot(incoming, normal);
      const double k = 1.0 - (1.0 - cosI * cosI) / (kEta * kEta);
      const glm::dvec3 refracted = incoming / kEta + (cosI / kEta - std::sqrt(k)) * normal;
      const auto projectedSine = [&](glm::dvec3 d) {
        const glm::dvec2 p = glm::normalize(glm::dvec2(d.x, d.y));
        return std::abs(p.y);  // sine of the angle to the projected normal (x axis)
      };
      EXPECT_NEAR(projectedSine(incoming) / projectedSine(refracted), etaPrime, 1e-12)
          << "θ " << thetaDegrees << "° γ " << gammaDegrees << "°";
    }
    // η''(θ): at γ = 0 the 2D reflectance with η'' equals the 3D parallel reflectance at θ.
    const double twoD = (etaSecond - 1.0) * (etaSecond - 1.0) / ((etaSecond + 1.0) * (etaSecond + 1.0));
    EXPECT_NEAR(twoD, reflectanceParallel(kEta, std::cos(theta)), 1e-12) << "θ " << thetaDegrees << "°";
    // Likewise the perpendicular part of the 2D Fresnel with η' equals the 3D one at the true
    // incidence angle, cos ψ = cosθ cosγ, for every γ.
    for (double gammaDegrees : {0.0, 30.0, 60.0}) {
      const double cosGamma = std::cos(degrees(gammaDegrees));
      EXPECT_NEAR(reflectancePerpendicular(etaPrime, cosGamma),
                  reflectancePerpendicular(kEta, std::cos(theta) * cosGamma), 1e-12);
    }
    EXPECT_NEAR(etaPrime * etaSecond, kEta * kEta, 1e-12);  // η'η'' = η²
  }
  EXPECT_DOUBLE_EQ(bravaisPerpendicularIndex(kEta, 0.0), kEta);
  EXPECT_DOUBLE_EQ(bravaisParallelIndex(kEta, 0.0), kEta);
}

TEST(MarschnerModel, LongitudinalLobeIntegratesToOneOverTheta) {
  // ∫ M_p(θi, θr) cos θi dθi = 1 over [−π/2, π/2] for any θr and width (d'Eon et al. 2011 eq. 7 is
  // a normalised von Mises-Fisher lobe integrated over azimuth). 64×8 Gauss-Legendre nodes
  // resolve the narrowest lobe (β = 2°) with ≥ 3 panels per β.
  const Quadrature theta = thetaRule(64);
  for (double width : {degrees(2.0), degrees(3.75), degrees(7.5), degrees(15.0), 0.5, 1.2})
    for (double thetaR : {-1.55, -1.0, -0.3, 0.0, 0.4, 1.1, 1.5, 1.57})
      for (double shift : {0.0, degrees(-7.5), degrees(11.25)}) {
        double integral = 0.0;
        for (std::size_t i = 0; i < theta.nodes.size(); ++i)
          integral += theta.weights[i] * std::cos(theta.nodes[i]) *
                      longitudinalLobe(width * width, theta.nodes[i], thetaR - 2.0 * shift);
        EXPECT_NEAR(integral, 1.0, 1e-6) << "β " << width << " θr " << thetaR << " α " << shift;
      }
  // The specular cone, shifted by α: for θr = 0 a narrow lobe peaks at θi = 2α, i.e. θh = α.
  // (Wide lobes peak slightly off the cone: d'Eon et al. 2011's off-specular peak.)
  const double narrow = degrees(1.0);
  for (double shift : {degrees(-7.5), degrees(3.75), degrees(11.25)}) {
    const auto m = [&](double thetaI) { return longitudinalLobe(narrow * narrow, thetaI, -2.0 * shift); };
    EXPECT_GT(m(2.0 * shift), m(2.0 * shift - 0.002)) << "α " << shift;
    EXPECT_GT(m(2.0 * shift), m(2.0 * shift + 0.002)) << "α " << shift;
  }
}

// ---------------------------------------------------------------------------------------------
// Energy

TEST(MarschnerModel, WhiteFurnaceAlbedoIsAtMostOne) {
  // Zero absorption: the fibre can only redistribute light, so ∫ S dωi ≤ 1 + 1e-2 (R, TT and TRT
  // only, so it stays below 1 by what TRRT and higher orders would carry). Checked for the default
  // lobes and for rough ones. Quadrature: 24×8 Gauss-Legendre nodes in θ (panels of 0.13 rad, two
  // per β_TT) and 32 midpoint nodes in φ (alias term exp(−(32·β_N)²/2) ≈ 2e-7); the doubled grid
  // below bounds the quadrature error.
  HairShadingParams smooth = blondeHairParams();
  smooth.absorption = glm::vec3(0.0f);
  HairShadingParams rough = smooth;
  rough.r = {degreesF(-5.0), degreesF(20.0)};
  rough.tt = {degreesF(2.5), degreesF(10.0)};
  rough.trt = {degreesF(7.5), degreesF(40.0)};
  rough.azimuthalWidth = degreesF(25.0);

  const glm::dvec3 coarse = directionalAlbedo(smooth, degrees(40.0), 24, 32);
  const glm::dvec3 fine = directionalAlbedo(smooth, degrees(40.0), 48, 64);
  const double quadratureError = std::abs(coarse.x - fine.x);
  EXPECT_LT(quadratureError, 1e-5);

  double maxAlbedo = 0.0;
  for (const HairShadingParams& params : {smooth, rough})
    for (double thetaDegrees : {-89.0, -75.0, -50.0, -25.0, 0.0, 25.0, 50.0, 75.0, 89.0}) {
      const glm::dvec3 albedo = directionalAlbedo(params, degrees(thetaDegrees), 24, 32);
      // Grey: without absorption the channels are identical.
      EXPECT_DOUBLE_EQ(albedo.x, albedo.z);
      // The brute-force sphere integral agrees with the energy argument of marschner.hpp:
      // ∫ M_p cosθi dθi = 1 and ∫ D dφ = 1 leave Σ_p ½∫A_p dh.
      const AzimuthalLobes lobes = azimuthalAlbedo(params, std::cos(degrees(thetaDegrees)));
      EXPECT_NEAR(albedo.x, lobes.r + lobes.tt.x + lobes.trt.x, 1e-6) << "θr " << thetaDegrees << "°";
      EXPECT_LE(albedo.x, 1.0 + 1e-2) << "θr " << thetaDegrees << "°";
      // Sanity: a clear fibre returns most of the light (R + TT + TRT carry ≥ 80 % of it).
      EXPECT_GT(albedo.x, 0.8) << "θr " << thetaDegrees << "°";
      maxAlbedo = std::max(maxAlbedo, albedo.x);
    }
  std::printf("[ white furnace ] max albedo %.6f, quadrature error %.2e\n", maxAlbedo, quadratureError);
  ::testing::Test::RecordProperty("max_albedo", std::to_string(maxAlbedo));
}

TEST(MarschnerModel, AlbedoFallsAsAbsorptionGrows) {
  for (double thetaDegrees : {0.0, 60.0}) {
    glm::dvec3 previous(2.0);
    for (float eumelanin : {0.0f, 0.25f, 0.5f, 1.0f, 2.0f, 4.0f, 8.0f}) {
      HairShadingParams params = blondeHairParams();
      params.absorption = absorptionFromMelanin(eumelanin, 0.0f);
      const glm::dvec3 albedo = directionalAlbedo(params, degrees(thetaDegrees), 24, 32);
      for (int c = 0; c < 3; ++c) EXPECT_LT(albedo[c], previous[c]) << "eumelanin " << eumelanin << " channel " << c;
      // Red is absorbed least by melanin (d'Eon et al. 2011 §6.1 cross sections).
      if (eumelanin > 0.0f) {
        EXPECT_GT(albedo.r, albedo.b);
      }
      previous = albedo;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Dark against blonde

TEST(MarschnerModel, DarkHairShowsReflectionBlondeHairShowsTransmission) {
  const HairShadingParams dark = darkHairParams();
  const HairShadingParams blonde = blondeHairParams();
  const glm::dvec3 deltaSigma = glm::dvec3(dark.absorption) - glm::dvec3(blonde.absorption);
  // Eye in the normal plane (cos θr = 1): a path crosses the fibre along a chord 2cosγt with
  // sin γt = h/η, between 2·sqrt(1 − 1/η²) (h → 1) and 2 (h = 0).
  const double shortestChord = 2.0 * std::sqrt(1.0 - 1.0 / (kEta * kEta));

  // R is a surface reflection: the same for both.
  for (double phi : {0.0, 0.5, 1.5, 3.0})
    EXPECT_DOUBLE_EQ(azimuthalScattering(dark, 1.0, std::cos(phi)).r,
                     azimuthalScattering(blonde, 1.0, std::cos(phi)).r);

  // TT and TRT differ only by the transmittance: each path's ratio is exp(chord·Δσ) per crossing,
  // so the ratio of the sums over paths lies between the chord bounds, at every φ.
  for (double phi : {kPi, 0.8 * kPi, 0.3 * kPi, 0.05 * kPi}) {
    const AzimuthalLobes b = azimuthalScattering(blonde, 1.0, std::cos(phi));
    const AzimuthalLobes d = azimuthalScattering(dark, 1.0, std::cos(phi));
    for (int c = 0; c < 3; ++c) {
      const double tt = b.tt[c] / d.tt[c];
      EXPECT_GE(tt, std::exp(shortestChord * deltaSigma[c]) * (1 - 1e-9)) << "φ " << phi << " channel " << c;
      EXPECT_LE(tt, std::exp(2.0 * deltaSigma[c]) * (1 + 1e-9)) << "φ " << phi << " channel " << c;
      const double trt = b.trt[c] / d.trt[c];
      EXPECT_GE(trt, std::exp(2.0 * shortestChord * deltaSigma[c]) * (1 - 1e-9)) << "φ " << phi;
      EXPECT_LE(trt, std::exp(4.0 * deltaSigma[c]) * (1 + 1e-9)) << "φ " << phi;
    }
  }
  // Forward scattering (φ = π) of blonde hair: ≥ e^4.9 ≈ 140 times dark hair's in red.
  EXPECT_GT(azimuthalScattering(blonde, 1.0, -1.0).tt.r, 100.0 * azimuthalScattering(dark, 1.0, -1.0).tt.r);

  // Lobe energies (∫ N_p dφ). R reflects at least the normal-incidence Fresnel ((η−1)/(η+1))² and,
  // averaged over the fibre's width, less than 10 %.
  const AzimuthalLobes darkEnergy = azimuthalAlbedo(dark, 1.0);
  const AzimuthalLobes blondeEnergy = azimuthalAlbedo(blonde, 1.0);
  const double normalFresnel = (kEta - 1.0) * (kEta - 1.0) / ((kEta + 1.0) * (kEta + 1.0));
  EXPECT_GE(darkEnergy.r, normalFresnel);
  EXPECT_LT(darkEnergy.r, 0.1);
  for (int c = 0; c < 3; ++c) {
    // Dark: T ≤ exp(−σa·shortestChord) bounds TT (and T² TRT): R dominates, in red by ≥ 7×,
    // in green and blue by orders of magnitude.
    const double transmittance = std::exp(-double(dark.absorption[c]) * shortestChord);
    EXPECT_LE(darkEnergy.tt[c], transmittance);
    EXPECT_LE(darkEnergy.trt[c], transmittance * transmittance);
    EXPECT_LT(darkEnergy.tt[c] + darkEnergy.trt[c], (c == 0 ? 0.15 : 0.01) * darkEnergy.r) << "channel " << c;
    // Blonde: T ≥ exp(−2σa) and ½∫(1−f)² dh ≥ 1 − 2·½∫f dh = 1 − 2·(R energy), so TT carries at
    // least exp(−2σa)(1 − 2 R) — more than twice R in every channel.
    const double blondeTransmittance = std::exp(-2.0 * double(blonde.absorption[c]));
    EXPECT_GE(blondeEnergy.tt[c], blondeTransmittance * (1.0 - 2.0 * blondeEnergy.r));
    EXPECT_GT(blondeEnergy.tt[c], 2.0 * blondeEnergy.r) << "channel " << c;
    // ...and TRT at least T² f_normal (1 − 2R), orders of magnitude above dark hair's.
    EXPECT_GE(blondeEnergy.trt[c],
              blondeTransmittance * blondeTransmittance * normalFresnel * (1.0 - 2.0 * blondeEnergy.r));
    EXPECT_GT(blondeEnergy.trt[c], 100.0 * darkEnergy.trt[c]);
  }
}

TEST(MarschnerModel, ValidateNamesTheBadParameter) {
  HairShadingParams params;
  EXPECT_TRUE(validate(params).has_value());
  params.absorption.y = std::nanf("");
  ASSERT_FALSE(validate(params).has_value());
  EXPECT_NE(validate(params).error().message.find("absorption[1]"), std::string::npos);
  params = {};
  params.tt.width = 0.0f;
  ASSERT_FALSE(validate(params).has_value());
  EXPECT_NE(validate(params).error().message.find("TT width"), std::string::npos);
  params = {};
  params.refractiveIndex = 0.9f;
  EXPECT_FALSE(validate(params).has_value());
}

// ---------------------------------------------------------------------------------------------
// GPU tables against the CPU model

// Vulkan's linear filter at normalised coordinates `uv` on one layer of a width×height table
// (texel centres at (i + ½)/n, clamp to edge), in double precision.
glm::dvec4 bilinear(const std::vector<glm::vec4>& texels, std::uint32_t width, std::uint32_t height,
                    std::uint32_t layer, glm::dvec2 uv) {
  const double x = uv.x * width - 0.5, y = uv.y * height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  const auto at = [&](double i, double j) {
    const auto ci = static_cast<std::size_t>(std::clamp(i, 0.0, double(width - 1)));
    const auto cj = static_cast<std::size_t>(std::clamp(j, 0.0, double(height - 1)));
    return glm::dvec4(texels[(std::size_t(layer) * height + cj) * width + ci]);
  };
  return (1 - ax) * (1 - ay) * at(fx, fy) + ax * (1 - ay) * at(fx + 1, fy) + (1 - ax) * ay * at(fx, fy + 1) +
         ax * ay * at(fx + 1, fy + 1);
}

// The texture coordinates of shaders/hair_shading.glsl: parameter x ∈ [0, 1] → (0.5 + x(n − 1))/n.
glm::dvec2 lutCoordinates(glm::dvec2 x, vk::Extent2D extent) {
  const glm::dvec2 size(extent.width, extent.height);
  return (0.5 + x * (size - 1.0)) / size;
}

class MarschnerLutTest : public testing::VulkanTest {
protected:
  void compareWithCpu(const HairShadingParams& params, const char* name);
};

void MarschnerLutTest::compareWithCpu(const HairShadingParams& params, const char* name) {
  const auto start = std::chrono::steady_clock::now();
  auto lut = MarschnerLut::create(device(), params);
  const double bakeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(lut.has_value()) << lut.error().message;
  std::printf("[ %s ] bake %.1f ms wall (pipeline creation included); GPU:", name, bakeMs);
  for (const PassTiming& timing : lut->bakeTimings())
    std::printf(" %.*s %.1f ms", int(timing.pass.name().size()), timing.pass.name().data(), timing.milliseconds);
  std::printf("\n");

  const vk::Extent2D mExtent = lut->extent(MarschnerTable::kLongitudinal);
  const vk::Extent2D nExtent = lut->extent(MarschnerTable::kAzimuthal);
  const auto m = lut->readTexels(MarschnerTable::kLongitudinal, 0);
  const auto n = lut->readTexels(MarschnerTable::kAzimuthal, 0);
  ASSERT_TRUE(m.has_value()) << m.error().message;
  ASSERT_TRUE(n.has_value()) << n.error().message;

  // 10,000 pairs of directions uniform on the sphere (so sin θ is uniform: the poles are covered).
  constexpr int kSamples = 10000;
  constexpr int kChannels = 13;  // M_R, M_TT, M_TRT, N_R, N_TT rgb, N_TRT rgb, S rgb
  const char* channelNames[kChannels] = {"M_R",     "M_TT",    "M_TRT",   "N_R", "N_TT.r", "N_TT.g", "N_TT.b",
                                         "N_TRT.r", "N_TRT.g", "N_TRT.b", "S.r", "S.g",    "S.b"};
  std::mt19937_64 random(20240611);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto randomDirection = [&] {
    const double z = 2.0 * uniform(random) - 1.0, azimuth = 2.0 * kPi * uniform(random);
    const double r = std::sqrt(1.0 - z * z);
    return glm::dvec3(r * std::cos(azimuth), r * std::sin(azimuth), z);
  };
  std::vector<std::array<double, kChannels>> cpu(kSamples), gpu(kSamples);
  for (int k = 0; k < kSamples; ++k) {
    const glm::dvec3 toLight = randomDirection(), toEye = randomDirection();
    const HairAngles angles = hairAngles(toLight, toEye, kTangent);
    const LongitudinalLobes cm = longitudinalScattering(params, angles.thetaI, angles.thetaR);
    const AzimuthalLobes cn = azimuthalScattering(params, angles.cosThetaR, angles.cosPhi);
    const glm::dvec3 cs = hairScattering(params, toLight, toEye, kTangent);
    cpu[k] = {cm.r, cm.tt, cm.trt, cn.r, cn.tt.r, cn.tt.g, cn.tt.b, cn.trt.r, cn.trt.g, cn.trt.b, cs.r, cs.g, cs.b};

    const glm::dvec4 gm = bilinear(*m, mExtent.width, mExtent.height, 0,
                                   lutCoordinates(glm::dvec2(angles.thetaI, angles.thetaR) / kPi + 0.5, mExtent));
    const glm::dvec2 nuv = lutCoordinates(glm::dvec2(std::acos(angles.cosPhi) / kPi, angles.cosThetaR), nExtent);
    const glm::dvec4 gn0 = bilinear(*n, nExtent.width, nExtent.height, 0, nuv);
    const glm::dvec4 gn1 = bilinear(*n, nExtent.width, nExtent.height, 1, nuv);
    const glm::dvec3 gs = gm.r * gn0.a + gm.g * glm::dvec3(gn0) + gm.b * glm::dvec3(gn1);
    gpu[k] = {gm.r, gm.g, gm.b, gn0.a, gn0.r, gn0.g, gn0.b, gn1.r, gn1.g, gn1.b, gs.r, gs.g, gs.b};
  }

  // Per channel: relative error ≤ 1 % wherever the CPU value exceeds 1 % of that channel's
  // largest value over the samples (below that a channel's flanks are invisible next to its peak).
  double worstOverall = 0.0;
  for (int c = 0; c < kChannels; ++c) {
    double largest = 0.0;
    for (int k = 0; k < kSamples; ++k) largest = std::max(largest, cpu[k][c]);
    ASSERT_GT(largest, 0.0) << channelNames[c];
    double worst = 0.0;
    int tested = 0;
    for (int k = 0; k < kSamples; ++k) {
      if (cpu[k][c] <= 0.01 * largest) continue;
      ++tested;
      const double error = std::abs(gpu[k][c] / cpu[k][c] - 1.0);
      worst = std::max(worst, error);
      EXPECT_LE(error, 0.01) << name << " " << channelNames[c] << " sample " << k << ": table " << gpu[k][c]
                             << ", model " << cpu[k][c];
    }
    std::printf("[ %s ] %-8s max %.3e  samples %5d  worst relative error %.3f %%\n", name, channelNames[c], largest,
                tested, 100.0 * worst);
    worstOverall = std::max(worstOverall, worst);
  }
  ::testing::Test::RecordProperty("worst_relative_error", std::to_string(worstOverall));
  ::testing::Test::RecordProperty("bake_ms", std::to_string(bakeMs));
}

TEST_F(MarschnerLutTest, BlondeTablesMatchTheCpuModel) {
  compareWithCpu(blondeHairParams(), "blonde");
}

TEST_F(MarschnerLutTest, DarkTablesMatchTheCpuModel) {
  compareWithCpu(darkHairParams(), "dark");
}

TEST_F(MarschnerLutTest, MipChainsAreBoxFilteredDownToOneTexel) {
  auto lut = MarschnerLut::create(device(), blondeHairParams());
  ASSERT_TRUE(lut.has_value()) << lut.error().message;
  for (const MarschnerTable table : {MarschnerTable::kLongitudinal, MarschnerTable::kAzimuthal}) {
    const vk::Extent2D extent = lut->extent(table);
    const std::uint32_t levels = lut->mipLevels(table);
    const std::uint32_t layers = table == MarschnerTable::kAzimuthal ? 2 : 1;
    // A full chain: log2 of the longer side, plus one.
    EXPECT_EQ(levels, std::uint32_t(std::bit_width(std::max(extent.width, extent.height))));
    const auto level0 = lut->readTexels(table, 0);
    const auto level1 = lut->readTexels(table, 1);
    const auto last = lut->readTexels(table, levels - 1);
    ASSERT_TRUE(level0 && level1 && last);
    ASSERT_EQ(last->size(), layers);
    // Halving blits with a linear filter sample each 2×2 block at its centre: its mean. Half
    // floats (M) round to 2^-11 relative, with subnormal steps of 6e-8; floats (N) to 2^-24, and
    // a device may flush their subnormals (< 1.2e-38) to zero.
    const bool half = table == MarschnerTable::kLongitudinal;
    const double tolerance = half ? 2e-3 : 1e-5;
    const double floor = half ? 1e-7 : 1e-37;
    const std::uint32_t w = extent.width, h = extent.height;
    for (std::uint32_t layer = 0; layer < layers; ++layer) {
      for (std::uint32_t j = 0; j < h / 2; j += 7)
        for (std::uint32_t i = 0; i < w / 2; i += 5) {
          const auto at = [&](std::uint32_t x, std::uint32_t y) {
            return glm::dvec4((*level0)[(std::size_t(layer) * h + y) * w + x]);
          };
          const glm::dvec4 mean =
              0.25 * (at(2 * i, 2 * j) + at(2 * i + 1, 2 * j) + at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1));
          const glm::dvec4 got((*level1)[(std::size_t(layer) * (h / 2) + j) * (w / 2) + i]);
          for (int c = 0; c < 4; ++c)
            ASSERT_NEAR(got[c], mean[c], tolerance * std::abs(mean[c]) + floor) << "texel " << i << "," << j;
        }
      // The 1×1 level is the mean of everything (box filters compose), up to rounding per level.
      glm::dvec4 mean(0.0);
      for (std::size_t t = 0; t < std::size_t(w) * h; ++t)
        mean += glm::dvec4((*level0)[layer * std::size_t(w) * h + t]);
      mean /= double(w) * h;
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR((*last)[layer][c], mean[c], (half ? 1e-2 : 1e-4) * std::abs(mean[c]) + floor);
    }
  }
}

TEST_F(MarschnerLutTest, RejectsInvalidParameters) {
  HairShadingParams params = blondeHairParams();
  params.azimuthalWidth = -1.0f;
  const auto lut = MarschnerLut::create(device(), params);
  ASSERT_FALSE(lut.has_value());
  EXPECT_NE(lut.error().message.find("azimuthal width"), std::string::npos) << lut.error().message;
  // Valid for the model, but M ~ 1/β² would overflow the half-float table.
  params = blondeHairParams();
  params.tt.width = 0.002f;
  const auto narrow = MarschnerLut::create(device(), params);
  ASSERT_FALSE(narrow.has_value());
  EXPECT_NE(narrow.error().message.find("minimum"), std::string::npos) << narrow.error().message;
}

}  // namespace
}  // namespace mane::render
