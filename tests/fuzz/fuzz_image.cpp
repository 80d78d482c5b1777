// libFuzzer harness: bytes → a scratch file → loadImage (stb_image: PNG, JPEG, BMP, GIF,
// TGA, PSD, HDR, PIC, PNM). Must return an image or an error, never crash, hang or leak; an
// image it returns must hold width * height * 4 bytes.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scenes/image.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mane::fuzz::InputFile file("input.png");
  auto image = mane::scenes::loadImage(file.write(data, size));
  if (image &&
      (image->width <= 0 || image->height <= 0 ||
       image->rgba.size() != static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height) * 4)) {
    std::abort();
  }
  return 0;
}
