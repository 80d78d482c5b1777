// The HDR post chain (render/passes/post_pass.hpp) and the output pass's tone maps, against the
// CPU references of render/passes/post_reference.hpp and the formulas of Reinhard et al. 2002:
//  - the glow's kernel is a normalised Gaussian; the GPU glow of an impulse and of a noise image
//    matches the CPU downsample + four blurs;
//  - the GPU log-average luminance equals the CPU's over the same tiny image (read back);
//  - end to end through the Renderer: Reinhard on known HDR values through the 8-bit sRGB output,
//    auto gain that brings a scene twice as bright to the same displayed luminance, adaptation
//    whose per-frame gain change stays under the bound that τ and Δt set, the passes' timers;
//  - god rays: the GPU polar round trip returns the image away from the light, the GPU's radial
//    blur (running sums) matches the CPU's direct sum, the blur of one bright texel spreads only
//    along its ray, outwards, and god rays that are off (or whose light is behind the camera or
//    off screen) leave the output bit-identical.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <span>

#include <glm/gtc/packing.hpp>
#include <glm/mat3x3.hpp>
#include <gtest/gtest.h>

#include "render/passes/light_disc_pass.hpp"
#include "render/passes/post_pass.hpp"
#include "render/passes/post_reference.hpp"
#include "render/renderer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

// ---------------------------------------------------------------------------------------------
// Helpers

float roundToHalf(float value) {
  return glm::unpackHalf1x16(glm::packHalf1x16(value));
}

// The image as the GPU holds it: every value rounded to half precision.
HdrImage roundedToHalf(HdrImage image) {
  for (glm::vec4& texel : image.texels)
    for (int c = 0; c < 4; ++c) texel[c] = roundToHalf(texel[c]);
  return image;
}

// An RGBA16F image with `image`'s texels, sampled (SHADER_READ_ONLY), as a frame's hdr() is.
Image uploadHdr(const Device& device, const HdrImage& image) {
  Image uploaded(device,
                 ImageSettings{.extent = {image.width, image.height},
                               .format = vk::Format::eR16G16B16A16Sfloat,
                               .usage = vk::ImageUsageFlagBits::eSampled | vk::ImageUsageFlagBits::eTransferDst});
  const Buffer staging(device, image.texels.size() * 8, vk::BufferUsageFlagBits::eTransferSrc,
                       vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  for (std::size_t i = 0; i < image.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const std::uint16_t half = glm::packHalf1x16(image.texels[i][c]);
      std::memcpy(staging.mapped().data() + 8 * i + 2 * c, &half, 2);
    }
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    transition(commands, uploaded, Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone, Access::eNone,
               Stage::eCopy, Access::eTransferWrite);
    commands.copyBufferToImage(*staging.buffer(), *uploaded.image(), Layout::eTransferDstOptimal,
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                                   .imageExtent = {image.width, image.height, 1}});
    transition(commands, uploaded, Layout::eTransferDstOptimal, Layout::eShaderReadOnlyOptimal, Stage::eCopy,
               Access::eTransferWrite, Stage::eComputeShader | Stage::eFragmentShader, Access::eShaderSampledRead);
  });
  return uploaded;
}

HdrImage blank(std::uint32_t width, std::uint32_t height) {
  return {width, height, std::vector<glm::vec4>(std::size_t(width) * height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f))};
}

// Values spread log-uniformly over [lowest, highest] per channel: an HDR scene's range.
HdrImage noise(std::uint32_t width, std::uint32_t height, float lowest, float highest, unsigned seed) {
  HdrImage image = blank(width, height);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> exponent(std::log(lowest), std::log(highest));
  for (glm::vec4& texel : image.texels)
    texel = glm::vec4(std::exp(exponent(random)), std::exp(exponent(random)), std::exp(exponent(random)), 1.0f);
  return roundedToHalf(image);
}

double srgbEncode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// The mean displayed luminance of an sRGB-encoded RGBA8 image (linear, 0..1).
double displayedLuminance(std::span<const std::uint8_t> rgba) {
  double sum = 0.0;
  for (std::size_t i = 0; i < rgba.size(); i += 4)
    sum += luminance(
        glm::dvec3(srgbDecode(rgba[i] / 255.0), srgbDecode(rgba[i + 1] / 255.0), srgbDecode(rgba[i + 2] / 255.0)));
  return sum / double(rgba.size() / 4);
}

// ---------------------------------------------------------------------------------------------
// The glow's kernel (CPU)

TEST(PostReference, GlowKernelIsANormalisedGaussian) {
  for (const float sigma : {0.8f, 1.5f, kGlowSigma}) {
    const std::vector<float> kernel = glowKernel(sigma);
    ASSERT_EQ(int(kernel.size()) - 1, std::min(kGlowMaxRadius, int(std::ceil(3.0f * sigma)))) << "σ " << sigma;
    double sum = kernel[0];
    for (std::size_t k = 1; k < kernel.size(); ++k) sum += 2.0 * kernel[k];
    // Float weights of a double sum: rounding leaves ~1e-7 per weight.
    EXPECT_NEAR(sum, 1.0, 1e-6) << "σ " << sigma;
    for (std::size_t k = 1; k < kernel.size(); ++k)
      EXPECT_NEAR(kernel[k] / kernel[0], std::exp(-0.5 * double(k * k) / (sigma * sigma)), 1e-6) << "k " << k;
  }
}

TEST(PostReference, AdaptationRateComposesOverFrames) {
  // 1 − exp(−Δt/τ): two frames of Δt move as far as one of 2Δt (exponential decay).
  const double one = adaptationRate(0.1, 0.5), two = adaptationRate(0.05, 0.5);
  EXPECT_NEAR(1.0 - one, (1.0 - two) * (1.0 - two), 1e-12);
  EXPECT_EQ(adaptationRate(0.1, 0.0), 1.0);
}

// ---------------------------------------------------------------------------------------------
// The chain's compute passes on uploaded HDR images

class PostChainTest : public testing::VulkanTest {
public:
  // Runs the passes `settings` asks for once on `frame`.
  void run(PostPass& chain, const PostSettings& settings, float exposure = 1.0f) {
    device().submitAndWait(
        [&](const vk::raii::CommandBuffer& commands) { chain.record(commands, settings, exposure); });
  }

