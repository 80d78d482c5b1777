#include "scenes/groom_loader.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <span>
#include <string>
#include <type_traits>

#include "scenes/detail/hair_format.hpp"

namespace mane::scenes {
namespace {

// Both formats were written by x86 tools and are read here by reinterpreting bytes.
static_assert(std::endian::native == std::endian::little, "groom files are little-endian; add byte swapping");

// AMD TressFX 3.1 `TressFXFileObject`: version, three counts, a bool padded to 4 bytes and 31
// reserved words put `verticesOffset` at byte 144; 6 offsets and 32 reserved words end it at 296.
constexpr std::uint64_t kTfx3HeaderBytes = 296;
constexpr std::uint64_t kTfx3VertexOffsetField = 144;
constexpr std::uint64_t kTfx3StrandUvField = 148;
constexpr std::uint64_t kTfx3StrandThicknessField = 156;
constexpr std::uint64_t kTfx3VertexBytes = 12;  // float3
// AMD TressFX 4.x `TressFXTFXFileHeader`: version, 2 counts, 5 offsets, 32 reserved words.
constexpr std::uint64_t kTfx4HeaderBytes = 160;
constexpr std::uint64_t kTfx4VertexOffsetField = 12;
constexpr std::uint64_t kTfx4StrandUvField = 16;
constexpr std::uint64_t kTfx4StrandThicknessField = 24;
constexpr std::uint64_t kTfx4VertexBytes = 16;  // float4, w unused here

using detail::kHairColoursBit;
using detail::kHairHeaderBytes;
using detail::kHairPointsBit;
using detail::kHairSegmentsBit;
using detail::kHairThicknessBit;
using detail::kHairTransparencyBit;

std::uint32_t readU32(std::span<const unsigned char> bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;
}

float readF32(std::span<const unsigned char> bytes, std::size_t at) {
  float value = 0.0f;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;
}

std::uint16_t readU16(std::span<const unsigned char> bytes, std::size_t at) {
  std::uint16_t value = 0;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;
}

std::string describe(const glm::vec3& p) {
  // snprintf rather than "(" + std::to_string(…): g++ 12 reports a false -Wrestrict on the
  // latter (GCC bug 105329).
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", static_cast<double>(p.x), static_cast<double>(p.y),
                static_cast<double>(p.z));
  return text;
}

std::string str(std::uint64_t value) {
  return std::to_string(value);
}

/// An open groom file and its size; reads byte ranges already checked against that size.
class GroomFile {
public:
  static Result<GroomFile> open(const std::filesystem::path& path) {
    GroomFile file;
    file.name_ = path.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return fail(file.name_ + ": file not found");
    file.size_ = std::filesystem::file_size(path, ec);
    if (ec) return fail(file.name_ + ": cannot read the file size: " + ec.message());
    file.stream_.open(path, std::ios::binary);
    if (!file.stream_) return fail(file.name_ + ": cannot open the file for reading");
    return file;
  }

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] std::uint64_t size() const { return size_; }

  /// Bytes [offset, offset + count); the caller has checked offset + count ≤ size().
  Result<std::vector<unsigned char>> read(std::uint64_t offset, std::uint64_t count) {
    std::vector<unsigned char> bytes(static_cast<std::size_t>(count));
    stream_.seekg(static_cast<std::streamoff>(offset));
    stream_.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(count));
    if (!stream_ || static_cast<std::uint64_t>(stream_.gcount()) != count)
      return fail(name_ + ": read error at bytes " + str(offset) + "–" + str(offset + count) +
                  " (the file changed while being read?)");
    return bytes;
  }

private:
  std::string name_;
  std::uint64_t size_ = 0;
  std::ifstream stream_;
};

/// Appends one strand of `count` points as stored, the first at `bytes[first]` and each `stride`
/// bytes after it; flaws are left for `finishGroom`.
void addStrand(StrandSet& set, std::span<const unsigned char> bytes, std::size_t first, std::size_t count,
               std::size_t stride) {
  std::vector<glm::vec3> points;
  points.reserve(count);
  for (std::size_t v = 0; v < count; ++v) {
    const std::size_t at = first + v * stride;
    points.emplace_back(readF32(bytes, at), readF32(bytes, at + 4), readF32(bytes, at + 8));
  }
  set.strands.push_back(std::move(points));
}

