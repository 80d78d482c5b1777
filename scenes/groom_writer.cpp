#include "scenes/groom_writer.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "scenes/detail/hair_format.hpp"
#include "scenes/sim_state.hpp"

namespace mane::scenes {
namespace {

static_assert(std::endian::native == std::endian::little, "HAIR files are little-endian; add byte swapping");

constexpr std::uint32_t kMaxPointsPerStrand = 65536;  // 65,535 segments in a uint16

template <class T>
void put(std::vector<unsigned char>& bytes, const T& value) {
  const auto* p = reinterpret_cast<const unsigned char*>(&value);
  bytes.insert(bytes.end(), p, p + sizeof value);
}

}  // namespace

Result<std::vector<unsigned char>> encodeCyHair(std::span<const std::uint32_t> pointsPerStrand,
                                                std::span<const glm::vec3> points, std::string_view info) {
  if (pointsPerStrand.empty()) return fail("HAIR: no strands to write (the format needs at least one hair)");
  std::uint64_t total = 0;
  for (std::size_t s = 0; s < pointsPerStrand.size(); ++s) {
    if (pointsPerStrand[s] < 2 || pointsPerStrand[s] > kMaxPointsPerStrand)
      return fail("HAIR: strand " + std::to_string(s) + " has " + std::to_string(pointsPerStrand[s]) +
                  " points; the format holds 2 to 65,536 per hair");
    total += pointsPerStrand[s];
  }
  if (total != points.size())
    return fail("HAIR: the strands' point counts add up to " + std::to_string(total) + ", not the " +
                std::to_string(points.size()) + " points given");
  std::vector<unsigned char> bytes;
  bytes.reserve(detail::kHairHeaderBytes + 2 * pointsPerStrand.size() + 12 * points.size());
  bytes.insert(bytes.end(), {'H', 'A', 'I', 'R'});
  put(bytes, static_cast<std::uint32_t>(pointsPerStrand.size()));
  put(bytes, static_cast<std::uint32_t>(points.size()));
  put(bytes, detail::kHairSegmentsBit | detail::kHairPointsBit);
  put(bytes, static_cast<std::uint32_t>(pointsPerStrand[0] - 1));  // default segments: unused with the array
  // Defaults that read back as "no look": thickness 0 is none (scenes/groom_looks.hpp), opaque,
  // white leaves the look's own colour. A scene drawing the file then draws it as it says.
  put(bytes, 0.0f);                                                // default thickness
  put(bytes, 0.0f);                                                // default transparency
  for (int i = 0; i < 3; ++i) put(bytes, 1.0f);                    // default colour
  char text[detail::kHairInfoBytes] = {};
  std::memcpy(text, info.data(), std::min(info.size(), detail::kHairInfoBytes - 1));
  bytes.insert(bytes.end(), text, text + detail::kHairInfoBytes);
  for (std::uint32_t count : pointsPerStrand) put(bytes, static_cast<std::uint16_t>(count - 1));
  for (const glm::vec3& p : points) put(bytes, p.x), put(bytes, p.y), put(bytes, p.z);
  return bytes;
}

Result<void> writeCyHair(const std::filesystem::path& file, std::span<const std::uint32_t> pointsPerStrand,
                         std::span<const glm::vec3> points, std::string_view info) {
  auto bytes = encodeCyHair(pointsPerStrand, points, info);
  if (!bytes) return fail(file.string() + ": " + bytes.error().message);
  return writeFileBytes(file, *bytes);
}

}  // namespace mane::scenes