  // God rays around `lightUv` on `frame` (threshold 1, decay 0.96): the GPU's, and the CPU
  // reference's from the same downsampled copy; `centre` is the light in copy texels.
  struct GodRays {
    HdrImage gpu, cpu;
    glm::vec2 centre{0.0f};
  };
  GodRays godRaysOf(const HdrImage& frame, glm::vec2 lightUv) {
    const Image uploaded = uploadHdr(device(), frame);
    PostPass chain(device(), uploaded);
    const PostSettings settings{.godRays = 1.0f, .godRayThreshold = 1.0f, .godRayDecay = 0.96f};
    run(chain, settings, 1.0f);
    device().submitAndWait(
        [&](const vk::raii::CommandBuffer& commands) { chain.record(commands, settings, 1.0f, lightUv); });
    EXPECT_TRUE(chain.godRaysRecorded());
    auto rays = chain.readGodRays();
    auto quarter = chain.readDownsampled();
    EXPECT_TRUE(rays.has_value() && quarter.has_value());
    if (!rays || !quarter) return {};
    const glm::vec2 centre = chain.godRayCentre(lightUv);
    return {*rays, godRaysReference(*quarter, centre, settings.godRayThreshold, settings.godRayDecay), centre};
  }

  // The reference's brightest red and the largest red difference from it.
  static std::pair<float, float> peakAndWorst(const GodRays& rays) {
    float peak = 0.0f, worst = 0.0f;
    for (std::size_t i = 0; i < rays.cpu.texels.size(); ++i) {
      peak = std::max(peak, rays.cpu.texels[i].r);
      worst = std::max(worst, std::abs(rays.cpu.texels[i].r - rays.gpu.texels[i].r));
    }
    return {peak, worst};
  }
};

// Half-float stores may round towards zero (Vulkan allows it; lavapipe does): up to 2⁻¹⁰ relative
// per image written, and biased low.
constexpr double kHalfStore = 1.0 / 1024.0;

// A single bright pixel: downsampled it is an impulse of 1/16 its value, and four blurs spread it
// into the outer product of the kernel convolved with itself. Tolerance: five half-float stores
// (downsample, four blurs) of the local value, plus 10⁻⁶ of the peak for the tails.
TEST_F(PostChainTest, GlowOfAnImpulseMatchesTheCpuKernel) {
  HdrImage frame = blank(256, 192);
  const glm::uvec2 pixel(4 * 32 + 1, 4 * 24 + 2);
  frame.texels[std::size_t(pixel.y) * frame.width + pixel.x] = glm::vec4(1600.0f, 800.0f, 400.0f, 1.0f);
  const Image uploaded = uploadHdr(device(), frame);
  PostPass chain(device(), uploaded);
  run(chain, {.glowStrength = 0.5f});
  auto glow = chain.readGlow();
  ASSERT_TRUE(glow.has_value()) << glow.error().message;
  const HdrImage expected = glowReference(frame, chain.glowWeights());
  ASSERT_EQ(glow->width, 64u);
  ASSERT_EQ(glow->height, 48u);
  const double peak = expected.at(32, 24).r;
  glm::dvec3 total(0.0);
  for (std::uint32_t y = 0; y < glow->height; ++y)
    for (std::uint32_t x = 0; x < glow->width; ++x) {
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(glow->at(x, y)[c], expected.at(x, y)[c], 5 * kHalfStore * expected.at(x, y)[c] + 1e-6 * peak)
            << x << "," << y;
      total += glm::dvec3(glow->at(x, y));
    }
  // The kernel sums to 1 and the impulse is farther than two radii from the edges: the blurs
  // keep its energy, 1/16 of the pixel's (less the stores' rounding, ≤ 5·2⁻¹⁰).
  EXPECT_NEAR(total.r, 100.0, 100.0 * 5 * kHalfStore);
  EXPECT_NEAR(total.g, 50.0, 50.0 * 5 * kHalfStore);
  EXPECT_NEAR(total.b, 25.0, 25.0 * 5 * kHalfStore);
  // The peak of the separable blur: (Σ w_k²)² per axis pair.
  double selfConvolution = 0.0;
  for (std::size_t k = 0; k < chain.glowWeights().size(); ++k)
    selfConvolution += (k == 0 ? 1.0 : 2.0) * double(chain.glowWeights()[k]) * chain.glowWeights()[k];
  EXPECT_NEAR(peak, 100.0 * selfConvolution * selfConvolution, 1e-5 * peak);
  EXPECT_NEAR(glow->at(32, 24).r, peak, 5 * kHalfStore * peak);
}

// Noise over 4 decades on a frame whose sides are not multiples of 4: the downsample's clamped
// last row and column and the blurs' clamped edges, against the CPU. Tolerance: one half-float
// store per image written, relative to the local value (the bilinear taps sit exactly half-way
// between pixels, where their weights are exact).
TEST_F(PostChainTest, GlowOfNoiseMatchesTheCpuReference) {
  const HdrImage frame = noise(90, 70, 0.01f, 100.0f, 7);
  const Image uploaded = uploadHdr(device(), frame);
  PostPass chain(device(), uploaded);
  run(chain, {.glowStrength = 1.0f});
  auto downsampled = chain.readDownsampled();
  auto glow = chain.readGlow();
  ASSERT_TRUE(downsampled.has_value() && glow.has_value());
  const HdrImage quarter = downsampleForPost(frame);
  const HdrImage expected = glowReference(frame, chain.glowWeights());
  ASSERT_EQ(downsampled->width, 23u);
  ASSERT_EQ(downsampled->height, 18u);
  double worstQuarter = 0.0, worstGlow = 0.0;
  for (std::size_t i = 0; i < quarter.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      worstQuarter = std::max(worstQuarter, std::abs(downsampled->texels[i][c] / quarter.texels[i][c] - 1.0));
      worstGlow = std::max(worstGlow, std::abs(glow->texels[i][c] / expected.texels[i][c] - 1.0));
    }
  EXPECT_LT(worstQuarter, 1.01 * kHalfStore) << "one half-float store";
  EXPECT_LT(worstGlow, 5 * kHalfStore) << "five half-float stores";
}

