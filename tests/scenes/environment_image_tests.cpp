// Radiance and OpenEXR panoramas: the shared assets, a hand-written file whose RGBE values fix the
// decoded radiance, a shared panorama written as OpenEXR, the repair of OpenEXR's flawed values,
// and the errors of files that are not panoramas.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/gtc/packing.hpp>

#include "render/environment/sun_extraction.hpp"
#include "render/exr.hpp"
#include "scenes/environment_image.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

// A flat (not run-length encoded) RGBE file: scanlines narrower than 8 pixels are always flat.
std::string rgbeFile(int width, int height, unsigned char r, unsigned char g, unsigned char b, unsigned char e) {
  std::string bytes =
      "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
  for (int i = 0; i < width * height; ++i) bytes += {char(r), char(g), char(b), char(e)};
  return bytes;
}

// A run-length encoded file, 8 pixels wide: each scanline's four channels as one run each.
std::string runLengthFile(int height, const std::string& channelRuns) {
  std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X 8\n";
  for (int row = 0; row < height; ++row) bytes += std::string("\x02\x02\x00\x08", 4) + channelRuns;
  return bytes;
}
const std::string kEightOfEach("\x88\x80\x88\x40\x88\x20\x88\x81", 8);  // runs of 8: 128, 64, 32, 129

TEST(EnvironmentImage, LoadsTheSharedPanoramasAsFiniteRadiance) {
  for (const char* name : {"env/venice_sunset_1k.hdr", "env/royal_esplanade_1k.hdr"}) {
    SCOPED_TRACE(name);
    MANE_RESOLVE_OR_SKIP(file, name);
    auto image = loadEnvironmentImage(file);
    ASSERT_TRUE(image.has_value()) << image.error().message;
    EXPECT_EQ(image->image.width, 1024);  // the assets README: 1k panoramas, 2:1
    EXPECT_EQ(image->image.height, 512);
    float brightest = 0.0f;
    double sum = 0.0;
    for (const glm::vec3& texel : image->image.texels) {
      ASSERT_TRUE(std::isfinite(texel.x) && std::isfinite(texel.y) && std::isfinite(texel.z));
      ASSERT_GE(std::min({texel.x, texel.y, texel.z}), 0.0f);
      brightest = std::max(brightest, texel.y);
      sum += texel.y;
    }
    // High dynamic range: the brightest texel (a sun or a lamp) far above the average.
    EXPECT_GT(brightest, 20.0 * sum / double(image->image.texels.size()));
  }
}

TEST(EnvironmentImage, DecodesRgbeAsMantissaTimesTwoToTheExponent) {
  // (128, 64, 32) with exponent 129: 128/256 × 2^(129 − 128) = 1, then 0.5 and 0.25 (Ward's RGBE;
  // stb_image leaves out his half-step, within 0.4 %).
  testing::ScratchDir dir;
  auto image = loadEnvironmentImage(dir.write("flat.hdr", rgbeFile(4, 2, 128, 64, 32, 129)));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  ASSERT_EQ(image->image.texels.size(), 8u);
  for (const glm::vec3& texel : image->image.texels) {
    EXPECT_NEAR(texel.x, 1.0f, 0.004f);
    EXPECT_NEAR(texel.y, 0.5f, 0.002f);
    EXPECT_NEAR(texel.z, 0.25f, 0.001f);
  }
}

TEST(EnvironmentImage, DecodesRunLengthScanlines) {
  testing::ScratchDir dir;
  auto image = loadEnvironmentImage(dir.write("runs.hdr", runLengthFile(4, kEightOfEach)));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  ASSERT_EQ(image->image.texels.size(), 32u);
  for (const glm::vec3& texel : image->image.texels) EXPECT_NEAR(texel.y, 0.5f, 0.002f);
}

