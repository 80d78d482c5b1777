#include "physics/ocean_waves.hpp"

#include <cmath>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "physics/detail/portable_math.hpp"
#include "physics/split_mix64.hpp"

namespace mane::physics {

namespace {

constexpr double kTwoPi = 6.28318530717958647693;
constexpr double kPi = 3.14159265358979323846;
// Pierson and Moskowitz's constants (1964).
constexpr double kPiersonMoskowitzAlpha = 8.1e-3;
constexpr double kPiersonMoskowitzBeta = 0.74;
// The lowest frequency sampled, as a share of the peak's: the spectrum below it holds under 1 %
// of the energy (exp(−β 2⁴ / (4β/5)) = e⁻²⁰).
constexpr double kLowestFrequencyOverPeak = 0.5;

// The peak frequency of the Pierson–Moskowitz spectrum: dS/dω = 0 at ω⁴ = (4β/5) ω₀⁴.
double peakFrequency(double windSpeed) {
  const double omega0 = kOceanGravity / windSpeed;
  return omega0 * std::sqrt(std::sqrt(0.8 * kPiersonMoskowitzBeta));
}

// ∫ S(ω) dω from 0 to `omega`, in m²: m₀ exp(−β (ω₀/ω)⁴).
double energyBelow(double omega, double windSpeed) {
  const double omega0 = kOceanGravity / windSpeed;
  const double ratio = omega0 / omega;
  const double m0 = kPiersonMoskowitzAlpha * windSpeed * windSpeed * windSpeed * windSpeed /
                    (4.0 * kPiersonMoskowitzBeta * kOceanGravity * kOceanGravity);
  return m0 * detail::exponential(-kPiersonMoskowitzBeta * ratio * ratio * ratio * ratio);
}

// An angle from the wind in [−π/2, π/2], distributed as (2/π) cos²θ (by rejection).
double spreadAngle(SplitMix64& random) {
  for (;;) {
    const double angle = (static_cast<double>(random.nextFloat()) - 0.5) * kPi;
    const double accept = random.nextFloat();
    const double c = detail::sineCosine(angle).cosine;
    if (accept < c * c) return angle;
  }
}

double phaseAt(const GerstnerWave& wave, double time) {
  const double phase = static_cast<double>(wave.phase) - static_cast<double>(wave.angularFrequency) * time;
  return phase - kTwoPi * std::floor(phase / kTwoPi);
}

bool finite(float v) {
  return std::isfinite(v);
}

}  // namespace

Result<void> validateOcean(const OceanSettings& settings) {
  const auto bad = [](const char* field, const std::string& expected) {
    return fail(std::string("Ocean settings: ") + field + " must be " + expected + ".");
  };
  if (!(finite(settings.windSpeed) && settings.windSpeed > 0.0f)) return bad("windSpeed", "positive (m/s)");
  const glm::vec2 d = settings.windDirection;
  if (!(finite(d.x) && finite(d.y) && d.x * d.x + d.y * d.y > 1e-12f))
    return bad("windDirection", "a finite, non-zero (x, z) direction");
  if (!(settings.choppiness >= 0.0f && settings.choppiness <= 1.0f)) return bad("choppiness", "in [0, 1]");
  if (settings.waveCount < 1 || settings.waveCount > kMaxOceanWaves)
    return bad("waveCount", "between 1 and " + std::to_string(kMaxOceanWaves));
  const double peakWavelength =
      kTwoPi * kOceanGravity / (peakFrequency(settings.windSpeed) * peakFrequency(settings.windSpeed));
  if (!(finite(settings.shortestWavelength) && settings.shortestWavelength > 0.0f &&
        settings.shortestWavelength < peakWavelength))
    return bad("shortestWavelength", "positive and below the peak wavelength of a " +
                                         std::to_string(settings.windSpeed) + " m/s wind (" +
                                         std::to_string(peakWavelength) + " m)");
  return {};
}

double piersonMoskowitzSignificantHeight(double windSpeed) {
  const double m0 = kPiersonMoskowitzAlpha * windSpeed * windSpeed * windSpeed * windSpeed /
                    (4.0 * kPiersonMoskowitzBeta * kOceanGravity * kOceanGravity);
  return 4.0 * std::sqrt(m0);
}

Result<OceanWaves> OceanWaves::create(const OceanSettings& settings) {
  if (auto valid = validateOcean(settings); !valid) return std::unexpected(valid.error());
  const double wind = settings.windSpeed;
  const double lowest = kLowestFrequencyOverPeak * peakFrequency(wind);
  const double highest = std::sqrt(kOceanGravity * kTwoPi / settings.shortestWavelength);
  const double windLength = std::sqrt(static_cast<double>(settings.windDirection.x) * settings.windDirection.x +
                                      static_cast<double>(settings.windDirection.y) * settings.windDirection.y);
  const double windX = settings.windDirection.x / windLength;
  const double windZ = settings.windDirection.y / windLength;

  SplitMix64 random(settings.seed);
  std::vector<GerstnerWave> waves;
  waves.reserve(static_cast<std::size_t>(settings.waveCount));
  // Band edges evenly spaced in ln ω.
  const double logRange = detail::logarithm(highest / lowest);
  double steepnessSquares = 0.0;
  double edge = lowest;
  for (int i = 0; i < settings.waveCount; ++i) {
    const double next = lowest * detail::exponential(logRange * (i + 1) / settings.waveCount);
    const double energy = energyBelow(next, wind) - energyBelow(edge, wind);
    // Each wave takes its band's energy at a random frequency within it, so that no two seas
    // share a period and the sum never repeats.
    const double omega = edge + (next - edge) * random.nextFloat();
    const double angle = spreadAngle(random);
    const double phase = kTwoPi * random.nextFloat();
    const detail::SineCosine turn = detail::sineCosine(angle);
    GerstnerWave wave;
    wave.direction = {static_cast<float>(windX * turn.cosine - windZ * turn.sine),
                      static_cast<float>(windX * turn.sine + windZ * turn.cosine)};
    wave.angularFrequency = static_cast<float>(omega);
    wave.wavenumber = static_cast<float>(omega * omega / kOceanGravity);
    wave.amplitude = static_cast<float>(std::sqrt(2.0 * energy));
    wave.phase = static_cast<float>(phase);
    const double steepness = static_cast<double>(wave.wavenumber) * wave.amplitude;
    steepnessSquares += steepness * steepness;
    waves.push_back(wave);
    edge = next;
  }
  // J − 1 ≈ −λ Σ kᵢAᵢ cos θᵢ, whose spread over a sea of independent phases is λ√(Σ (kᵢAᵢ)²/2):
  // at choppiness c it is c/3, and the surface folds (J < 0) where it reaches 3/c of it.
  const double spread = std::sqrt(0.5 * steepnessSquares);
  const float choppiness = spread > 0.0 ? static_cast<float>(settings.choppiness / (3.0 * spread)) : 0.0f;
  return OceanWaves(std::move(waves), choppiness);
}

Result<OceanWaves> OceanWaves::fromWaves(std::vector<GerstnerWave> waves, float choppiness) {
  if (waves.size() > static_cast<std::size_t>(kMaxOceanWaves))
    return fail("Ocean: " + std::to_string(waves.size()) + " waves, more than the " + std::to_string(kMaxOceanWaves) +
                " the GPU holds.");
  if (!(finite(choppiness) && choppiness >= 0.0f)) return fail("Ocean: the choppiness must be finite and ≥ 0.");
  for (std::size_t i = 0; i < waves.size(); ++i) {
    const GerstnerWave& w = waves[i];
    const float length2 = w.direction.x * w.direction.x + w.direction.y * w.direction.y;
    const auto bad = [&](const char* what) { return fail("Ocean: wave " + std::to_string(i) + " has " + what + "."); };
    if (!(finite(length2) && std::abs(length2 - 1.0f) < 1e-4f)) return bad("a direction that is not unit");
    if (!(finite(w.wavenumber) && w.wavenumber > 0.0f)) return bad("a wavenumber that is not positive");
    if (!(finite(w.angularFrequency) && w.angularFrequency > 0.0f)) return bad("a frequency that is not positive");
    if (!(finite(w.amplitude) && w.amplitude >= 0.0f)) return bad("a negative or non-finite amplitude");
    if (!finite(w.phase)) return bad("a phase that is not finite");
  }
  return OceanWaves(std::move(waves), choppiness);
}

OceanWaves::OceanWaves(std::vector<GerstnerWave> waves, float choppiness)
    : waves_(std::move(waves)), choppiness_(choppiness) {}

void OceanWaves::phasesAt(double time, std::span<float> out) const {
  for (std::size_t i = 0; i < waves_.size() && i < out.size(); ++i)
    out[i] = static_cast<float>(phaseAt(waves_[i], time));
}

OceanSample OceanWaves::sample(glm::vec2 rest, double time) const {
  return evaluate(rest, time, nullptr);
}

OceanSample OceanWaves::evaluate(glm::vec2 rest, double time, glm::dmat2* horizontalMap) const {
  const double lambda = choppiness_;
  double x = rest.x;
  double y = 0.0;
  double z = rest.y;
  double slopeX = 0.0;  // ∂y/∂x₀
  double slopeZ = 0.0;  // ∂y/∂z₀
  double pullXX = 0.0;  // the horizontal map's Jacobian is I − pull
  double pullZZ = 0.0;
  double pullXZ = 0.0;
  glm::dvec3 velocity{0.0};
  for (const GerstnerWave& wave : waves_) {
    const double dx = wave.direction.x;
    const double dz = wave.direction.y;
    const double k = wave.wavenumber;
    const double a = wave.amplitude;
    const double omega = wave.angularFrequency;
    // The phase rounded to float, as the GPU receives it.
    const double phase = static_cast<float>(phaseAt(wave, time));
    const detail::SineCosine sc = detail::sineCosine(k * (dx * rest.x + dz * rest.y) + phase);
    const double horizontal = lambda * a * sc.sine;
    x -= dx * horizontal;
    z -= dz * horizontal;
    y += a * sc.cosine;
    slopeX -= k * a * dx * sc.sine;
    slopeZ -= k * a * dz * sc.sine;
    const double pull = lambda * k * a * sc.cosine;
    pullXX += pull * dx * dx;
    pullZZ += pull * dz * dz;
    pullXZ += pull * dx * dz;
    const double speed = a * omega;
    velocity.x += lambda * speed * dx * sc.cosine;
    velocity.z += lambda * speed * dz * sc.cosine;
    velocity.y += speed * sc.sine;
  }
  // n ∝ ∂p/∂z₀ × ∂p/∂x₀, the surface's two tangents.
  const glm::dvec3 alongX{1.0 - pullXX, slopeX, -pullXZ};
  const glm::dvec3 alongZ{-pullXZ, slopeZ, 1.0 - pullZZ};
  const glm::dvec3 n{alongZ.y * alongX.z - alongZ.z * alongX.y, alongZ.z * alongX.x - alongZ.x * alongX.z,
                     alongZ.x * alongX.y - alongZ.y * alongX.x};
  const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  OceanSample result;
  result.rest = rest;
  result.position = glm::vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  result.normal = glm::vec3(n / length);
  result.velocity = glm::vec3(velocity);
  result.jacobian = static_cast<float>((1.0 - pullXX) * (1.0 - pullZZ) - pullXZ * pullXZ);
  if (horizontalMap) *horizontalMap = glm::dmat2(1.0 - pullXX, -pullXZ, -pullXZ, 1.0 - pullZZ);
  return result;
}

OceanSample OceanWaves::surfaceAt(glm::vec2 position, double time) const {
  // Newton's method on x₀ ↦ horizontal(x₀) = position, the horizontal map's Jacobian matrix
  // being I − pull; where that matrix is nearly singular (a crest close to folding), the plain
  // fixed point's step, position − horizontal(x₀). A step that does not bring the water closer is
  // halved, up to four times.
  const glm::dvec2 target = position;
  glm::dvec2 rest = target;
  glm::dmat2 map(1.0);
  OceanSample s = evaluate(glm::vec2(rest), time, &map);
  const auto missOf = [&](const OceanSample& sample) {
    return target - glm::dvec2(sample.position.x, sample.position.z);
  };
  glm::dvec2 miss = missOf(s);
  // Done once the water lies within a tenth of a millimetre, far closer than the decimetre cells
  // that ask: most points take two or three steps. A micrometre took half as many again, and is
  // finer than float positions hold a hundred metres out.
  for (int step = 0; step < kSurfaceSteps && glm::dot(miss, miss) > 1e-8; ++step) {
    const double determinant = map[0][0] * map[1][1] - map[0][1] * map[1][0];
    glm::dvec2 move = miss;
    if (determinant > 0.1)
      move =
          glm::dvec2(map[1][1] * miss.x - map[1][0] * miss.y, -map[0][1] * miss.x + map[0][0] * miss.y) / determinant;
    const double before = glm::dot(miss, miss);
    for (int halving = 0; halving <= 4; ++halving) {
      glm::dmat2 nextMap(1.0);
      const OceanSample next = evaluate(glm::vec2(rest + move), time, &nextMap);
      const glm::dvec2 nextMiss = missOf(next);
      if (glm::dot(nextMiss, nextMiss) < before || halving == 4) {
        rest += move;
        s = next;
        map = nextMap;
        miss = nextMiss;
        break;
      }
      move *= 0.5;
    }
  }
  return s;
}

}  // namespace mane::physics
