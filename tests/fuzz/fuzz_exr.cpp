// libFuzzer harness: bytes → decodeExr (the OpenEXR library reading from memory, after the
// decoder's own checks). Must return an image or an error, never crash, hang or leak; an image it
// returns must hold width × height texels within the size limits.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "render/exr.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto image = mane::render::decodeExr(std::span(data, size), "input.exr");
  if (!image) return 0;
  if (image->width <= 0 || image->height <= 0 || image->width > mane::render::kMaxExrSide ||
      image->height > mane::render::kMaxExrSide ||
      static_cast<long long>(image->width) * image->height > mane::render::kMaxExrPixels ||
      image->texels.size() != static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height))
    std::abort();
  return 0;
}