// The tiny image read back and its log-average on the CPU (double) against the GPU's reduction
// (float sums of ≤ 4096 logs: 1e-5 relative); the tiny image against the CPU's from the frame
// (two half-float stores of means, ≤ 2·2⁻¹⁰); the first frame snaps, so gain = key / L̄.
TEST_F(PostChainTest, LogAverageMatchesTheCpuOverTheSameTinyImage) {
  const HdrImage frame = noise(610, 290, 0.001f, 50.0f, 11);  // downsampled 153×73, blocks of 3: 51×25
  const Image uploaded = uploadHdr(device(), frame);
  PostPass chain(device(), uploaded);
  const PostSettings settings{.autoGain = true, .key = 0.18f};
  run(chain, settings, 1.0f);
  auto tiny = chain.readTiny();
  ASSERT_TRUE(tiny.has_value());
  ASSERT_EQ(tiny->width, 51u);
  ASSERT_EQ(tiny->height, 25u);
  const PostExposure state = chain.readExposure();
  EXPECT_EQ(state.frames, 1u);
  const double gpu = std::exp(double(state.frameLogLuminance));
  EXPECT_NEAR(gpu / logAverageLuminance(*tiny), 1.0, 1e-5);
  EXPECT_EQ(state.adaptedLogLuminance, state.frameLogLuminance) << "the first frame snaps";
  EXPECT_NEAR(state.gain * gpu / 0.18, 1.0, 1e-5);

  const HdrImage expectedTiny = tinyForAutoGain(downsampleForPost(frame));
  for (std::size_t i = 0; i < expectedTiny.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(tiny->texels[i][c] / expectedTiny.texels[i][c], 1.0, 2 * kHalfStore) << i;
  EXPECT_NEAR(gpu / logAverageLuminance(expectedTiny), 1.0, 2 * kHalfStore);
}

// Run after run, the same frame gives the same bits (fixed reduction order).
TEST_F(PostChainTest, LogAverageIsDeterministic) {
  const HdrImage frame = noise(333, 222, 0.001f, 50.0f, 5);
  const Image uploaded = uploadHdr(device(), frame);
  PostPass chain(device(), uploaded);
  run(chain, {.autoGain = true});
  const float first = chain.readExposure().frameLogLuminance;
  for (int i = 0; i < 3; ++i) {
    run(chain, {.autoGain = true});
    EXPECT_EQ(chain.readExposure().frameLogLuminance, first);
  }
}

// ---------------------------------------------------------------------------------------------
// God rays on the chain's downsampled copy

// A smooth positive frame, 256×192, periods of 128 and 96 pixels (32 and 24 copy texels): bilinear
// interpolation at ≤ 2 texel spacing loses at most h²/8·k²·amplitude ≈ 2 % of the amplitude per
// transform, so the round trip is a fair test of the mapping rather than of the sampling.
HdrImage smoothFrame() {
  HdrImage frame = blank(256, 192);
  for (std::uint32_t y = 0; y < frame.height; ++y)
    for (std::uint32_t x = 0; x < frame.width; ++x) {
      const float wave = std::sin(6.2831853f * x / 128.0f) * std::cos(6.2831853f * y / 96.0f);
      frame.texels[std::size_t(y) * frame.width + x] = glm::vec4(1.0f + 0.5f * wave, 1.0f - 0.3f * wave, 1.0f, 1.0f);
    }
  return roundedToHalf(frame);
}

// Image → polar → back on the GPU (threshold 0 keeps every texel, no blur), against the
// downsampled copy it started from, at every texel at least 2 texels from the light (closer, all
// of a texel's rays meet at one point). Tolerance 0.04 (8 % of the 0.5 amplitude): two bilinear
// resamplings of the waves (≈ 2 % each, above) plus half-float stores. And against the CPU
// round trip of the same copy: 2·10⁻³ (the stores and float trigonometry).
TEST_F(PostChainTest, PolarRoundTripReturnsTheImageAwayFromTheCentre) {
  const HdrImage frame = smoothFrame();
  const Image uploaded = uploadHdr(device(), frame);
  PostPass chain(device(), uploaded);
  const glm::vec2 lightUv(0.37f, 0.58f);
  const PostSettings settings{.godRays = 1.0f, .godRayThreshold = 0.0f};
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    chain.recordDownsample(commands);
    chain.recordGodRays(commands, settings, lightUv, false);
    chain.recordHandOff(commands, settings, 1.0f);
  });
  auto quarter = chain.readDownsampled();
  auto back = chain.readGodRays();
  auto polar = chain.readGodRayPolar();
  ASSERT_TRUE(quarter.has_value() && back.has_value() && polar.has_value());
  const glm::uvec2 size(quarter->width, quarter->height);
  ASSERT_EQ(glm::uvec2(polar->width, polar->height), godRayPolarSize(size));
  const glm::vec2 centre = chain.godRayCentre(lightUv);
  const glm::uvec2 used = godRayPolarExtent(size, centre);
  EXPECT_LT(used.x * used.y, polar->width * polar->height) << "a light away from the corners uses part of it";
  const HdrImage cpu = fromPolar(toPolar(godRayBright(*quarter, 0.0f), centre, used), centre, size);
  double worst = 0.0, worstCpu = 0.0;
  for (std::uint32_t y = 0; y < size.y; ++y)
    for (std::uint32_t x = 0; x < size.x; ++x) {
      if (glm::length(glm::vec2(x + 0.5f, y + 0.5f) - centre) < 2.0f) continue;
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, double(std::abs(back->at(x, y)[c] - quarter->at(x, y)[c])));
        worstCpu = std::max(worstCpu, double(std::abs(back->at(x, y)[c] - cpu.at(x, y)[c])));
      }
    }
  EXPECT_LT(worst, 0.04) << "round trip against the original";
  EXPECT_LT(worstCpu, 2e-3) << "GPU against the CPU round trip";
  std::printf("polar round trip: worst %.4f against the original, %.5f against the CPU\n", worst, worstCpu);
}

// Every texel of `rays` brighter than 10⁻³ of the brightest lies on the ray from `light` through
// `source` and beyond `source`: at distance t along the ray, within 1 + 1.71·t/|source − light|
// texels of it (the bright texel spans ±(√2/2 + 1) texels across the ray after the bilinear
// polar sample, widening with the distance, plus one for the inverse sample) and no nearer the
// light than 1.5 texels before the source. Returns how far out the rays reach.
float checkOnRay(const HdrImage& rays, glm::vec2 light, glm::vec2 source) {
  float brightest = 0.0f;
  for (const glm::vec4& texel : rays.texels) brightest = std::max(brightest, texel.r);
  EXPECT_GT(brightest, 0.0f);
  const glm::vec2 along = glm::normalize(source - light);
  const float sourceDistance = glm::length(source - light);
  float reach = 0.0f;
  for (std::uint32_t y = 0; y < rays.height; ++y)
    for (std::uint32_t x = 0; x < rays.width; ++x) {
      if (rays.at(x, y).r <= 1e-3f * brightest) continue;
      const glm::vec2 d = glm::vec2(x + 0.5f, y + 0.5f) - light;
      const float t = glm::dot(d, along);
      const float across = std::abs(d.x * along.y - d.y * along.x);
      EXPECT_LE(across, 1.0f + 1.71f * t / sourceDistance) << x << "," << y << " off the ray";
      EXPECT_GE(t, sourceDistance - 1.5f) << x << "," << y << " towards the light";
      reach = std::max(reach, t - sourceDistance);
    }
  return reach;
}