// stb_image 2.27 reads a run-length count of zero for ever, and the zeros past a file's end as
// such counts: both hung the loader until it checked them.
TEST(EnvironmentImage, AZeroRunLengthOrAFileCutShortIsAnErrorNotAHang) {
  testing::ScratchDir dir;
  // Found by tests/fuzz/fuzz_environment: stb_image reads sizes as strtol does, white space and
  // all ("-Y  3+X 8"), and the loader's own walk must read them alike to see the zero.
  const std::string spaced = std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y  3+X 8\n") +
                             std::string("\x02\x02\x00\x08\x88\x80\x85\x04\x01\xc6\x02", 11);
  auto hang = loadEnvironmentImage(dir.write("spaced.hdr", spaced));
  ASSERT_FALSE(hang.has_value());
  EXPECT_NE(hang.error().message.find("spaced.hdr: cannot decode the panorama:"), std::string::npos)
      << hang.error().message;
  // And its header ends at a line that a NUL starts, as a C string reads it.
  const std::string nul = std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\0\0\0\n-Y 4+X 8\xa2\x32@ \n", 51) +
                          std::string("\x02\x02\x00\x08", 4);
  hang = loadEnvironmentImage(dir.write("nul.hdr", nul));
  ASSERT_FALSE(hang.has_value());
  EXPECT_NE(hang.error().message.find("nul.hdr: cannot decode the panorama: the file is cut short at scanline 0"),
            std::string::npos)
      << hang.error().message;
  std::string zero = kEightOfEach;
  zero[2] = 0;
  auto image = loadEnvironmentImage(dir.write("zero.hdr", runLengthFile(4, zero)));
  ASSERT_FALSE(image.has_value());
  EXPECT_NE(
      image.error().message.find("zero.hdr: cannot decode the panorama: scanline 0 holds a run-length count of zero"),
      std::string::npos)
      << image.error().message;
  const std::string whole = runLengthFile(4, kEightOfEach);
  image = loadEnvironmentImage(dir.write("short.hdr", whole.substr(0, whole.size() - 3)));
  ASSERT_FALSE(image.has_value());
  EXPECT_NE(image.error().message.find("short.hdr: cannot decode the panorama: the file is cut short at scanline 3"),
            std::string::npos)
      << image.error().message;
  const std::string flat = rgbeFile(4, 2, 128, 64, 32, 129);
  image = loadEnvironmentImage(dir.write("flat_short.hdr", flat.substr(0, flat.size() - 1)));
  ASSERT_FALSE(image.has_value());
  EXPECT_NE(image.error().message.find("cut short: 31 bytes of pixels, 32 needed"), std::string::npos)
      << image.error().message;
}

// Found by tests/fuzz/fuzz_environment: RGBE reaches 1.7e38, and four such texels overflowed
// the panorama's resampling into a cube map.
TEST(EnvironmentImage, RadianceBeyondFloatsReachIsClampedAndCounted) {
  testing::ScratchDir dir;
  auto image = loadEnvironmentImage(dir.write("bright.hdr", rgbeFile(4, 2, 255, 255, 255, 255)));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  EXPECT_EQ(image->clampedTexels, 8u);
  for (const glm::vec3& texel : image->image.texels) EXPECT_EQ(texel, glm::vec3(kMaxPanoramaRadiance));
}

// The Venice panorama's sun, cut out of it: low over the horizon (its brightest texel is 3° up)
// and the warm light of a sunset.
TEST(EnvironmentImage, TheVenicePanoramasSunIsCutOutAsAWarmLowLight) {
  MANE_RESOLVE_OR_SKIP(file, "env/venice_sunset_1k.hdr");
  auto panorama = loadEnvironmentImage(file);
  ASSERT_TRUE(panorama.has_value()) << panorama.error().message;
  const render::SunExtraction cut = render::extractSun(render::cubeFromEquirect(panorama->image, 256));
  ASSERT_TRUE(cut.sun.has_value());
  const double elevation = glm::degrees(std::asin(double(cut.sun->direction.y)));
  EXPECT_GT(elevation, 0.0);
  EXPECT_LT(elevation, 8.0);
  EXPECT_GT(cut.sun->color.r, cut.sun->color.g);
  EXPECT_GT(cut.sun->color.g, cut.sun->color.b);
}

