#include "scenes/image.hpp"

#include <memory>
#include <string>

#include "stb_image.h"

namespace mane::scenes {
namespace {

// Larger than any texture we ship (4096 x 4096) with room to spare; a header claiming more
// would make stb_image allocate and clear gigabytes for a file of a few bytes (found by
// tests/fuzz/fuzz_image: a 110-byte GIF declaring 20050 x 18261 pixels).
constexpr int kMaxImageSide = 16384;                  // Vulkan's usual maxImageDimension2D
constexpr long long kMaxImagePixels = 8192LL * 8192;  // 256 MiB of RGBA8

}  // namespace

Result<Image> loadImage(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return fail(name + ": file not found");
  int width = 0;
  int height = 0;
  int channels = 0;
  // Only the header: an unreadable one falls through to stbi_load, which gives the reason.
  if (stbi_info(name.c_str(), &width, &height, &channels) != 0 &&
      (width > kMaxImageSide || height > kMaxImageSide || static_cast<long long>(width) * height > kMaxImagePixels)) {
    return fail(name + ": image too large: " + std::to_string(width) + " x " + std::to_string(height) +
                " pixels (at most " + std::to_string(kMaxImageSide) + " on a side and " +
                std::to_string(kMaxImagePixels) + " in all)");
  }
  // Decode to the file's own channel count and expand to RGBA below: asking stb_image 2.27
  // for 4 channels converts 16-bit PNM data with its 8-bit converter and then reads past
  // the buffer (found by tests/fuzz/fuzz_image; fixed upstream in 2.28).
  // stbi_load is reentrant apart from its failure-reason string, which is per thread only
  // with STBI_THREAD_LOCAL; good enough for a message.
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(name.c_str(), &width, &height, &channels, 0),
                                                   &stbi_image_free);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    return fail(name + ": cannot decode image: " + (reason ? reason : "unknown error"));
  }
  // stb_image accepts some headers with a zero dimension (a PNM "P6 2 <junk>" reads as
  // 2 x 0) and returns a valid but empty buffer.
  if (width <= 0 || height <= 0) {
    return fail(name + ": cannot decode image: it has no pixels (" + std::to_string(width) + " x " +
                std::to_string(height) + ")");
  }
  if (channels < 1 || channels > 4) {
    return fail(name + ": cannot decode image: unsupported channel count " + std::to_string(channels));
  }
  Image image;
  image.width = width;
  image.height = height;
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  image.rgba.resize(count * 4);
  const stbi_uc* in = pixels.get();
  std::uint8_t* out = image.rgba.data();
  // Same expansion as stb_image's own: grey → (g, g, g), missing alpha → 255.
  for (std::size_t i = 0; i < count; ++i, in += channels, out += 4) {
    switch (channels) {
      case 1:
        out[0] = out[1] = out[2] = in[0];
        out[3] = 255;
        break;
      case 2:
        out[0] = out[1] = out[2] = in[0];
        out[3] = in[1];
        break;
      case 3:
        out[0] = in[0];
        out[1] = in[1];
        out[2] = in[2];
        out[3] = 255;
        break;
      default:
        out[0] = in[0];
        out[1] = in[1];
        out[2] = in[2];
        out[3] = in[3];
        break;
    }
  }
  return image;
}

}  // namespace mane::scenes