/// Where a point lies in the file, for messages: "FILE: strand S, vertex V (byte B)".
struct PointLocator {
  const std::string& file;
  const char* pointWord;  ///< how the format calls a point
  std::function<std::uint64_t(std::size_t strand, std::size_t point)> byteOf;

  [[nodiscard]] std::string at(std::size_t strand, std::size_t point) const {
    return file + ": strand " + str(strand) + ", " + pointWord + " " + str(point) + " (byte " +
           str(byteOf(strand, point)) + ")";
  }
};

/// The strict refusal of `repair`, a flaw of `stored` (the strand as read).
std::string strictError(const PointLocator& locate, const StrandRepair& repair, const std::vector<glm::vec3>& stored,
                        std::size_t flawedStrands) {
  const std::string where = locate.at(repair.strand, repair.point);
  const std::string previous = std::string(locate.pointWord) + " " + str(repair.point == 0 ? 0 : repair.point - 1);
  std::string what;
  switch (repair.flaw) {
    case StrandFlaw::kNonFinitePoint:
      what = "position " + describe(stored[repair.point]) + " is not finite (NaN or infinite)";
      break;
    case StrandFlaw::kRepeatedPoint:
      what = "same position " + describe(stored[repair.point]) + " as " + previous + " (zero-length segment)";
      break;
    case StrandFlaw::kZeroLengthSegment:
      what = "position " + describe(stored[repair.point]) + " all but coincides with " + previous +
             " (zero-length segment)";
      break;
    case StrandFlaw::kTooFewPoints:
      what = stored.size() < 2 ? "the strand has " + str(stored.size()) + " " + locate.pointWord +
                                     "; a strand needs at least 2"
                               : "its points coincide or all but coincide (fewer than 2 distinct positions); a strand "
                                 "needs at least 2";
      break;
    case StrandFlaw::kAbsurdLength:
      what = "the strand is absurdly long here (a segment or the strand over " +
             str(static_cast<std::uint64_t>(kAbsurdLengthFactor)) + "× the groom's median)";
      break;
  }
  return where + ": " + what + "; strict loading refuses flawed strands (" + str(flawedStrands) +
         " in this file) rather than repairing or dropping them";
}

/// Repairs the strands as read (groom_repair.hpp), or under `strict` refuses the first flawed one.
Result<StrandSet> finishGroom(StrandSet set, const PointLocator& locate, const GroomLoadOptions& options) {
  std::vector<std::vector<glm::vec3>> stored;
  if (options.strict) stored = set.strands;
  set.repairs = repairStrands(set);
  if (options.strict && !set.repairs.clean()) {
    const StrandRepair& first = set.repairs.repairs.front();
    return fail(strictError(locate, first, stored[first.strand], set.repairs.repairs.size()));
  }
  if (set.strands.empty())
    return fail(locate.file + ": every strand is flawed, none is left to load (" + set.repairs.summary() + ")");
  return set;
}

/// `count` records of `recordBytes` each at the offset stored at `field` of the header, or
/// nothing where that offset is 0 (the array is absent).
Result<std::vector<unsigned char>> readOptionalArray(GroomFile& file, std::span<const unsigned char> head,
                                                     std::uint64_t field, std::uint64_t headerBytes,
                                                     std::uint64_t count, std::uint64_t recordBytes, const char* what) {
  const std::uint32_t offset = readU32(head, static_cast<std::size_t>(field));
  if (offset == 0) return std::vector<unsigned char>{};
  const std::string& name = file.name();
  if (offset < headerBytes)
    return fail(name + ": the " + what + " array offset " + str(offset) + " (byte " + str(field) +
                ") points into the " + str(headerBytes) + "-byte header");
  if (offset > file.size() || count > (file.size() - offset) / recordBytes)
    return fail(name + ": the " + what + " array (" + str(count) + " × " + str(recordBytes) + " bytes from byte " +
                str(offset) + ", offset at byte " + str(field) + ") runs past the end of the file (" +
                str(file.size()) + " bytes): truncated, or the offset is corrupt");
  return file.read(offset, count * recordBytes);
}

std::string lowerExtension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

std::size_t StrandSet::pointCount() const {
  std::size_t count = 0;
  for (const std::vector<glm::vec3>& strand : strands) count += strand.size();
  return count;
}