// The GPU's radial blur walks each ray with running sums instead of summing its taps
// (shaders/post_ray_blur.comp); against the CPU's direct sum of the same polar image (read back)
// over a noise frame, with the light off centre so that rays of every length are blurred. Each
// texel within a half-float store of the reference (2⁻¹⁰ relative), plus 10⁻⁵ of the brightest
// input for the running sums' fp32 rounding; a weight off by 1 % fails it.
TEST_F(PostChainTest, RadialBlurByRunningSumsMatchesTheDirectSum) {
  HdrImage frame = blank(1024, 768);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> brightness(0.0f, 4.0f);
  for (glm::vec4& texel : frame.texels)
    texel = glm::vec4(brightness(random), brightness(random), brightness(random), 1);
  const Image uploaded = uploadHdr(device(), frame);
  PostPass chain(device(), uploaded);
  const glm::vec2 lightUv(0.3f, 0.65f);
  const PostSettings settings{.godRays = 1.0f, .godRayThreshold = 0.0f, .godRayDecay = 0.96f};
  device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    chain.recordDownsample(commands);
    chain.recordGodRays(commands, settings, lightUv, true);
    chain.recordHandOff(commands, settings, 1.0f);
  });
  auto quarter = chain.readDownsampled();
  auto polar = chain.readGodRayPolar();
  auto blurred = chain.readGodRayPolarBlurred();
  ASSERT_TRUE(quarter.has_value() && polar.has_value() && blurred.has_value());
  const glm::uvec2 used = godRayPolarExtent({quarter->width, quarter->height}, chain.godRayCentre(lightUv));
  ASSERT_GT(used.y, std::uint32_t(2 * kGodRayTaps * kGodRayStep)) << "rays longer than the taps reach";
  HdrImage inUse = blank(used.x, used.y);
  float peak = 0.0f;
  for (std::uint32_t j = 0; j < used.y; ++j)
    for (std::uint32_t i = 0; i < used.x; ++i) {
      inUse.texels[std::size_t(j) * used.x + i] = polar->at(i, j);
      peak = std::max(peak, polar->at(i, j).r);
    }
  const HdrImage cpu = radialBlur(inUse, godRayWeights(settings.godRayDecay));
  std::size_t outside = 0;
  double worst = 0.0;
  for (std::uint32_t j = 0; j < used.y; ++j)
    for (std::uint32_t i = 0; i < used.x; ++i)
      for (int c = 0; c < 3; ++c) {
        const double expected = cpu.at(i, j)[c], difference = std::abs(blurred->at(i, j)[c] - expected);
        worst = std::max(worst, difference / std::max(expected, 1e-3));
        if (difference > kHalfStore * expected + 1e-5 * peak) ++outside;
      }
  EXPECT_EQ(outside, 0u) << "of " << used.x * used.y * 3 << " values; worst relative difference " << worst;
}

// One bright copy texel (a 4×4 block of 50 in a black frame), the light 26 texels away: the blur
// carries it outwards along its ray only, on the GPU and in the CPU reference, and the two agree
// (within 2 % of the peak: float trigonometry against double, half-float stores).
// The part of the polar image a light uses reaches the farthest corner, with rays at most 2 copy
// texels apart there: all of it for a light in a corner, about a quarter for one at the centre.
TEST(PostReference, GodRaysUseThePolarImageOutToTheFarthestCorner) {
  const glm::uvec2 quarter(320, 180);
  const glm::uvec2 all = godRayPolarSize(quarter);
  EXPECT_EQ(godRayPolarExtent(quarter, {0.0f, 0.0f}), all);
  EXPECT_EQ(godRayPolarExtent(quarter, glm::vec2(quarter)), all);
  const glm::uvec2 centred = godRayPolarExtent(quarter, 0.5f * glm::vec2(quarter));
  EXPECT_EQ(centred.y, std::uint32_t(std::ceil(0.5 * std::hypot(320.0, 180.0))) + 1);
  EXPECT_GE(double(centred.x), std::numbers::pi * centred.y);
  EXPECT_EQ(centred.x % 8, 0u);
  EXPECT_LT(centred.x * centred.y, all.x * all.y / 3);
}

// The radial blur moves light outwards along each ray without adding any: a polar image with one
// bright row (at the light, beside it, or further out) keeps each column's sum (short of the
// image's end), and a row at the light lights the rows k·step beyond it with w[k] exactly.
TEST(PostReference, RadialBlurKeepsTheLightOfEachRay) {
  const std::vector<float> weights = godRayWeights(0.96f);
  for (std::uint32_t row : {0u, 1u, 10u}) {
    HdrImage polar = blank(4, 160);
    for (std::uint32_t i = 0; i < 4; ++i) polar.texels[std::size_t(row) * 4 + i] = glm::vec4(float(i + 1));
    const HdrImage blurred = radialBlur(polar, weights);
    for (std::uint32_t i = 0; i < 4; ++i) {
      double sum = 0.0;
      for (std::uint32_t j = 0; j < 160; ++j) sum += blurred.at(i, j).r;
      EXPECT_NEAR(sum, double(i + 1), 1e-5 * double(i + 1)) << "row " << row << ", column " << i;
    }
    if (row == 0)
      for (std::uint32_t j = 0; j < 160; ++j) {
        const int tap = int(j) / kGodRayStep;
        const float expected = int(j) % kGodRayStep == 0 && tap < kGodRayTaps ? weights[std::size_t(tap)] : 0.0f;
        EXPECT_NEAR(blurred.at(0, j).r, expected, 1e-7f) << j;
      }
  }
}

