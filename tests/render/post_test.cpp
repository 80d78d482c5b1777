// The HDR post chain (render/passes/post_chain.hpp) and the output pass's tone maps, against the
// CPU references of render/passes/post_reference.hpp and the formulas of Reinhard et al. 2002:
//  - the glow's kernel is a normalised Gaussian; the GPU glow of an impulse and of a noise image
//    matches the CPU downsample + four blurs;
//  - the GPU log-average luminance equals the CPU's over the same tiny image (read back);
//  - end to end through the Renderer: Reinhard on known HDR values through the 8-bit sRGB output,
//    auto gain that brings a scene twice as bright to the same displayed luminance, adaptation
//    whose per-frame gain change stays under the bound that τ and Δt set, the passes' timers.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <span>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/passes/post_chain.hpp"
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
  void run(PostChain& chain, const PostSettings& settings, float exposure = 1.0f) {
    device().submitAndWait(
        [&](const vk::raii::CommandBuffer& commands) { chain.record(commands, settings, exposure); });
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
  PostChain chain(device(), uploaded);
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
  PostChain chain(device(), uploaded);
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
  PostChain chain(device(), uploaded);
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
  PostChain chain(device(), uploaded);
  run(chain, {.autoGain = true});
  const float first = chain.readExposure().frameLogLuminance;
  for (int i = 0; i < 3; ++i) {
    run(chain, {.autoGain = true});
    EXPECT_EQ(chain.readExposure().frameLogLuminance, first);
  }
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

TEST_F(PostRendering, PostPassesAreTimedOnlyWhenAskedFor) {
  auto renderer = makeRenderer({32, 32}, true);
  std::vector<PassTiming> timings;
  const auto names = [&] {
    std::vector<std::string> passes;
    for (const PassTiming& timing : timings) passes.push_back(timing.pass);
    return passes;
  };
  draw(*renderer, litQuad(1.0f, {}), &timings);
  if (timings.empty()) GTEST_SKIP() << "the device has no timestamps";
  EXPECT_EQ(names(), (std::vector<std::string>{"surfaces", "output"})) << "the default adds no passes";
  draw(*renderer, litQuad(1.0f, {.autoGain = true, .glowStrength = 0.5f}), &timings);
  EXPECT_EQ(names(), (std::vector<std::string>{"surfaces", "post downsample", "auto gain", "glow", "output"}));
  for (const PassTiming& timing : timings) EXPECT_GT(timing.milliseconds, 0.0) << timing.pass;
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
}

}  // namespace
}  // namespace mane::render