Result<StrandSet> loadTfx(const std::filesystem::path& path, const GroomLoadOptions& options) {
  auto opened = GroomFile::open(path);
  if (!opened) return std::unexpected(opened.error());
  GroomFile& file = *opened;
  const std::string& name = file.name();

  if (file.size() < 4)
    return fail(name + ": file is " + str(file.size()) + " bytes, too short for a TressFX header (truncated)");
  auto head = file.read(0, std::min(file.size(), kTfx3HeaderBytes));
  if (!head) return std::unexpected(head.error());
  const float version = readF32(*head, 0);
  // The version float is the format's only signature.
  const bool v3 = version >= 3.0f && version < 4.0f;
  const bool v4 = version >= 4.0f && version < 5.0f;
  if (!v3 && !v4) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(version));
    return fail(name + ": TressFX version " + text +
                " at byte 0 is not supported (expected 3.x or 4.x; not a .tfx file?)");
  }
  const std::uint64_t headerBytes = v3 ? kTfx3HeaderBytes : kTfx4HeaderBytes;
  const std::uint64_t offsetField = v3 ? kTfx3VertexOffsetField : kTfx4VertexOffsetField;
  const std::uint64_t vertexBytes = v3 ? kTfx3VertexBytes : kTfx4VertexBytes;
  const std::string layout = v3 ? "TressFX v3" : "TressFX v4";
  if (file.size() < headerBytes)
    return fail(name + ": file is " + str(file.size()) + " bytes, shorter than the " + layout + " header (" +
                str(headerBytes) + " bytes; truncated)");

  const std::uint32_t strandCount = readU32(*head, 4);
  const std::uint32_t verticesPerStrand = readU32(*head, 8);
  const std::uint32_t vertexOffset = readU32(*head, static_cast<std::size_t>(offsetField));
  if (strandCount == 0) return fail(name + ": the header declares 0 strands (byte 4): the groom is empty");
  if (verticesPerStrand < 2)
    return fail(name + ": the header declares " + str(verticesPerStrand) +
                " vertices per strand (byte 8); a strand needs at least 2");
  if (vertexOffset < headerBytes)
    return fail(name + ": the vertex array offset " + str(vertexOffset) + " (byte " + str(offsetField) +
                ") points into the " + str(headerBytes) + "-byte " + layout + " header");
  if (vertexOffset > file.size())
    return fail(name + ": the vertex array offset " + str(vertexOffset) + " (byte " + str(offsetField) +
                ") is past the end of the file (" + str(file.size()) + " bytes; truncated)");
  // Both counts are 32-bit, so their product fits in 64 bits; the byte size may not, hence the
  // comparison by division.
  const std::uint64_t vertexCount = std::uint64_t{strandCount} * verticesPerStrand;
  const std::uint64_t available = file.size() - vertexOffset;
  if (vertexCount > available / vertexBytes)
    return fail(name + ": the header declares " + str(strandCount) + " strands × " + str(verticesPerStrand) +
                " vertices of " + str(vertexBytes) + " bytes from byte " + str(vertexOffset) + ", but the file has " +
                str(available) + " bytes there (" + str(available / vertexBytes) +
                " vertices): truncated, or the counts are corrupt");

  const std::uint64_t arrayBytes = vertexCount * vertexBytes;
  auto vertices = file.read(vertexOffset, arrayBytes);
  if (!vertices) return std::unexpected(vertices.error());
  StrandSet set;
  set.strands.reserve(strandCount);
  const std::size_t strandBytes = static_cast<std::size_t>(verticesPerStrand * vertexBytes);
  for (std::size_t s = 0; s < strandCount; ++s)
    addStrand(set, *vertices, s * strandBytes, verticesPerStrand, static_cast<std::size_t>(vertexBytes));

  auto thickness = readOptionalArray(file, *head, v3 ? kTfx3StrandThicknessField : kTfx4StrandThicknessField,
                                     headerBytes, strandCount, 4, "per-strand thickness");
  if (!thickness) return std::unexpected(thickness.error());
  for (std::size_t s = 0; s < thickness->size() / 4; ++s) set.strandThickness.push_back(readF32(*thickness, 4 * s));
  auto uvs = readOptionalArray(file, *head, v3 ? kTfx3StrandUvField : kTfx4StrandUvField, headerBytes, strandCount,
                               8, "per-strand UV");
  if (!uvs) return std::unexpected(uvs.error());
  for (std::size_t s = 0; s < uvs->size() / 8; ++s)
    set.strandUvs.emplace_back(readF32(*uvs, 8 * s), readF32(*uvs, 8 * s + 4));

  const PointLocator locate{name, "vertex", [&](std::size_t strand, std::size_t vertex) {
                              return vertexOffset + (std::uint64_t{strand} * verticesPerStrand + vertex) * vertexBytes;
                            }};
  return finishGroom(std::move(set), locate, options);
}

