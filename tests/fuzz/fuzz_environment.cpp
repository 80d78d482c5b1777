// libFuzzer harness: bytes → a scratch file → loadEnvironmentImage (Radiance RGBE through
// stb_image, after the loader's own checks of the scanlines). Must return a panorama or an error,
// never crash, hang or leak; a panorama it returns must hold width × height finite, non-negative
// texels, twice as wide as high within a pixel.

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
  if (image->width <= 0 || image->height <= 0 || std::abs(image->width - 2 * image->height) > 1 ||
      image->texels.size() != static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height))
    std::abort();
  for (const auto& texel : image->texels)
    if (!(texel.x >= 0.0f && texel.y >= 0.0f && texel.z >= 0.0f && std::isfinite(texel.x + texel.y + texel.z)))
      std::abort();
  return 0;
}
