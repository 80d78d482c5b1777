#include "tests/support/image_compare.hpp"

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "render/png.hpp"
#include "stb_image.h"

namespace mane::testing {

Comparison compareImages(const ImageView& actual, const ImageView& expected, const Tolerance& tolerance,
                         const std::filesystem::path& diffPath) {
  Comparison result;
  if (actual.width != expected.width || actual.height != expected.height) {
    result.message = "size " + std::to_string(actual.width) + "x" + std::to_string(actual.height) + " differs from " +
                     std::to_string(expected.width) + "x" + std::to_string(expected.height);
    return result;
  }
  result.totalPixels = std::size_t(actual.width) * actual.height;
  std::vector<std::uint8_t> diff(result.totalPixels * 4);
  for (std::size_t pixel = 0; pixel < result.totalPixels; ++pixel) {
    int largest = 0;
    for (int channel = 0; channel < 4; ++channel)
      largest =
          std::max(largest, std::abs(int(actual.rgba[pixel * 4 + channel]) - int(expected.rgba[pixel * 4 + channel])));
    result.largestDifference = std::max(result.largestDifference, largest);
    const bool fails = largest > tolerance.maxChannelDifference;
    result.failingPixels += fails;
    const auto grey = static_cast<std::uint8_t>(actual.rgba[pixel * 4 + 1] / 4);
    diff[pixel * 4 + 0] = fails ? 255 : grey;
    diff[pixel * 4 + 1] = fails ? 0 : grey;
    diff[pixel * 4 + 2] = fails ? 0 : grey;
    diff[pixel * 4 + 3] = 255;
  }
  const double fraction = double(result.failingPixels) / double(result.totalPixels);
  result.passed = fraction <= tolerance.maxFailingFraction;
  if (!result.passed) {
    result.message = std::to_string(result.failingPixels) + " of " + std::to_string(result.totalPixels) +
                     " pixels differ by more than " + std::to_string(tolerance.maxChannelDifference) + " (largest " +
                     std::to_string(result.largestDifference) + ")";
    if (render::writePng(diffPath, actual.width, actual.height, diff)) result.message += "; diff: " + diffPath.string();
  }
  return result;
}

Comparison compareWithGolden(const std::string& name, const ImageView& actual, const Tolerance& tolerance) {
  const std::filesystem::path golden = std::filesystem::path(MANE_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
  const std::filesystem::path outDir = std::filesystem::current_path() / "golden-diff";
  if (std::getenv("MANE_UPDATE_GOLDEN")) {
    Comparison written;
    written.passed = render::writePng(golden, actual.width, actual.height, actual.rgba).has_value();
    written.message = written.passed ? "wrote " + golden.string() : "could not write " + golden.string();
    return written;
  }
  int width = 0, height = 0, channels = 0;
  std::uint8_t* pixels = stbi_load(golden.c_str(), &width, &height, &channels, 4);
  if (!pixels) {
    Comparison missing;
    missing.message = golden.string() + ": cannot read the golden image (" + stbi_failure_reason() +
                      "); regenerate with MANE_UPDATE_GOLDEN=1";
    return missing;
  }
  const std::vector<std::uint8_t> expected(pixels, pixels + std::size_t(width) * height * 4);
  stbi_image_free(pixels);
  Comparison result = compareImages(actual, {std::uint32_t(width), std::uint32_t(height), expected}, tolerance,
                                    outDir / (name + ".diff.png"));
  if (!result.passed) (void)render::writePng(outDir / (name + ".actual.png"), actual.width, actual.height, actual.rgba);
  return result;
}

}  // namespace mane::testing