TEST_F(PostChainTest, RadialBlurOfABrightTexelSpreadsOnlyAlongItsRayAwayFromTheLight) {
  HdrImage frame = blank(256, 192);
  const glm::uvec2 source(40, 30);
  for (std::uint32_t dy = 0; dy < 4; ++dy)
    for (std::uint32_t dx = 0; dx < 4; ++dx)
      frame.texels[std::size_t(4 * source.y + dy) * frame.width + 4 * source.x + dx] = glm::vec4(50, 50, 50, 1);
  const GodRays rays = godRaysOf(frame, glm::vec2(16.0f / 64.0f, 20.0f / 48.0f));
  ASSERT_FALSE(rays.gpu.texels.empty());
  const glm::vec2 sourceCentre = glm::vec2(source) + 0.5f;
  const float gpuReach = checkOnRay(rays.gpu, rays.centre, sourceCentre);
  const float cpuReach = checkOnRay(rays.cpu, rays.centre, sourceCentre);
  // Taps 2 polar texels apart, 32 of them: the shaft reaches ≈ 62 texels, cut by the frame's edge
  // (here ≈ 30 texels along the ray).
  EXPECT_GT(gpuReach, 20.0f);
  EXPECT_NEAR(gpuReach, cpuReach, 1.5f);
  const auto [peak, worst] = peakAndWorst(rays);
  EXPECT_LT(worst, 0.02f * peak);
  std::printf("single texel: reach %.1f texels, GPU vs CPU worst %.4f of peak %.4f\n", gpuReach, worst, peak);
}

// A bright block on the light itself (a visible sun): every ray starts in it, and taps that would
// reach back past the light must add nothing on the GPU as in the CPU reference (whose blur keeps
// each ray's light: RadialBlurKeepsTheLightOfEachRay). Within 2 % of the peak.
TEST_F(PostChainTest, RadialBlurOfABrightBlockOnTheLightMatchesTheCpu) {
  HdrImage frame = blank(256, 192);
  for (std::uint32_t y = 88; y < 104; ++y)
    for (std::uint32_t x = 120; x < 136; ++x) frame.texels[std::size_t(y) * frame.width + x] = glm::vec4(50, 50, 50, 1);
  const GodRays rays = godRaysOf(frame, glm::vec2(0.5f, 0.5f));
  ASSERT_FALSE(rays.gpu.texels.empty());
  const auto [peak, worst] = peakAndWorst(rays);
  EXPECT_GT(peak, 1.0f);
  EXPECT_LT(worst, 0.02f * peak);
  std::printf("block on the light: GPU vs CPU worst %.4f of peak %.4f\n", worst, peak);
}

// ---------------------------------------------------------------------------------------------
// End to end through the Renderer

// A Lambert quad filling about half the frame's height, in front of the background.
const std::array<glm::vec3, 4> kPositions{glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(1, 1, 0),
                                          glm::vec3(-1, 1, 0)};
const std::array<glm::vec3, 4> kNormals{glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1)};
const std::array<std::uint32_t, 6> kIndices{0, 1, 2, 0, 2, 3};

class PostRendering : public testing::VulkanTest {
public:
  std::unique_ptr<Renderer> makeRenderer(vk::Extent2D extent, bool withQuad) {
    auto renderer = Renderer::create(device(), {.extent = extent});
    EXPECT_TRUE(renderer.has_value());
    StaticScene scene;
    if (withQuad) {
      scene.meshes = {MeshData{.positions = kPositions, .normals = kNormals, .indices = kIndices}};
      scene.materials = {MaterialData{.baseColor = {0.8f, 0.6f, 0.4f}}};
    }
    EXPECT_TRUE((*renderer)->setScene(scene).has_value());
    return std::move(*renderer);
  }

  // The quad lit by a key light, ambient and background all scaled by `brightness`: the HDR frame
  // scales with it (Lambert is linear in the light).
  static FrameInput litQuad(float brightness, const PostSettings& post) {
    return FrameInput{.camera = {.position = {0, 0, 6}, .target = {0, 0, 0}},
                      .lights = {DirectionalLight{.direction = glm::normalize(glm::vec3(0.3f, 0.4f, 0.9f)),
                                                  .intensity = 3.0f * brightness}},
                      .instances = {{.mesh = 0, .material = 0}},
                      .ambient = glm::vec3(0.05f * brightness),
                      .background = glm::vec3(0.05f, 0.08f, 0.12f) * brightness,
                      .post = post};
  }

  static std::vector<std::uint8_t> draw(Renderer& renderer, const FrameInput& frame,
                                        std::vector<PassTiming>* timings = nullptr) {
    auto rendered = renderer.render(frame);
    EXPECT_TRUE(rendered.has_value()) << rendered.error().message;
    if (timings && rendered) *timings = *rendered;
    auto rgba = renderer.readOutput();
    EXPECT_TRUE(rgba.has_value());
    return rgba ? *rgba : std::vector<std::uint8_t>{};
  }
};

// Uniform HDR colours (the background alone), tone mapped with a fixed exposure and with the auto
// gain, against Reinhard's formula on the half-float colour (render/passes/post_reference.hpp's
// reinhard), sRGB-encoded: ±1 code (the encode may round either way).
TEST_F(PostRendering, ReinhardMatchesItsFormulaOnKnownHdrValues) {
  auto renderer = makeRenderer({16, 16}, false);
  const std::array<glm::vec3, 7> colours{glm::vec3(0.05f),       glm::vec3(0.18f),       glm::vec3(1.0f),
                                         glm::vec3(4, 2, 1),     glm::vec3(0.5f, 3, 12), glm::vec3(30.0f),
                                         glm::vec3(200, 100, 50)};
  for (const glm::vec3& colour : colours)
    for (const bool autoGain : {false, true}) {
      const float exposure = autoGain ? 1.0f : 0.7f;
      const FrameInput frame{
          .background = colour,
          .exposure = exposure,
          .post = {.toneMapping = ToneMapping::kReinhard, .autoGain = autoGain, .resetAdaptation = true}};
      const std::vector<std::uint8_t> rgba = draw(*renderer, frame);
      ASSERT_FALSE(rgba.empty());
      const glm::dvec3 hdr(roundToHalf(colour.r), roundToHalf(colour.g), roundToHalf(colour.b));
      // A uniform frame's log-average is δ + L itself.
      const double gain = autoGain ? 0.18 / (kLogLuminanceDelta + luminance(hdr)) : exposure;
      const glm::dvec3 displayed = reinhard(hdr, gain);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(rgba[c], 255.0 * srgbEncode(displayed[c]), 1.0)
            << "colour " << colour[c] << " channel " << c << (autoGain ? " auto gain" : " exposure 0.7");
      // With the auto gain, a grey lands at the key value a, displayed as a/(1 + a).
      if (autoGain && colour.r == colour.b) {
        EXPECT_NEAR(luminance(displayed), 0.18 / 1.18, 1e-3);
      }
    }
}

