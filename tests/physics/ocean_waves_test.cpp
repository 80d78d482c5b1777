// Gerstner waves from the wind, and the portable sine, cosine, exponential and logarithm.
//
// Oracles: the C library's sin, cos, exp and log (for the portable ones), one Gerstner
// wave's closed form (position, normal, Jacobian), the velocity as the time derivative of the
// position, the Pierson–Moskowitz spectrum's integral between the bands' edges, the cos²
// spreading's mean, and the surface's variance sampled in space against Σ A²/2.

#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/detail/portable_math.hpp"
#include "physics/ocean_waves.hpp"

namespace mane::physics {
namespace {

TEST(PortableMath, AgreesWithTheCLibraryToAFewUlps) {
  for (double x = -2000.0; x <= 2000.0; x += 0.37) {
    const detail::SineCosine sc = detail::sineCosine(x);
    EXPECT_NEAR(sc.sine, std::sin(x), 2e-15 * std::max(1.0, std::abs(x) / 100.0)) << x;
    EXPECT_NEAR(sc.cosine, std::cos(x), 2e-15 * std::max(1.0, std::abs(x) / 100.0)) << x;
  }
  for (double x = -700.0; x <= 700.0; x += 0.731) {
    EXPECT_NEAR(detail::exponential(x) / std::exp(x), 1.0, 1e-14) << x;
  }
  EXPECT_EQ(detail::exponential(-800.0), 0.0);
  for (double x = 1e-300; x < 1e300; x *= 7.3) {
    EXPECT_NEAR(detail::logarithm(x), std::log(x), 1e-15 * std::max(1.0, std::abs(std::log(x)))) << x;
  }
  EXPECT_TRUE(std::isnan(detail::logarithm(0.0)));
  EXPECT_TRUE(std::isnan(detail::logarithm(-1.0)));
}

TEST(OceanWaves, OneWaveIsGerstnersClosedForm) {
  const float angle = 0.5f;
  const GerstnerWave wave{.direction = {std::cos(angle), std::sin(angle)},
                          .wavenumber = 0.3f,
                          .angularFrequency = std::sqrt(kOceanGravity * 0.3f),
                          .amplitude = 1.5f,
                          .phase = 0.7f};
  const float lambda = 0.8f / (wave.wavenumber * wave.amplitude);
  const auto ocean = OceanWaves::fromWaves({wave}, lambda);
  ASSERT_TRUE(ocean) << ocean.error().message;
  const double d[2] = {wave.direction.x, wave.direction.y};
  for (double time : {0.0, 1.3, 17.9}) {
    for (float x = -20.0f; x <= 20.0f; x += 3.1f) {
      for (float z = -20.0f; z <= 20.0f; z += 4.3f) {
        const OceanSample s = ocean->sample({x, z}, time);
        const double theta = wave.wavenumber * (d[0] * x + d[1] * z) + wave.phase - wave.angularFrequency * time;
        const double a = wave.amplitude;
        const double k = wave.wavenumber;
        EXPECT_NEAR(s.position.x, x - lambda * d[0] * a * std::sin(theta), 2e-5);
        EXPECT_NEAR(s.position.z, z - lambda * d[1] * a * std::sin(theta), 2e-5);
        EXPECT_NEAR(s.position.y, a * std::cos(theta), 2e-5);
        EXPECT_NEAR(s.jacobian, 1.0 - lambda * k * a * std::cos(theta), 2e-5);
        // Along the travel the profile is (s − λA sin θ, A cos θ): its normal leans by
        // (k A sin θ, 1 − λ k A cos θ), normalised.
        const double along = k * a * std::sin(theta);
        const double up = 1.0 - lambda * k * a * std::cos(theta);
        const double length = std::hypot(along, up);
        EXPECT_NEAR(s.normal.x, d[0] * along / length, 2e-5);
        EXPECT_NEAR(s.normal.z, d[1] * along / length, 2e-5);
        EXPECT_NEAR(s.normal.y, up / length, 2e-5);
      }
    }
  }
}

TEST(OceanWaves, VelocityIsThePositionsTimeDerivative) {
  const auto ocean = OceanWaves::create({.windSpeed = 12.0f, .choppiness = 0.9f});
  ASSERT_TRUE(ocean) << ocean.error().message;
  const double h = 1e-3;
  for (float x = -40.0f; x <= 40.0f; x += 13.0f) {
    const glm::vec2 rest(x, 0.37f * x + 5.0f);
    const OceanSample s = ocean->sample(rest, 10.0);
    const glm::vec3 ahead = ocean->sample(rest, 10.0 + h).position;
    const glm::vec3 behind = ocean->sample(rest, 10.0 - h).position;
    const glm::vec3 derivative = (ahead - behind) / static_cast<float>(2.0 * h);
    for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(s.velocity[axis], derivative[axis], 2e-2) << axis;
  }
}

// ∫ S dω over [a, b] of Pierson and Moskowitz's spectrum, in closed form with the C library.
double spectrumEnergy(double windSpeed, double a, double b) {
  const double g = kOceanGravity;
  const double alpha = 8.1e-3;
  const double beta = 0.74;
  const double omega0 = g / windSpeed;
  const double m0 = alpha * g * g / (4.0 * beta * std::pow(omega0, 4.0));
  return m0 * (std::exp(-beta * std::pow(omega0 / b, 4.0)) - std::exp(-beta * std::pow(omega0 / a, 4.0)));
}

TEST(OceanWaves, TheWavesHoldThePiersonMoskowitzSeasEnergy) {
  for (float wind : {5.0f, 10.0f, 20.0f}) {
    const OceanSettings settings{.windSpeed = wind, .shortestWavelength = 0.5f};
    const auto ocean = OceanWaves::create(settings);
    ASSERT_TRUE(ocean) << ocean.error().message;
    ASSERT_EQ(ocean->waves().size(), 45u);
    double variance = 0.0;
    double lowest = 1e9;
    double highest = 0.0;
    for (const GerstnerWave& w : ocean->waves()) {
      variance += 0.5 * static_cast<double>(w.amplitude) * w.amplitude;
      lowest = std::min(lowest, static_cast<double>(w.angularFrequency));
      highest = std::max(highest, static_cast<double>(w.angularFrequency));
      EXPECT_NEAR(w.wavenumber, w.angularFrequency * w.angularFrequency / kOceanGravity, 1e-5 * w.wavenumber);
    }
    // The band edges: half the peak frequency, and the shortest wavelength's.
    const double peak = kOceanGravity / wind * std::pow(0.8 * 0.74, 0.25);
    const double top = std::sqrt(kOceanGravity * 2.0 * std::numbers::pi / 0.5);
    EXPECT_GE(lowest, 0.5 * peak);
    EXPECT_LE(highest, top * (1.0 + 1e-6));
    const double expected = spectrumEnergy(wind, 0.5 * peak, top);
    EXPECT_NEAR(variance / expected, 1.0, 1e-5) << wind;
    // Nearly all the sea's energy lies in the bands: 4√(Σ A²/2) is the significant height.
    const double hs = piersonMoskowitzSignificantHeight(wind);
    EXPECT_NEAR(hs, 0.2092 * wind * wind / kOceanGravity, 1e-3 * hs);
    EXPECT_NEAR(4.0 * std::sqrt(variance) / hs, 1.0, 0.01) << wind;
  }
}

TEST(OceanWaves, TheSampledSurfaceHasTheWavesVariance) {
  const auto ocean = OceanWaves::create({.windSpeed = 8.0f, .choppiness = 0.0f, .seed = 7});
  ASSERT_TRUE(ocean) << ocean.error().message;
  double expected = 0.0;
  for (const GerstnerWave& w : ocean->waves()) expected += 0.5 * static_cast<double>(w.amplitude) * w.amplitude;
  // Heights over 4 km × 4 km, far more than the longest wave: uncorrelated phases average out.
  double sum = 0.0;
  double sumSquares = 0.0;
  int count = 0;
  for (float x = -2000.0f; x < 2000.0f; x += 23.7f) {
    for (float z = -2000.0f; z < 2000.0f; z += 29.3f) {
      const double y = ocean->sample({x, z}, 3.0).position.y;
      sum += y;
      sumSquares += y * y;
      ++count;
    }
  }
  const double mean = sum / count;
  EXPECT_NEAR(mean, 0.0, 0.05 * std::sqrt(expected));
  EXPECT_NEAR((sumSquares / count - mean * mean) / expected, 1.0, 0.05);
}

TEST(OceanWaves, DirectionsSpreadAboutTheWindAsCosineSquared) {
  const glm::vec2 wind = glm::normalize(glm::vec2(-1.0f, 2.0f));
  double meanCos = 0.0;
  int count = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const auto ocean = OceanWaves::create({.windDirection = {-1.0f, 2.0f}, .seed = seed});
    ASSERT_TRUE(ocean) << ocean.error().message;
    for (const GerstnerWave& w : ocean->waves()) {
      const double c = w.direction.x * wind.x + w.direction.y * wind.y;
      EXPECT_GE(c, -1e-6);
      EXPECT_NEAR(std::hypot(w.direction.x, w.direction.y), 1.0, 1e-6);
      meanCos += c;
      ++count;
    }
  }
  // E[cos θ] under (2/π) cos²θ on [−π/2, π/2] is 8/(3π) = 0.8488; 1,800 draws of σ ≈ 0.16.
  EXPECT_NEAR(meanCos / count, 8.0 / (3.0 * std::numbers::pi), 0.012);
}

TEST(OceanWaves, TheSameSeedGrowsTheSameSeaBitForBit) {
  const auto a = OceanWaves::create({.seed = 5});
  const auto b = OceanWaves::create({.seed = 5});
  const auto c = OceanWaves::create({.seed = 6});
  ASSERT_TRUE(a && b && c);
  ASSERT_EQ(a->waves().size(), b->waves().size());
  for (std::size_t i = 0; i < a->waves().size(); ++i) {
    EXPECT_EQ(a->waves()[i].amplitude, b->waves()[i].amplitude);
    EXPECT_EQ(a->waves()[i].phase, b->waves()[i].phase);
    EXPECT_EQ(a->waves()[i].direction, b->waves()[i].direction);
  }
  EXPECT_NE(a->waves()[0].phase, c->waves()[0].phase);
  EXPECT_EQ(a->sample({3.0f, 4.0f}, 100.25).position, b->sample({3.0f, 4.0f}, 100.25).position);
}

TEST(OceanWaves, TheChoppinessSpreadsTheJacobianByAThird) {
  for (float choppiness : {0.3f, 1.0f}) {
    const auto ocean = OceanWaves::create({.windSpeed = 9.0f, .choppiness = choppiness, .seed = 3});
    ASSERT_TRUE(ocean);
    double sum = 0.0;
    double sumSquares = 0.0;
    int count = 0;
    int folded = 0;
    for (float x = -1500.0f; x < 1500.0f; x += 13.7f) {
      for (float z = -1500.0f; z < 1500.0f; z += 17.3f) {
        const double j = ocean->sample({x, z}, 5.0).jacobian;
        sum += j;
        sumSquares += j * j;
        folded += j < 0.0;
        ++count;
      }
    }
    const double mean = sum / count;
    const double spread = std::sqrt(sumSquares / count - mean * mean);
    // To first order J − 1 is a sum of 45 independent cosines: its deviation is c/3 (the
    // Jacobian's second-order terms add a little).
    EXPECT_NEAR(spread / (choppiness / 3.0), 1.0, 0.08) << choppiness;
    EXPECT_NEAR(mean, 1.0, 0.02) << choppiness;
    // Folds three deviations out: about 0.13 % of a Gaussian sea at choppiness 1, none at 0.3.
    if (choppiness == 1.0f) {
      EXPECT_GT(folded, 0);
      EXPECT_LT(double(folded) / count, 0.01);
    } else {
      EXPECT_EQ(folded, 0);
    }
  }
}

TEST(OceanWaves, PhasesForTheGpuLieInOneTurn) {
  const auto ocean = OceanWaves::create({});
  ASSERT_TRUE(ocean);
  std::vector<float> phases(ocean->waves().size());
  for (double time : {0.0, 0.5, 1e3, 3.6e4}) {
    ocean->phasesAt(time, phases);
    for (float p : phases) {
      EXPECT_GE(p, 0.0f);
      EXPECT_LE(p, static_cast<float>(2.0 * std::numbers::pi));
    }
  }
}

TEST(OceanWaves, SurfaceAtFindsTheWaterOverAPoint) {
  for (float choppiness : {0.0f, 0.5f, 1.0f}) {
    const auto ocean = OceanWaves::create({.windSpeed = 15.0f, .choppiness = choppiness});
    ASSERT_TRUE(ocean);
    float worst = 0.0f;
    int points = 0;
    int nearFolds = 0;
    for (float x = -100.0f; x <= 100.0f; x += 2.3f) {
      for (float z = -100.0f; z <= 100.0f; z += 2.9f) {
        const OceanSample s = ocean->surfaceAt({x, z}, 42.0);
        ++points;
        // Where the surface is about to fold, several waters may lie over a point, or none near.
        if (s.jacobian < 0.2f) {
          ++nearFolds;
          continue;
        }
        worst = std::max(worst, std::hypot(s.position.x - x, s.position.z - z));
        // It says where that water rests: sampled there, it is the same water.
        const OceanSample again = ocean->sample(s.rest, 42.0);
        ASSERT_EQ(again.position, s.position);
      }
    }
    // Within a tenth of a millimetre: far closer than the hull cells that ask (decimetres).
    EXPECT_LT(worst, 1e-4f) << choppiness;
    EXPECT_LT(double(nearFolds) / points, 0.01) << choppiness;
  }
}

TEST(OceanWaves, RefusesSettingsOutOfRangeByName) {
  const auto refused = [](OceanSettings s, const char* field) {
    const auto ocean = OceanWaves::create(s);
    ASSERT_FALSE(ocean) << field;
    EXPECT_NE(ocean.error().message.find(field), std::string::npos) << ocean.error().message;
  };
  refused({.windSpeed = 0.0f}, "windSpeed");
  refused({.windSpeed = NAN}, "windSpeed");
  refused({.windDirection = {0.0f, 0.0f}}, "windDirection");
  refused({.choppiness = 1.5f}, "choppiness");
  refused({.waveCount = 0}, "waveCount");
  refused({.waveCount = kMaxOceanWaves + 1}, "waveCount");
  refused({.windSpeed = 2.0f, .shortestWavelength = 50.0f}, "shortestWavelength");
  EXPECT_FALSE(OceanWaves::fromWaves({GerstnerWave{.direction = {2.0f, 0.0f}}}, 0.0f));
  EXPECT_FALSE(OceanWaves::fromWaves({GerstnerWave{.wavenumber = -1.0f}}, 0.0f));
  EXPECT_FALSE(OceanWaves::fromWaves(std::vector<GerstnerWave>(kMaxOceanWaves + 1), 0.0f));
  EXPECT_TRUE(OceanWaves::fromWaves({}, 0.0f));
}

}  // namespace
}  // namespace mane::physics
