#include "render/passes/post_reference.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace mane::render {
namespace {

std::uint32_t ceilDivide(std::uint32_t value, std::uint32_t divisor) {
  return (value + divisor - 1) / divisor;
}

// The polar image out to `reach` copy texels from the light: a radius per texel, and ⌈πR⌉ angles
// rounded up to a multiple of 8, so neighbouring rays are at most 2 texels apart at the far end.
glm::uvec2 polarSizeReaching(double reach) {
  const auto radii = std::uint32_t(std::ceil(reach)) + 1;
  const auto angles = std::uint32_t(std::ceil(3.141592653589793 * radii));
  return {ceilDivide(angles, 8) * 8, radii};
}

HdrImage blankImage(glm::uvec2 size) {
  return {size.x, size.y, std::vector<glm::vec4>(std::size_t(size.x) * size.y)};
}

// Bilinear sample at continuous texel coordinates c (texel centres at i + ½); x wraps when `wrapX`,
// else clamps; y clamps. As shaders/post_common.glsl's postBilinear.
glm::dvec4 bilinear(const HdrImage& image, glm::dvec2 c, bool wrapX) {
  const glm::dvec2 f = c - 0.5;
  const glm::dvec2 base = glm::floor(f);
  const glm::dvec2 t = f - base;
  const auto column = [&](long x) {
    const long w = long(image.width);
    return wrapX ? std::uint32_t(((x % w) + w) % w) : std::uint32_t(std::clamp(x, 0L, w - 1));
  };
  const auto row = [&](long y) { return std::uint32_t(std::clamp(y, 0L, long(image.height) - 1)); };
  const long x0 = long(base.x), y0 = long(base.y);
  const glm::dvec4 top =
      glm::mix(glm::dvec4(image.at(column(x0), row(y0))), glm::dvec4(image.at(column(x0 + 1), row(y0))), t.x);
  const glm::dvec4 bottom =
      glm::mix(glm::dvec4(image.at(column(x0), row(y0 + 1))), glm::dvec4(image.at(column(x0 + 1), row(y0 + 1))), t.x);
  return glm::mix(top, bottom, t.y);
}

constexpr double kTwoPi = 6.283185307179586;

}  // namespace

double luminance(glm::dvec3 rgb) {
  return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

glm::uvec2 postQuarterSize(glm::uvec2 frame) {
  return {ceilDivide(frame.x, kPostDownsampleFactor), ceilDivide(frame.y, kPostDownsampleFactor)};
}

std::uint32_t postTinyBlock(glm::uvec2 quarter) {
  return std::max(1u, ceilDivide(std::max(quarter.x, quarter.y), kPostTinyMaxSize));
}

glm::uvec2 postTinySize(glm::uvec2 quarter) {
  const std::uint32_t block = postTinyBlock(quarter);
  return {ceilDivide(quarter.x, block), ceilDivide(quarter.y, block)};
}

std::vector<float> glowKernel(float sigma) {
  const int radius = std::clamp(int(std::ceil(3.0 * sigma)), 0, kGlowMaxRadius);
  std::vector<double> weights(std::size_t(radius) + 1);
  double total = 0.0;
  for (int k = 0; k <= radius; ++k) {
    weights[k] = std::exp(-0.5 * double(k) * k / (double(sigma) * sigma));
    total += k == 0 ? weights[k] : 2.0 * weights[k];
  }
  std::vector<float> kernel(weights.size());
  for (std::size_t k = 0; k < weights.size(); ++k) kernel[k] = float(weights[k] / total);
  return kernel;
}

HdrImage downsampleForPost(const HdrImage& frame) {
  HdrImage quarter = blankImage(postQuarterSize({frame.width, frame.height}));
  const std::uint32_t factor = kPostDownsampleFactor;
  for (std::uint32_t y = 0; y < quarter.height; ++y)
    for (std::uint32_t x = 0; x < quarter.width; ++x) {
      glm::dvec4 sum(0.0);
      for (std::uint32_t dy = 0; dy < factor; ++dy)
        for (std::uint32_t dx = 0; dx < factor; ++dx)
          sum += glm::dvec4(
              frame.at(std::min(factor * x + dx, frame.width - 1), std::min(factor * y + dy, frame.height - 1)));
      quarter.texels[std::size_t(y) * quarter.width + x] = glm::vec4(sum / double(factor * factor));
    }
  return quarter;
}

HdrImage blurAlong(const HdrImage& image, std::span<const float> kernel, int axis) {
  HdrImage blurred = blankImage({image.width, image.height});
  const int radius = int(kernel.size()) - 1;
  const int last = axis == 0 ? int(image.width) - 1 : int(image.height) - 1;
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) {
      glm::dvec4 sum(0.0);
      for (int k = -radius; k <= radius; ++k) {
        const int along = std::clamp((axis == 0 ? int(x) : int(y)) + k, 0, last);
        const glm::vec4& texel = axis == 0 ? image.at(std::uint32_t(along), y) : image.at(x, std::uint32_t(along));
        sum += double(kernel[std::size_t(std::abs(k))]) * glm::dvec4(texel);
      }
      blurred.texels[std::size_t(y) * image.width + x] = glm::vec4(sum);
    }
  return blurred;
}