// The quad scene, then the same twice as bright: after the adaptation settles, the displayed mean
// luminance is back where it was, within 2 % (Reinhard and the linear scale alike). Δt = 0.1 s,
// τ = 0.25 s: each frame closes 1 − exp(−0.4) = 33 % of the log distance, so 14 frames leave
// ln 2 · 0.67¹⁴ = 0.26 % of the gain to go.
TEST_F(PostRendering, AutoGainBringsASceneTwiceAsBrightToTheSameDisplayedLuminance) {
  for (const ToneMapping mapping : {ToneMapping::kReinhard, ToneMapping::kLinear}) {
    auto renderer = makeRenderer({64, 48}, true);
    PostSettings post{.toneMapping = mapping,
                      .autoGain = true,
                      .adaptationSeconds = 0.25f,
                      .frameSeconds = 0.1f,
                      .resetAdaptation = true};
    const double before = displayedLuminance(draw(*renderer, litQuad(1.0f, post)));
    post.resetAdaptation = false;
    const double unadapted = displayedLuminance(draw(*renderer, litQuad(2.0f, post)));
    std::vector<std::uint8_t> rgba;
    for (int frame = 0; frame < 14; ++frame) rgba = draw(*renderer, litQuad(2.0f, post));
    const double after = displayedLuminance(rgba);
    EXPECT_NEAR(after / before, 1.0, 0.02) << "tone mapping " << int(mapping);
    EXPECT_GT(unadapted / before, 1.1) << "the first bright frame is brighter: the gain adapts over time";
    // The gain itself: key / L̄, L̄ twice the first scene's.
    const PostExposure state = renderer->post().readExposure();
    EXPECT_NEAR(state.adaptedLogLuminance, state.frameLogLuminance, 0.01);
  }
}

// A scene 4× brighter from one frame to the next at 30 frames per second, τ = 0.5 s: the adapted
// log-luminance moves α = 1 − exp(−Δt/τ) = 6.45 % of its distance per frame (shaders/post_adapt.comp),
// so the gain changes by at most α·ln 4 in log (a factor 4^α = 1.094) per frame, the first frame
// most; and the displayed luminance at a steady scene changes no more than the gain (Reinhard's
// curve and the clamp compress), plus a tenth of a percent for the 8-bit codes.
TEST_F(PostRendering, AdaptationNeverJumpsMoreThanTauAndDeltaTAllow) {
  auto renderer = makeRenderer({64, 48}, true);
  PostSettings post{.toneMapping = ToneMapping::kReinhard,
                    .autoGain = true,
                    .adaptationSeconds = 0.5f,
                    .frameSeconds = 1.0f / 30.0f,
                    .resetAdaptation = true};
  draw(*renderer, litQuad(1.0f, post));
  post.resetAdaptation = false;
  const double rate = adaptationRate(post.frameSeconds, post.adaptationSeconds);
  const double bound = rate * std::log(4.0);
  double previousGain = renderer->post().readExposure().gain;
  double previousDisplayed = 0.0;
  double largestStep = 0.0;
  for (int frame = 0; frame < 30; ++frame) {
    const double displayed = displayedLuminance(draw(*renderer, litQuad(4.0f, post)));
    const double gain = renderer->post().readExposure().gain;
    const double step = std::abs(std::log(gain / previousGain));
    EXPECT_LE(step, bound * (1.0 + 1e-3)) << "frame " << frame;
    EXPECT_LT(gain, previousGain) << "frame " << frame << ": the gain falls towards the brighter scene's";
    largestStep = std::max(largestStep, step);
    if (frame > 0) {
      EXPECT_LE(std::abs(std::log(displayed / previousDisplayed)), bound + 1e-3) << "frame " << frame;
    }
    previousGain = gain;
    previousDisplayed = displayed;
  }
  EXPECT_GT(largestStep, 0.99 * bound) << "the first frame after the change moves the full share α";
}

// The glow leaves a uniform frame as it is (a normalised blur of a constant) and softens an edge:
// background pixels next to the bright quad light up.
TEST_F(PostRendering, GlowSpreadsLightAcrossAnEdgeOnly) {
  auto renderer = makeRenderer({64, 48}, true);
  const PostSettings sharp{};
  const PostSettings soft{.glowStrength = 0.5f};
  FrameInput empty{.background = glm::vec3(0.3f, 0.2f, 0.1f)};
  const std::vector<std::uint8_t> plain = draw(*renderer, empty);
  empty.post = soft;
  const std::vector<std::uint8_t> glowing = draw(*renderer, empty);
  for (std::size_t i = 0; i < plain.size(); ++i) ASSERT_NEAR(plain[i], glowing[i], 1) << i;

  const std::vector<std::uint8_t> edge = draw(*renderer, litQuad(1.0f, sharp));
  const std::vector<std::uint8_t> softened = draw(*renderer, litQuad(1.0f, soft));
  // The quad spans about x 19..44 at y 24 (6 m away, 0.7 rad field of view): a few pixels left of it.
  const std::size_t outside = (std::size_t(24) * 64 + 15) * 4;
  EXPECT_GT(int(softened[outside]), int(edge[outside]) + 5) << "background beside the quad brightens";
}

