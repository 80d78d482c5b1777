#include "scenes/environment_image.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/common.hpp>

#include "render/exr.hpp"
#include "scenes/detail/file_bytes.hpp"
#include "stb_image.h"

namespace mane::scenes {
namespace {

// The same limits as OpenEXR panoramas'.
constexpr int kMaxSide = render::kMaxExrSide;
constexpr long long kMaxPixels = render::kMaxExrPixels;

/// The next header line from `at` as stb_image 2.27 reads it (stbi__hdr_gettoken): up to a
/// newline, at most 1023 bytes (the rest of a longer line skipped), the file's last byte left out
/// where no newline ends it, and cut at a NUL as a C string is. Moves `at` past the newline.
std::string headerLine(std::string_view bytes, std::size_t& at) {
  constexpr std::size_t kLongest = 1023;
  const auto end = [&] { return at >= bytes.size(); };
  const auto next = [&] { return end() ? '\0' : bytes[at++]; };
  std::string line;
  for (char c = next(); !end() && c != '\n'; c = next()) {
    line.push_back(c);
    if (line.size() == kLongest) {
      while (!end() && next() != '\n') {
      }
      break;
    }
  }
  return line.substr(0, line.find('\0'));
}

/// A number as strtol reads it: white space, a sign, decimal digits; none without a digit.
/// Magnitudes stop growing at 1e15, far past any size a panorama may have.
std::optional<long long> readNumber(std::string_view text, std::size_t& at) {
  constexpr long long kHuge = 1'000'000'000'000'000LL;
  while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
  bool negative = false;
  if (at < text.size() && (text[at] == '+' || text[at] == '-')) negative = text[at++] == '-';
  const std::size_t first = at;
  long long value = 0;
  for (; at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])); ++at)
    value = std::min(value * 10 + (text[at] - '0'), kHuge);
  if (at == first) return std::nullopt;
  return negative ? -value : value;
}

/// What is wrong with the pixels of a Radiance file that stb_image 2.27 would not say: a
/// run-length count of zero, which it reads for ever (as it reads the zeros past a file's end), and
/// scanlines cut short, whose missing pixels it leaves unset. Nothing for a sound file, or for a
/// header it refuses itself. Scanlines are walked as it walks them: run-length encoded (a 2, 2,
/// width header, then each channel's runs and dumps) where the image is 8 to 32767 pixels wide and
/// the first scanline says so, flat RGBE otherwise.
std::optional<std::string> rgbeProblem(std::string_view bytes) {
  // The header, read as stb_image reads it: the magic line, lines up to an empty one (one of them
  // the format), then the resolution.
  std::size_t at = 0;
  const std::string magic = headerLine(bytes, at);
  if (magic != "#?RADIANCE" && magic != "#?RGBE") return std::nullopt;
  bool rgbe = false;
  for (std::string line = headerLine(bytes, at); !line.empty(); line = headerLine(bytes, at))
    rgbe = rgbe || line == "FORMAT=32-bit_rle_rgbe";
  if (!rgbe) return std::nullopt;
  const std::string line = headerLine(bytes, at);
  if (!line.starts_with("-Y ")) return std::nullopt;
  std::size_t cursor = 3;
  const std::optional<long long> rows = readNumber(line, cursor);
  while (cursor < line.size() && line[cursor] == ' ') ++cursor;
  if (!rows || line.substr(cursor, 3) != "+X ") return std::nullopt;
  cursor += 3;
  const std::optional<long long> columns = readNumber(line, cursor);
  if (!columns || *columns <= 0 || *rows <= 0) return std::nullopt;
  const long long width = *columns, height = *rows;
  // stb_image reads these numbers into an int; the size check that follows would see them wrapped.
  if (width > kMaxSide || height > kMaxSide || width * height > kMaxPixels)
    return "the panorama is too large: " + std::to_string(width) + " x " + std::to_string(height) +
           " pixels (at most " + std::to_string(kMaxSide) + " on a side and " + std::to_string(kMaxPixels) + " in all)";
  const auto remaining = [&] { return bytes.size() - at; };
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
  const bool runLength = width >= 8 && width < 32768 && remaining() >= 4 && byte(at) == 2 && byte(at + 1) == 2 &&
                         (byte(at + 2) & 0x80) == 0;
  if (!runLength) {
    const long long needed = width * height * 4;
    if (static_cast<long long>(remaining()) < needed)
      return "the file is cut short: " + std::to_string(remaining()) + " bytes of pixels, " + std::to_string(needed) +
             " needed";
    return std::nullopt;
  }
  for (long long row = 0; row < height; ++row) {
    const std::string where = "scanline " + std::to_string(row);
    if (remaining() < 4) return "the file is cut short at " + where;
    if (byte(at) != 2 || byte(at + 1) != 2 || (byte(at + 2) & 0x80) != 0)
      return where + " is not run-length encoded like the first";
    at += 4;  // stb_image checks the width these bytes give
    for (int channel = 0; channel < 4; ++channel) {
      long long left = width;
      while (left > 0) {
        if (remaining() < 1) return "the file is cut short at " + where;
        int count = byte(at++);
        const bool run = count > 128;
        if (run) count -= 128;
        if (count == 0) return where + " holds a run-length count of zero";
        if (count > left) return std::nullopt;  // stb_image says "bad RLE data"
        const std::size_t payload = run ? 1 : static_cast<std::size_t>(count);
        if (remaining() < payload) return "the file is cut short at " + where;
        at += payload;
        left -= count;
      }
    }
  }
  return std::nullopt;
}

