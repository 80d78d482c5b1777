#pragma once
// Golden-image comparison (Filament renderdiff style): a per-channel tolerance and the fraction
// of pixels allowed over it. On failure the difference image is written beside the build so a
// person can look at it.
//
// Regenerate goldens:  MANE_UPDATE_GOLDEN=1 ctest --preset release -L golden
// (writes tests/golden/<name>.png from the current render; review the images before committing).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace mane::testing {

struct ImageView {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::span<const std::uint8_t> rgba;
};

struct Tolerance {
  int maxChannelDifference = 8;      ///< in 8-bit steps
  double maxFailingFraction = 0.01;  ///< of all pixels
};

struct Comparison {
  bool passed = false;
  int largestDifference = 0;
  std::size_t failingPixels = 0;
  std::size_t totalPixels = 0;
  std::string message;  ///< why it failed, and where the difference image is
};

/// Compares two images; on failure writes `diffPath` (red where a pixel fails, grey elsewhere).
Comparison compareImages(const ImageView& actual, const ImageView& expected, const Tolerance& tolerance,
                         const std::filesystem::path& diffPath);

/// Compares `actual` with tests/golden/<name>.png, or writes that file when MANE_UPDATE_GOLDEN
/// is set. The diff and the actual image go to <build>/golden-diff/<name>.{diff,actual}.png.
Comparison compareWithGolden(const std::string& name, const ImageView& actual, const Tolerance& tolerance);

}  // namespace mane::testing