Result<StrandSet> loadCyHair(const std::filesystem::path& path, const GroomLoadOptions& options) {
  auto opened = GroomFile::open(path);
  if (!opened) return std::unexpected(opened.error());
  GroomFile& file = *opened;
  const std::string& name = file.name();

  if (file.size() < kHairHeaderBytes)
    return fail(name + ": file is " + str(file.size()) + " bytes, shorter than the " + str(kHairHeaderBytes) +
                "-byte HAIR header (truncated)");
  auto head = file.read(0, kHairHeaderBytes);
  if (!head) return std::unexpected(head.error());
  if (std::memcmp(head->data(), "HAIR", 4) != 0) {
    std::string found;
    for (std::size_t i = 0; i < 4; ++i) {
      const unsigned char c = (*head)[i];
      if (std::isprint(c)) {
        found += static_cast<char>(c);
      } else {
        char text[8];
        std::snprintf(text, sizeof text, "\\x%02x", static_cast<unsigned>(c));
        found += text;
      }
    }
    return fail(name + ": bytes 0–3 are \"" + found + "\", not the signature \"HAIR\" (not a HAIR file)");
  }
  const std::uint32_t hairCount = readU32(*head, 4);
  const std::uint32_t pointCount = readU32(*head, 8);
  const std::uint32_t arrays = readU32(*head, 12);
  const std::uint32_t defaultSegments = readU32(*head, 16);
  if ((arrays & kHairPointsBit) == 0)
    return fail(name + ": the array flags " + str(arrays) + " (byte 12) announce no point array (bit 1): no positions");
  if (hairCount == 0) return fail(name + ": the header declares 0 hairs (byte 4): the groom is empty");

  // Where each announced array lies; counts are 32-bit, so no sum below can overflow 64 bits.
  struct Span {
    const char* what;
    std::uint64_t begin;
    std::uint64_t bytes;
  };
  std::vector<Span> layout;
  std::uint64_t end = kHairHeaderBytes;
  const auto place = [&](std::uint32_t bit, const char* what, std::uint64_t bytes) {
    if ((arrays & bit) == 0) return;
    layout.push_back({what, end, bytes});
    end += bytes;
  };
  place(kHairSegmentsBit, "segments", 2 * std::uint64_t{hairCount});
  place(kHairPointsBit, "points", 12 * std::uint64_t{pointCount});
  place(kHairThicknessBit, "thickness", 4 * std::uint64_t{pointCount});
  place(kHairTransparencyBit, "transparency", 4 * std::uint64_t{pointCount});
  place(kHairColoursBit, "colours", 12 * std::uint64_t{pointCount});
  for (const Span& array : layout) {
    if (array.begin + array.bytes > file.size())
      return fail(name + ": the " + array.what + " array (bytes " + str(array.begin) + "–" +
                  str(array.begin + array.bytes) + ", for " + str(hairCount) + " hairs and " + str(pointCount) +
                  " points) runs past the end of the file (" + str(file.size()) +
                  " bytes): truncated, or the counts are corrupt");
  }

  // Points per hair: from the segments array, else the header's default.
  std::vector<std::uint32_t> pointsPerHair;
  if ((arrays & kHairSegmentsBit) != 0) {
    auto segments = file.read(kHairHeaderBytes, 2 * std::uint64_t{hairCount});
    if (!segments) return std::unexpected(segments.error());
    pointsPerHair.resize(hairCount);
    std::uint64_t total = 0;
    for (std::size_t h = 0; h < hairCount; ++h) {
      const std::uint16_t count = readU16(*segments, 2 * h);
      // A hair of 0 segments is one point: a flawed strand, dropped by finishGroom unless strict.
      if (count == 0 && options.strict)
        return fail(name + ": strand " + str(h) + " has 0 segments (byte " + str(kHairHeaderBytes + 2 * h) +
                    "); a strand needs at least 1");
      pointsPerHair[h] = std::uint32_t{count} + 1;
      total += pointsPerHair[h];
    }
    if (total != pointCount)
      return fail(name + ": the segments array gives " + str(total) + " points in all, but the header declares " +
                  str(pointCount) + " (byte 8)");
  } else {
    if (defaultSegments == 0)
      return fail(name + ": there is no segments array and the default segment count (byte 16) is 0");
    const std::uint64_t perHair = std::uint64_t{defaultSegments} + 1;
    if (std::uint64_t{hairCount} * perHair != pointCount)
      return fail(name + ": " + str(hairCount) + " hairs of " + str(defaultSegments) +
                  " segments (the default, byte 16) make " + str(std::uint64_t{hairCount} * perHair) +
                  " points, but the header declares " + str(pointCount) + " (byte 8)");
    pointsPerHair.assign(hairCount, static_cast<std::uint32_t>(perHair));
  }

  const auto arrayOf = [&](const char* what) {
    return std::find_if(layout.begin(), layout.end(),
                        [&](const Span& array) { return std::strcmp(array.what, what) == 0; });
  };
  const Span& pointArray = *arrayOf("points");
  auto points = file.read(pointArray.begin, pointArray.bytes);
  if (!points) return std::unexpected(points.error());
  StrandSet set;
  // Header bytes 20–39, after the default segment count.
  set.hairDefaults = StrandSet::HairDefaults{
      .thickness = readF32(*head, 20),
      .transparency = readF32(*head, 24),
      .colour = glm::vec3(readF32(*head, 28), readF32(*head, 32), readF32(*head, 36))};
  set.strands.reserve(hairCount);
  std::vector<std::uint64_t> firstPoint;  // of each hair, in the point array
  firstPoint.reserve(hairCount);
  std::uint64_t next = 0;
  for (std::uint32_t count : pointsPerHair) {
    firstPoint.push_back(next);
    addStrand(set, *points, static_cast<std::size_t>(next * 12), count, 12);
    next += count;
  }

  // The per-point arrays, split by hair like the points.
  const auto readPerPoint = [&]<class T>(const char* what, std::size_t components,
                                         std::vector<std::vector<T>>& perHair) -> Result<void> {
    const auto array = arrayOf(what);
    if (array == layout.end()) return {};
    auto bytes = file.read(array->begin, array->bytes);
    if (!bytes) return std::unexpected(bytes.error());
    perHair.resize(hairCount);
    for (std::size_t h = 0; h < hairCount; ++h) {
      perHair[h].resize(pointsPerHair[h]);
      for (std::size_t i = 0; i < pointsPerHair[h]; ++i) {
        const std::size_t at = static_cast<std::size_t>((firstPoint[h] + i) * 4 * components);
        if constexpr (std::is_same_v<T, float>) {
          perHair[h][i] = readF32(*bytes, at);
        } else {
          perHair[h][i] = T(readF32(*bytes, at), readF32(*bytes, at + 4), readF32(*bytes, at + 8));
        }
      }
    }
    return {};
  };
  if (auto read = readPerPoint("thickness", 1, set.thickness); !read) return std::unexpected(read.error());
  if (auto read = readPerPoint("transparency", 1, set.transparency); !read) return std::unexpected(read.error());
  if (auto read = readPerPoint("colours", 3, set.colours); !read) return std::unexpected(read.error());

  const PointLocator locate{name, "point", [&](std::size_t strand, std::size_t point) {
                              return pointArray.begin + (firstPoint[strand] + point) * 12;
                            }};
  return finishGroom(std::move(set), locate, options);
}

Result<StrandSet> loadGroomFile(const std::filesystem::path& file, const GroomLoadOptions& options) {
  const std::string extension = lowerExtension(file);
  if (extension == ".tfx") return loadTfx(file, options);
  if (extension == ".hair") return loadCyHair(file, options);
  return fail(file.string() + ": unsupported groom file extension \"" + extension +
              "\" (expected .tfx for AMD TressFX or .hair for Cem Yuksel's HAIR format)");
}

}  // namespace mane::scenes