// God rays off, or on with the light behind the camera or off screen: the output is bit-identical
// to the plain path's (the same specialised pipeline, no extra pass). On, with the light behind
// the quad in a bright sky: the sky beside the quad brightens along the rays, the quad's middle
// does not (±1 code), and the pass is timed.
TEST_F(PostRendering, GodRaysOffLeaveTheOutputBitIdentical) {
  auto renderer = makeRenderer({64, 48}, true);
  for (const PostSettings& base :
       {PostSettings{},
        PostSettings{
            .toneMapping = ToneMapping::kReinhard, .autoGain = true, .glowStrength = 0.5f, .resetAdaptation = true}}) {
    const std::vector<std::uint8_t> plain = draw(*renderer, litQuad(1.0f, base));  // light behind the camera
    PostSettings rays = base;
    rays.godRays = 2.0f;
    rays.godRayThreshold = 0.0f;
    std::vector<PassTiming> timings;
    EXPECT_EQ(draw(*renderer, litQuad(1.0f, rays), &timings), plain) << "light behind the camera";
    for (const PassTiming& timing : timings) EXPECT_NE(timing.pass, PassName::kGodRays);
    FrameInput offScreen = litQuad(1.0f, rays);
    offScreen.lights.insert(offScreen.lights.begin(),
                            DirectionalLight{.direction = glm::normalize(glm::vec3(3, 0, -1)), .intensity = 0.0f});
    FrameInput offScreenPlain = offScreen;
    offScreenPlain.post = base;
    EXPECT_EQ(draw(*renderer, offScreen), draw(*renderer, offScreenPlain)) << "light off screen";
  }
  EXPECT_FALSE(godRayLightUv(Camera{.position = {0, 0, 6}}, glm::vec3(0, 0, 1), 4.0f / 3.0f).has_value());
  const auto ahead = godRayLightUv(Camera{.position = {0, 0, 6}}, glm::vec3(0, 0, -1), 4.0f / 3.0f);
  ASSERT_TRUE(ahead.has_value());
  EXPECT_NEAR(ahead->x, 0.5f, 1e-5f);
  EXPECT_NEAR(ahead->y, 0.5f, 1e-5f);

  // The light straight ahead, behind the quad; a sky of 2 (above the threshold of 1), exposure 0.25.
  FrameInput sky{.camera = {.position = {0, 0, 6}, .target = {0, 0, 0}},
                 .lights = {DirectionalLight{.direction = {0, 0, -1}, .intensity = 0.0f},
                            DirectionalLight{.direction = glm::normalize(glm::vec3(0.3f, 0.4f, 0.9f))}},
                 .instances = {{.mesh = 0, .material = 0}},
                 .background = glm::vec3(2.0f),
                 .exposure = 0.25f};
  const std::vector<std::uint8_t> dark = draw(*renderer, sky);
  sky.post.godRays = 4.0f;
  std::vector<PassTiming> timings;
  const std::vector<std::uint8_t> lit = draw(*renderer, sky, &timings);
  const std::size_t sideOfQuad = (std::size_t(24) * 64 + 8) * 4;
  EXPECT_GT(int(lit[sideOfQuad]), int(dark[sideOfQuad]) + 5) << "the sky brightens along the rays";
  // The quad's centre: the rays only run outwards from the light, which it hides.
  const std::size_t quadCentre = (std::size_t(24) * 64 + 32) * 4;
  EXPECT_NEAR(int(lit[quadCentre]), int(dark[quadCentre]), 1) << "no rays over the occluder's middle";
  if (!timings.empty()) {
    EXPECT_NE(
        std::find_if(timings.begin(), timings.end(), [](const PassTiming& t) { return t.pass == PassName::kGodRays; }),
        timings.end());
  }
}

// The output pass against the formula it applies to the chain's results, pixel by pixel: the
// frame (a uniform sky, B) mixed with the glow by s, the god rays × r added, times the gain (the
// exposure, or the auto gain the chain measured), clamped and sRGB-encoded; the glow and the rays
// read back and bilinear-sampled on the CPU at each pixel's centre. ±1 code (the encode and the
// sampler's sub-texel precision may round either way).
TEST_F(PostRendering, OutputAppliesTheGainGlowAndGodRaysAsTheirFormulasSay) {
  // Sizes that 4 does not divide: the copy covers a little more than the frame.
  constexpr std::uint32_t kWidth = 66, kHeight = 50;
  auto renderer = makeRenderer({kWidth, kHeight}, false);
  const auto bilinear = [](const HdrImage& image, glm::dvec2 uv) {
    const glm::dvec2 at = uv * glm::dvec2(image.width, image.height) - 0.5;
    const glm::dvec2 low = glm::floor(at), t = at - low;
    const auto texel = [&](double x, double y) {
      return glm::dvec3(image.at(std::uint32_t(std::clamp(x, 0.0, double(image.width - 1))),
                                 std::uint32_t(std::clamp(y, 0.0, double(image.height - 1)))));
    };
    return glm::mix(glm::mix(texel(low.x, low.y), texel(low.x + 1, low.y), t.x),
                    glm::mix(texel(low.x, low.y + 1), texel(low.x + 1, low.y + 1), t.x), t.y);
  };
  for (const bool autoGain : {false, true}) {
    const PostSettings post{
        .autoGain = autoGain, .glowStrength = 0.4f, .resetAdaptation = true, .godRays = 1.5f, .godRayThreshold = 0.3f};
    const FrameInput sky{
        .camera = {.position = {0, 0, 6}, .target = {0, 0, 0}},
        .lights = {DirectionalLight{.direction = glm::normalize(glm::vec3(0.2f, 0.1f, -1.0f)), .intensity = 0.0f}},
        .background = glm::vec3(0.9f, 0.6f, 0.3f),
        .exposure = 0.7f,
        .post = post};
    const std::vector<std::uint8_t> rgba = draw(*renderer, sky);
    const PostPass& chain = renderer->post();
    auto glow = chain.readGlow();
    auto rays = chain.readGodRays();
    ASSERT_TRUE(glow.has_value() && rays.has_value() && rgba.size() == std::size_t(kWidth) * kHeight * 4);
    const double gain = autoGain ? chain.readExposure().gain : 0.7;
    const glm::dvec3 frame(roundToHalf(0.9f), roundToHalf(0.6f), roundToHalf(0.3f));
    const double s = post.glowStrength, r = post.godRays;
    double brightestRay = 0.0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const glm::dvec2 uv = glm::dvec2((x + 0.5) / kWidth, (y + 0.5) / kHeight) * glm::dvec2(chain.overlayUvScale());
        const glm::dvec3 ray = bilinear(*rays, uv);
        brightestRay = std::max(brightestRay, luminance(ray));
        const glm::dvec3 expected = gain * ((1.0 - s) * frame + s * bilinear(*glow, uv) + r * ray);
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(rgba[(std::size_t(y) * kWidth + x) * 4 + std::size_t(c)], 255.0 * srgbEncode(expected[c]), 1.0)
              << "pixel " << x << ", " << y << " channel " << c << (autoGain ? " auto gain" : " exposure");
      }
    EXPECT_GT(brightestRay, 0.05) << "the rays add something to check";
  }
}

