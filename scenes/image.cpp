#include "scenes/image.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "scenes/detail/file_bytes.hpp"
#include "stb_image.h"

namespace mane::scenes {
namespace {

// Larger than any texture we ship (4096 x 4096) with room to spare; a header claiming more
// would make stb_image allocate and clear gigabytes for a file of a few bytes (found by
// tests/fuzz/fuzz_image: a 110-byte GIF declaring 20050 x 18261 pixels).
constexpr int kMaxImageSide = 16384;                  // Vulkan's usual maxImageDimension2D
constexpr long long kMaxImagePixels = 8192LL * 8192;  // 256 MiB of RGBA8

/// What is wrong with a binary PGM/PPM ("P5"/"P6", the kinds stb_image reads) that stb_image
/// 2.27 would not say (both fixed upstream in 2.28); nothing for a sound one or another format:
/// - a header number too large for an int, which it sums digit by digit in an int (undefined
///   behaviour past 2147483647);
/// - a file shorter than the pixels its header declares, whose missing pixels it leaves as
///   whatever its fresh allocation held.
/// The header is read the way stb_image reads it: whitespace and '#' comments, then digits, and
/// the pixels start after the one character that ends the maximum value.
std::optional<std::string> pnmProblem(std::span<const unsigned char> bytes) {
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '6')) return std::nullopt;
  std::size_t at = 2;
  const auto isSpace = [](unsigned char c) { return c == ' ' || (c >= '\t' && c <= '\r'); };  // \t \n \v \f \r
  const auto isDigit = [](unsigned char c) { return c >= '0' && c <= '9'; };
  std::uint64_t numbers[3] = {};
  const char* names[3] = {"width", "height", "maximum value"};
  for (int n = 0; n < 3; ++n) {
    for (;;) {
      while (at < bytes.size() && isSpace(bytes[at])) ++at;
      if (at == bytes.size() || bytes[at] != '#') break;
      while (at < bytes.size() && bytes[at] != '\n' && bytes[at] != '\r') ++at;
    }
    std::string digits;
    for (; at < bytes.size() && isDigit(bytes[at]); ++at)
      if (!digits.empty() || bytes[at] != '0') digits += static_cast<char>(bytes[at]);  // leading zeros add nothing
    if (digits.size() > 10 || (digits.size() == 10 && digits > "2147483647"))
      return "the PNM header's " + std::string(names[n]) + " " +
             (digits.size() > 20 ? digits.substr(0, 20) + "…" : digits) + " is too large (at most 2147483647)";
    numbers[n] = digits.empty() ? 0 : std::stoull(digits);
  }
  const std::uint64_t sampleBytes = numbers[2] > 255 ? 2 : 1;
  const std::uint64_t pixelBytes = (bytes[1] == '6' ? 3 : 1) * sampleBytes;
  const std::uint64_t start = at + 1;
  // Each number is below 2^31, so the pixel count fits; one past 2^56 needs more bytes than any file has.
  const std::uint64_t pixels = numbers[0] * numbers[1];
  const std::uint64_t needed = pixels >> 56 ? UINT64_MAX : start + pixels * pixelBytes;
  if (numbers[2] > 65535 || bytes.size() >= needed) return std::nullopt;  // stb_image refuses the first itself
  return "truncated PNM: its header declares " + std::to_string(numbers[0]) + " x " + std::to_string(numbers[1]) +
         " pixels of " + std::to_string(pixelBytes) + (pixelBytes == 1 ? " byte" : " bytes") + " from byte " +
         std::to_string(start) + ", which need " + std::to_string(needed) + " bytes, but the file has " +
         std::to_string(bytes.size());
}

/// Whether `bytes` are too few for the TGA image their header declares (stb_image reads past the
/// end of a TGA file as zeros, so a few bytes declaring thousands of pixels on a side decoded
/// into a black image, slowly). The bound is exact for uncompressed data; run-length-encoded
/// data needs at least one packet byte and one pixel per 128 pixels. Describes the shortfall, or
/// nothing for a complete TGA and for any other file (none of stb_image's other formats has a
/// second byte of 0 or 1, TGA's colour-map type).
std::optional<std::string> truncatedTga(std::span<const unsigned char> bytes) {
  if (bytes.size() < 18 || bytes[1] > 1) return std::nullopt;
  const auto u16 = [&](std::size_t at) { return std::uint64_t{bytes[at]} | std::uint64_t{bytes[at + 1]} << 8; };
  const unsigned type = bytes[2];
  const bool runLength = type >= 8;
  if (type % 8 < 1 || type % 8 > 3 || type > 11) return std::nullopt;
  const std::uint64_t width = u16(12);
  const std::uint64_t height = u16(14);
  const std::uint64_t pixelBytes = (std::uint64_t{bytes[16]} + 7) / 8;
  std::uint64_t needed = 18 + std::uint64_t{bytes[0]};  // header and image id
  // The colour map, as stb_image skips to it and reads it.
  if (bytes[1] == 1) needed += u16(3) + u16(5) * ((std::uint64_t{bytes[7]} + 7) / 8);
  needed += runLength ? (width * height + 127) / 128 * (1 + pixelBytes) : width * height * pixelBytes;
  if (width == 0 || height == 0 || bytes.size() >= needed) return std::nullopt;
  return "its header declares " + std::to_string(width) + " x " + std::to_string(height) + " pixels of " +
         std::to_string(pixelBytes) + (pixelBytes == 1 ? " byte" : " bytes") +
         (runLength ? " run-length encoded" : "") + ", which need at least " + std::to_string(needed) +
         " bytes, but the file has " + std::to_string(bytes.size());
}