HdrImage glowReference(const HdrImage& frame, std::span<const float> kernel) {
  HdrImage glow = downsampleForPost(frame);
  for (int pass = 0; pass < 4; ++pass) glow = blurAlong(glow, kernel, pass % 2);
  return glow;
}

HdrImage tinyForAutoGain(const HdrImage& quarter) {
  const std::uint32_t block = postTinyBlock({quarter.width, quarter.height});
  HdrImage tiny = blankImage(postTinySize({quarter.width, quarter.height}));
  for (std::uint32_t y = 0; y < tiny.height; ++y)
    for (std::uint32_t x = 0; x < tiny.width; ++x) {
      glm::dvec4 sum(0.0);
      double count = 0.0;
      for (std::uint32_t qy = block * y; qy < std::min(block * (y + 1), quarter.height); ++qy)
        for (std::uint32_t qx = block * x; qx < std::min(block * (x + 1), quarter.width); ++qx) {
          sum += glm::dvec4(quarter.at(qx, qy));
          count += 1.0;
        }
      tiny.texels[std::size_t(y) * tiny.width + x] = glm::vec4(sum / count);
    }
  return tiny;
}

double logAverageLuminance(const HdrImage& image) {
  double sum = 0.0;
  for (const glm::vec4& texel : image.texels) sum += std::log(kLogLuminanceDelta + luminance(glm::dvec3(texel)));
  return std::exp(sum / double(image.texels.size()));
}

double adaptationRate(double frameSeconds, double adaptationSeconds) {
  if (!(adaptationSeconds > 0.0)) return 1.0;
  return 1.0 - std::exp(-std::max(frameSeconds, 0.0) / adaptationSeconds);
}

double adaptLogLuminance(double adaptedLog, double frameLog, double rate) {
  return adaptedLog + rate * (frameLog - adaptedLog);
}

glm::dvec3 reinhard(glm::dvec3 rgb, double gain) {
  const glm::dvec3 scaled = gain * rgb;
  return scaled / (1.0 + luminance(scaled));
}

glm::uvec2 godRayPolarSize(glm::uvec2 quarter) {
  return polarSizeReaching(glm::length(glm::dvec2(quarter)));
}

glm::uvec2 godRayPolarExtent(glm::uvec2 quarter, glm::vec2 centre) {
  double farthest = 0.0;
  for (const glm::dvec2 corner : {glm::dvec2(0.0), glm::dvec2(quarter.x, 0.0), glm::dvec2(0.0, quarter.y),
                                  glm::dvec2(quarter)})
    farthest = std::max(farthest, glm::length(corner - glm::dvec2(centre)));
  return glm::min(polarSizeReaching(farthest), godRayPolarSize(quarter));
}