// The OpenEXR path against the Radiance one: a shared panorama written as fp16 OpenEXR reads back
// as its own texels rounded to fp16.
TEST(EnvironmentImage, APanoramaReadsTheSameFromOpenExr) {
  MANE_RESOLVE_OR_SKIP(file, "env/venice_sunset_1k.hdr");
  auto radiance = loadEnvironmentImage(file);
  ASSERT_TRUE(radiance.has_value()) << radiance.error().message;
  const render::EquirectImage& source = radiance->image;
  std::vector<std::uint16_t> halves;
  for (const glm::vec3& texel : source.texels)
    for (const float value : {texel.r, texel.g, texel.b, 1.0f}) halves.push_back(glm::packHalf1x16(value));
  testing::ScratchDir dir;
  ASSERT_TRUE(render::writeExr(dir.path() / "venice.exr", source.width, source.height, halves).has_value());
  auto exr = loadEnvironmentImage(dir.path() / "venice.exr");
  ASSERT_TRUE(exr.has_value()) << exr.error().message;
  ASSERT_EQ(exr->image.width, source.width);
  ASSERT_EQ(exr->image.height, source.height);
  EXPECT_EQ(exr->clampedTexels + exr->zeroedTexels, 0u);
  for (std::size_t i = 0; i < source.texels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(exr->image.texels[i][c], glm::unpackHalf1x16(halves[4 * i + std::size_t(c)])) << i << ", " << c;
}

// OpenEXR holds what RGBE cannot: negative values, NaN and infinity. The first two become 0, the
// last the brightest radiance kept, and each texel is counted.
TEST(EnvironmentImage, NegativeAndNotANumberTexelsAreZeroedAndInfinityClamped) {
  const std::uint16_t one = 0x3c00, minusOne = 0xbc00, nan = 0x7e00, infinity = 0x7c00;
  std::vector<std::uint16_t> halves;
  for (int i = 0; i < 8; ++i) {
    const std::uint16_t red = i == 1 ? minusOne : i == 2 ? nan : i == 3 ? infinity : one;
    halves.insert(halves.end(), {red, one, i == 4 ? nan : one, one});
  }
  testing::ScratchDir dir;
  ASSERT_TRUE(render::writeExr(dir.path() / "flawed.exr", 4, 2, halves).has_value());
  auto image = loadEnvironmentImage(dir.path() / "flawed.exr");
  ASSERT_TRUE(image.has_value()) << image.error().message;
  EXPECT_EQ(image->zeroedTexels, 3u);
  EXPECT_EQ(image->clampedTexels, 1u);
  EXPECT_EQ(image->image.texels[1], glm::vec3(0.0f, 1.0f, 1.0f));
  EXPECT_EQ(image->image.texels[2], glm::vec3(0.0f, 1.0f, 1.0f));
  EXPECT_EQ(image->image.texels[3], glm::vec3(kMaxPanoramaRadiance, 1.0f, 1.0f));
  EXPECT_EQ(image->image.texels[4], glm::vec3(1.0f, 1.0f, 0.0f));
  EXPECT_EQ(image->image.texels[5], glm::vec3(1.0f));
}

TEST(EnvironmentImage, FilesThatAreNotPanoramasGiveClearErrors) {
  testing::ScratchDir dir;
  const auto message = [&](const std::string& name, const std::string& bytes) {
    auto image = loadEnvironmentImage(dir.write(name, bytes));
    return image ? std::string("loaded") : image.error().message;
  };
  EXPECT_NE(message("photo.hdr", "\x89PNG\r\n").find("photo.hdr: not a Radiance HDR or OpenEXR file"),
            std::string::npos);
  EXPECT_NE(message("cut.exr", std::string("\x76\x2f\x31\x01\x02\x00\x00\x00channels", 16))
                .find("cut.exr: cannot decode the OpenEXR file: "),
            std::string::npos);
  EXPECT_NE(message("square.hdr", rgbeFile(4, 4, 1, 1, 1, 128)).find("twice as wide as it is high"), std::string::npos);
  EXPECT_NE(message("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 50000 +X 100000\n").find("too large"),
            std::string::npos);
  // Found by tests/fuzz/fuzz_environment: sizes beyond an int, which stb_image reads wrapped.
  EXPECT_NE(message("wrapped.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1999499999 +X 999999499999\n")
                .find("wrapped.hdr: cannot decode the panorama: the panorama is too large: 999999499999 x 1999499999"),
            std::string::npos);
  EXPECT_NE(
      message("format.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 4\n").find("format.hdr: cannot decode"),
      std::string::npos);
  EXPECT_NE(loadEnvironmentImage(dir.path() / "missing.hdr").error().message.find("not found"), std::string::npos);
}

}  // namespace
}  // namespace mane::scenes