bool isExr(std::span<const unsigned char> bytes) {
  return bytes.size() >= 4 && bytes[0] == 0x76 && bytes[1] == 0x2f && bytes[2] == 0x31 && bytes[3] == 0x01;
}

/// stb_image's decoding of a Radiance file: three floats a texel, rows top to bottom.
struct RgbePixels {
  int width = 0;
  int height = 0;
  std::unique_ptr<float, void (*)(void*)> pixels{nullptr, &stbi_image_free};
};

Result<RgbePixels> decodeRgbe(const std::vector<unsigned char>& bytes, const std::string& name) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    return fail(name + ": cannot decode the panorama: the file is over 2 GiB");
  const int size = static_cast<int>(bytes.size());
  if (stbi_is_hdr_from_memory(bytes.data(), size) == 0)
    return fail(name +
                ": not a Radiance HDR or OpenEXR file (it must begin with \"#?RADIANCE\", \"#?RGBE\" or the "
                "bytes 76 2f 31 01)");
  if (auto problem = rgbeProblem(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size())))
    return fail(name + ": cannot decode the panorama: " + *problem);
  RgbePixels rgbe;
  int channels = 0;
  // The header as stb_image reads it, too: a large declared size would otherwise be allocated
  // before the scanlines are found missing.
  if (stbi_info_from_memory(bytes.data(), size, &rgbe.width, &rgbe.height, &channels) != 0 &&
      (rgbe.width > kMaxSide || rgbe.height > kMaxSide ||
       static_cast<long long>(rgbe.width) * rgbe.height > kMaxPixels))
    return fail(name + ": panorama too large: " + std::to_string(rgbe.width) + " x " + std::to_string(rgbe.height) +
                " pixels (at most " + std::to_string(kMaxSide) + " on a side and " + std::to_string(kMaxPixels) +
                " in all)");
  rgbe.pixels.reset(stbi_loadf_from_memory(bytes.data(), size, &rgbe.width, &rgbe.height, &channels, 3));
  if (!rgbe.pixels) {
    const char* reason = stbi_failure_reason();
    return fail(name + ": cannot decode the panorama: " + (reason ? reason : "unknown error"));
  }
  return rgbe;
}

/// The panorama of `width` × `height` texels given by `texel(i)`: checked to be equirectangular,
/// its texels repaired (see Panorama).
template <class Texel>
Result<Panorama> panoramaOf(const std::string& name, int width, int height, Texel texel) {
  if (width <= 0 || height <= 0)
    return fail(name + ": the panorama has no pixels (" + std::to_string(width) + " x " + std::to_string(height) + ")");
  if (std::abs(width - 2 * height) > 1)
    return fail(name + ": the panorama is " + std::to_string(width) + " x " + std::to_string(height) +
                " pixels; an equirectangular one is twice as wide as it is high");
  Panorama panorama{.image = {.width = width, .height = height}};
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  panorama.image.texels.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    glm::vec3 repaired = texel(i);
    bool zeroed = false, clamped = false;
    for (int c = 0; c < 3; ++c) {
      if (!(repaired[c] >= 0.0f)) {  // negative or not a number
        repaired[c] = 0.0f;
        zeroed = true;
      } else if (repaired[c] > kMaxPanoramaRadiance) {
        repaired[c] = kMaxPanoramaRadiance;
        clamped = true;
      }
    }
    panorama.zeroedTexels += zeroed ? 1 : 0;
    panorama.clampedTexels += clamped ? 1 : 0;
    panorama.image.texels[i] = repaired;
  }
  return panorama;
}

}  // namespace

Result<Panorama> loadEnvironmentImage(const std::filesystem::path& file) {
  const std::string name = file.string();
  auto read = detail::readFileBytes(file);
  if (!read) return std::unexpected(read.error());
  const std::vector<unsigned char>& bytes = *read;
  if (isExr(bytes)) {
    auto exr = render::decodeExr(bytes, name);
    if (!exr) return std::unexpected(exr.error());
    return panoramaOf(name, exr->width, exr->height, [&](std::size_t i) { return glm::vec3(exr->texels[i]); });
  }
  auto rgbe = decodeRgbe(bytes, name);
  if (!rgbe) return std::unexpected(rgbe.error());
  const float* texels = rgbe->pixels.get();
  return panoramaOf(name, rgbe->width, rgbe->height,
                    [&](std::size_t i) { return glm::vec3(texels[3 * i], texels[3 * i + 1], texels[3 * i + 2]); });
}

}  // namespace mane::scenes