/// Readies a PNG for stb_image 2.27, guarding it in two places (both fixed upstream in 2.28):
/// - a chunk declaring more data than the file holds, for which it allocates before reading (a
///   few bytes declaring 1 GiB of IDAT took 2 GiB): refused, naming the chunk; such a file never
///   decoded anyway;
/// - empty IDAT chunks, which carry nothing, but a first one it copied into its not yet
///   allocated buffer, memcpy(nullptr, …, 0), undefined behaviour: removed.
/// Chunks are read up to IEND, as stb_image reads them; anything but a PNG is left as it is.
std::optional<std::string> preparePng(std::vector<unsigned char>& bytes) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin())) return std::nullopt;
  const auto typeIs = [&](std::size_t at, const char* type) {
    return std::equal(bytes.begin() + static_cast<std::ptrdiff_t>(at + 4),
                      bytes.begin() + static_cast<std::ptrdiff_t>(at + 8), type);
  };
  std::vector<std::size_t> empty;  // offsets of empty IDAT chunks
  // A chunk is its length, type, data and CRC; stb_image reads a last one whose CRC is cut off.
  for (std::size_t at = 8; bytes.size() - at >= 8 && !typeIs(at, "IEND");) {
    const std::uint64_t length = std::uint64_t{bytes[at]} << 24 | std::uint64_t{bytes[at + 1]} << 16 |
                                 std::uint64_t{bytes[at + 2]} << 8 | bytes[at + 3];  // big-endian
    if (length > bytes.size() - at - 8) {
      std::string type;
      for (std::size_t i = at + 4; i < at + 8; ++i)
        type += bytes[i] >= 0x20 && bytes[i] < 0x7f ? static_cast<char>(bytes[i]) : '?';
      return "truncated PNG: its \"" + type + "\" chunk at byte " + std::to_string(at) + " declares " +
             std::to_string(length) + " bytes of data, but only " + std::to_string(bytes.size() - at - 8) + " follow";
    }
    if (length == 0 && typeIs(at, "IDAT")) empty.push_back(at);
    at += std::min<std::uint64_t>(12 + length, bytes.size() - at);
  }
  for (auto at = empty.rbegin(); at != empty.rend(); ++at) {
    const auto chunk = bytes.begin() + static_cast<std::ptrdiff_t>(*at);
    bytes.erase(chunk, chunk + static_cast<std::ptrdiff_t>(std::min<std::size_t>(12, bytes.size() - *at)));
  }
  return std::nullopt;
}

}  // namespace

Result<Image> loadImage(const std::filesystem::path& file) {
  const std::string name = file.string();
  // Decoded from memory: stb_image reading a file calls fread for every byte it asks for past
  // the end, so a truncated file declaring a large image took seconds to decode into zeros.
  auto read = detail::readFileBytes(file);
  if (!read) return std::unexpected(read.error());
  std::vector<unsigned char>& bytes = *read;
  if (auto problem = preparePng(bytes)) return fail(name + ": cannot decode image: " + *problem);
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    return fail(name + ": cannot decode image: the file is over 2 GiB");
  const int size = static_cast<int>(bytes.size());
  if (auto problem = pnmProblem(bytes)) return fail(name + ": cannot decode image: " + *problem);
  if (auto shortfall = truncatedTga(bytes)) return fail(name + ": cannot decode image: truncated TGA: " + *shortfall);
  int width = 0;
  int height = 0;
  int channels = 0;
  // Only the header: an unreadable one falls through to stbi_load, which gives the reason.
  if (stbi_info_from_memory(bytes.data(), size, &width, &height, &channels) != 0 &&
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
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), size, &width, &height, &channels, 0), &stbi_image_free);
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