HdrImage godRayBright(const HdrImage& quarter, float threshold) {
  HdrImage bright = blankImage({quarter.width, quarter.height});
  for (std::size_t i = 0; i < quarter.texels.size(); ++i) {
    const glm::dvec3 rgb(quarter.texels[i]);
    const double l = luminance(rgb);
    const double share = l > 0.0 ? std::max(l - double(threshold), 0.0) / l : 0.0;
    bright.texels[i] = glm::vec4(glm::vec3(rgb * share), 1.0f);
  }
  return bright;
}

HdrImage toPolar(const HdrImage& image, glm::vec2 centre, glm::uvec2 polarSize) {
  HdrImage polar = blankImage(polarSize);
  for (std::uint32_t j = 0; j < polarSize.y; ++j)
    for (std::uint32_t i = 0; i < polarSize.x; ++i) {
      const double theta = kTwoPi * (i + 0.5) / polarSize.x;
      const glm::dvec2 at = glm::dvec2(centre) + double(j) * glm::dvec2(std::cos(theta), std::sin(theta));
      polar.texels[std::size_t(j) * polarSize.x + i] = glm::vec4(bilinear(image, at, false));
    }
  return polar;
}

HdrImage fromPolar(const HdrImage& polar, glm::vec2 centre, glm::uvec2 size) {
  HdrImage image = blankImage(size);
  for (std::uint32_t y = 0; y < size.y; ++y)
    for (std::uint32_t x = 0; x < size.x; ++x) {
      const glm::dvec2 d = glm::dvec2(x + 0.5, y + 0.5) - glm::dvec2(centre);
      double theta = std::atan2(d.y, d.x);
      if (theta < 0.0) theta += kTwoPi;
      const glm::dvec2 at(theta * polar.width / kTwoPi, glm::length(d) + 0.5);
      image.texels[std::size_t(y) * size.x + x] = glm::vec4(bilinear(polar, at, true));
    }
  return image;
}

std::vector<float> godRayWeights(float decay) {
  std::vector<double> weights(kGodRayTaps);
  double total = 0.0;
  // The taper brings the last taps to nearly 0, so that a shaft fades out instead of ending where
  // the taps do (decay^31 is still 0.28 at the default 0.96).
  for (int k = 0; k < kGodRayTaps; ++k) {
    const double along = double(k) / double(kGodRayTaps);
    total += weights[std::size_t(k)] = std::pow(double(decay), k) * (1.0 - along * along);
  }
  std::vector<float> normalised(weights.size());
  for (std::size_t k = 0; k < weights.size(); ++k) normalised[k] = float(weights[k] / total);
  return normalised;
}

HdrImage radialBlur(const HdrImage& polar, std::span<const float> weights) {
  HdrImage blurred = blankImage({polar.width, polar.height});
  for (std::uint32_t j = 0; j < polar.height; ++j)
    for (std::uint32_t i = 0; i < polar.width; ++i) {
      glm::dvec4 sum(0.0);
      for (std::size_t k = 0; k < weights.size() && long(j) - long(k) * kGodRayStep >= 0; ++k)
        sum += double(weights[k]) * glm::dvec4(polar.at(i, std::uint32_t(long(j) - long(k) * kGodRayStep)));
      blurred.texels[std::size_t(j) * polar.width + i] = glm::vec4(sum);
    }
  return blurred;
}

HdrImage godRaysReference(const HdrImage& quarter, glm::vec2 centre, float threshold, float decay) {
  const glm::uvec2 size(quarter.width, quarter.height);
  const HdrImage polar = toPolar(godRayBright(quarter, threshold), centre, godRayPolarExtent(size, centre));
  return fromPolar(radialBlur(polar, godRayWeights(decay)), centre, size);
}

}  // namespace mane::render
