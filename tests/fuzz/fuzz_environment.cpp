// libFuzzer harness: bytes → a scratch file → loadEnvironmentImage (Radiance RGBE through
// stb_image, after the loader's own checks of the scanlines). Must return a panorama or an error,
// never crash, hang or leak; a panorama it returns must hold width × height non-negative texels no
// brighter than kMaxPanoramaRadiance, twice as wide as high within a pixel.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scenes/environment_image.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mane::fuzz::InputFile file("input.hdr");
  auto image = mane::scenes::loadEnvironmentImage(file.write(data, size));
  if (!image) return 0;
  const mane::render::EquirectImage& panorama = image->image;
  if (panorama.width <= 0 || panorama.height <= 0 || std::abs(panorama.width - 2 * panorama.height) > 1 ||
      panorama.texels.size() != static_cast<std::size_t>(panorama.width) * static_cast<std::size_t>(panorama.height))
    std::abort();
  constexpr float kMax = mane::scenes::kMaxPanoramaRadiance;
  for (const auto& texel : panorama.texels)
    for (int c = 0; c < 3; ++c)
      if (!(texel[c] >= 0.0f && texel[c] <= kMax)) std::abort();
  return 0;
}