TEST_F(PostRendering, PostPassesAreTimedOnlyWhenAskedFor) {
  auto renderer = makeRenderer({32, 32}, true);
  std::vector<PassTiming> timings;
  const auto names = [&] {
    std::vector<PassName> passes;
    for (const PassTiming& timing : timings) passes.push_back(timing.pass);
    return passes;
  };
  draw(*renderer, litQuad(1.0f, {}), &timings);
  if (timings.empty()) GTEST_SKIP() << "the device has no timestamps";
  EXPECT_EQ(names(), (std::vector{PassName::kSurfaceShadows, PassName::kSurfaces, PassName::kOutput}))
      << "the default adds no post passes";
  draw(*renderer, litQuad(1.0f, {.autoGain = true, .glowStrength = 0.5f}), &timings);
  EXPECT_EQ(names(), (std::vector{PassName::kSurfaceShadows, PassName::kSurfaces, PassName::kPostDownsample,
                                  PassName::kAutoGain, PassName::kGlow, PassName::kPostOverlay, PassName::kOutput}));
  for (const PassTiming& timing : timings) EXPECT_GT(timing.milliseconds, 0.0) << timing.pass;
  // The passes run one after another in the order recorded: the first begins the frame, and each
  // begins no earlier than the one before it ended.
  EXPECT_EQ(timings.front().startMilliseconds, 0.0);
  for (std::size_t i = 1; i < timings.size(); ++i)
    EXPECT_GE(timings[i].startMilliseconds, timings[i - 1].startMilliseconds + timings[i - 1].milliseconds - 1e-6)
        << timings[i].pass;
}

TEST_F(PostRendering, RejectsBadSettingsByName) {
  auto renderer = makeRenderer({8, 8}, false);
  const auto errorOf = [&](const PostSettings& post) {
    auto rendered = renderer->render(FrameInput{.post = post});
    EXPECT_FALSE(rendered.has_value());
    return rendered ? std::string() : rendered.error().message;
  };
  EXPECT_NE(errorOf({.key = 0.0f}).find("key"), std::string::npos);
  EXPECT_NE(errorOf({.glowStrength = 1.5f}).find("glowStrength"), std::string::npos);
  EXPECT_NE(errorOf({.adaptationSeconds = -1.0f}).find("adaptationSeconds"), std::string::npos);
  EXPECT_NE(errorOf({.frameSeconds = NAN}).find("frameSeconds"), std::string::npos);
  EXPECT_NE(errorOf({.godRays = -1.0f}).find("godRays"), std::string::npos);
  EXPECT_NE(errorOf({.godRayDecay = 0.0f}).find("godRayDecay"), std::string::npos);
  EXPECT_EQ(errorOf({.godRays = 1.0f, .godRayLight = 1}),
            "the god rays stream from light 1, but the frame has 0 lights");
}

// A light's disc is the cone of its angular radius r around the direction to it. Straight ahead
// of a camera of vertical field θ on an image H pixels high, its outline is a circle of radius
// tan r / tan(θ/2) · H/2 pixels (11.5 here) at the image's centre, of radiance colour ×
// discRadiance: the area where it covers more than half a pixel within 3 % of the circle's, its
// centre within a quarter pixel, the middle's value the exposed radiance (±1 code). The quad in
// front hides all of it.
TEST_F(PostRendering, ALightsDiscIsACircleOfItsAngularRadiusBehindTheScene) {
  auto renderer = makeRenderer({128, 96}, true);
  const float radius = glm::radians(5.0f);
  const glm::vec3 colour(1.0f, 0.5f, 0.25f);
  FrameInput frame{
      .camera = {.position = {0, 0, 6}, .target = {0, 0, 0}},
      .lights = {DirectionalLight{
          .direction = {0, 0, -1}, .color = colour, .intensity = 0.0f, .discRadius = radius, .discRadiance = 2.0f}},
      .background = glm::vec3(0.0f),
      .exposure = 0.25f};
  const std::vector<std::uint8_t> disc = draw(*renderer, frame);
  ASSERT_EQ(disc.size(), std::size_t(128 * 96 * 4));
  const double halfCovered = 255.0 * srgbEncode(0.5 * 2.0 * 0.25);
  double area = 0.0;
  glm::dvec2 centroid(0.0);
  for (std::uint32_t y = 0; y < 96; ++y)
    for (std::uint32_t x = 0; x < 128; ++x)
      if (disc[(std::size_t(y) * 128 + x) * 4] > halfCovered) {
        area += 1.0;
        centroid += glm::dvec2(x + 0.5, y + 0.5);
      }
  const double pixels = std::tan(double(radius)) / std::tan(0.5 * double(frame.camera.verticalFovRadians)) * 48.0;
  EXPECT_NEAR(area, std::numbers::pi * pixels * pixels, 0.03 * std::numbers::pi * pixels * pixels);
  centroid /= area;
  EXPECT_NEAR(centroid.x, 64.0, 0.25);
  EXPECT_NEAR(centroid.y, 48.0, 0.25);
  const std::size_t middle = (std::size_t(48) * 128 + 64) * 4;
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(int(disc[middle + std::size_t(c)]), std::lround(255.0 * srgbEncode(2.0 * 0.25 * colour[c])), 1) << c;
  std::printf("disc of %.2f px radius: area %.1f against %.1f\n", pixels, area, std::numbers::pi * pixels * pixels);

  frame.instances = {{.mesh = 0, .material = 0}};
  const std::vector<std::uint8_t> hidden = draw(*renderer, frame);
  frame.lights[0].discRadius = 0.0f;
  EXPECT_EQ(hidden, draw(*renderer, frame)) << "the quad in front covers the disc";
}

// The rectangle drawn for a disc: around it on screen, nothing when it is all behind the camera
// or off screen, the whole screen when only part of it is behind.
TEST(LightDiscBounds, HoldTheDiscOnScreenOnly) {
  const Camera camera{.position = {0, 0, 6}, .target = {0, 0, 0}};
  const glm::mat4 ndcFromDirection = camera.projection(4.0f / 3.0f) * glm::mat4(glm::mat3(camera.view()));
  const float radius = glm::radians(5.0f);
  const auto ahead = discBounds(ndcFromDirection, {0, 0, -1}, radius);
  ASSERT_TRUE(ahead.has_value());
  const float half = std::tan(radius) / std::tan(0.5f * camera.verticalFovRadians);  // NDC, vertically
  EXPECT_LE(ahead->y, -half);
  EXPECT_GE(ahead->w, half);
  EXPECT_LT(ahead->w, 1.1f * half);
  EXPECT_NEAR(ahead->x, -ahead->z, 1e-5f);
  EXPECT_FALSE(discBounds(ndcFromDirection, {0, 0, 1}, radius).has_value()) << "behind the camera";
  EXPECT_FALSE(discBounds(ndcFromDirection, glm::normalize(glm::vec3(1, 0, -1)), radius).has_value()) << "off screen";
  const auto across = discBounds(ndcFromDirection, glm::normalize(glm::vec3(1, 0, -0.03f)), radius);
  ASSERT_TRUE(across.has_value()) << "partly behind the camera";
  EXPECT_EQ(*across, glm::vec4(-1, -1, 1, 1));
}

}  // namespace
}  // namespace mane::render
