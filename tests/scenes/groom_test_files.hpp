#pragma once
// Synthetic groom files for the loader and repair tests: TressFX v3/v4 and HAIR files written
// byte by byte as their formats lay them out (scenes/groom_loader.hpp), with points on a known
// pattern so a test can name the point it breaks.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::scenes::testing {

inline void putU32(std::string& bytes, std::size_t at, std::uint32_t value) {
  if (bytes.size() < at + 4) bytes.resize(at + 4, '\0');
  std::memcpy(bytes.data() + at, &value, 4);
}
inline void putF32(std::string& bytes, std::size_t at, float value) {
  if (bytes.size() < at + 4) bytes.resize(at + 4, '\0');
  std::memcpy(bytes.data() + at, &value, 4);
}

/// Point v of strand s in the synthetic grooms: strands hang down −Y, 1 cm apart, from roots
/// spread along X.
inline glm::vec3 syntheticPoint(std::size_t s, std::size_t v) {
  return {0.01f * static_cast<float>(s), -0.01f * static_cast<float>(v), 0.002f * static_cast<float>(v * v)};
}

/// A TressFX 3.x file as AMD's `TressFXFileObject` lays it out (296-byte header, float3
/// vertices at byte 296) with the counts and offset as given.
inline std::string tfxV3(std::uint32_t strands, std::uint32_t verts, std::size_t pointsWritten) {
  std::string bytes(296, '\0');
  putF32(bytes, 0, 3.0f);
  putU32(bytes, 4, strands);
  putU32(bytes, 8, verts);
  putU32(bytes, 144, 296);
  for (std::size_t i = 0; i < pointsWritten; ++i) {
    const glm::vec3 p = syntheticPoint(i / std::max<std::uint32_t>(verts, 1), i % std::max<std::uint32_t>(verts, 1));
    for (int c = 0; c < 3; ++c) putF32(bytes, bytes.size(), p[c]);
  }
  return bytes;
}

/// A TressFX 4.x file (`TressFXTFXFileHeader`, 160 bytes; float4 vertices at byte 160).
inline std::string tfxV4(std::uint32_t strands, std::uint32_t verts) {
  std::string bytes(160, '\0');
  putF32(bytes, 0, 4.0f);
  putU32(bytes, 4, strands);
  putU32(bytes, 8, verts);
  putU32(bytes, 12, 160);
  for (std::size_t i = 0; i < std::size_t{strands} * verts; ++i) {
    const glm::vec3 p = syntheticPoint(i / verts, i % verts);
    for (int c = 0; c < 3; ++c) putF32(bytes, bytes.size(), p[c]);
    putF32(bytes, bytes.size(), i % verts == 0 ? 0.0f : 1.0f);  // w: TressFX's inverse mass
  }
  return bytes;
}

/// A HAIR file (cyHairFile.h): 128-byte header, then the announced arrays. `segments` empty:
/// no segments array, every hair has `defaultSegments`.
inline std::string cyHair(const std::vector<std::uint16_t>& segments, std::uint32_t hairs, std::uint32_t defaultSegments,
                   std::uint32_t extraArrays = 0) {
  std::string bytes(128, '\0');
  std::memcpy(bytes.data(), "HAIR", 4);
  std::uint32_t points = 0;
  for (std::uint32_t h = 0; h < hairs; ++h) points += (segments.empty() ? defaultSegments : segments[h]) + 1;
  putU32(bytes, 4, hairs);
  putU32(bytes, 8, points);
  putU32(bytes, 12, (segments.empty() ? 0u : 1u) | 2u | extraArrays);
  putU32(bytes, 16, defaultSegments);
  for (std::uint16_t s : segments) bytes.append(reinterpret_cast<const char*>(&s), 2);
  for (std::uint32_t h = 0; h < hairs; ++h) {
    const std::uint32_t count = (segments.empty() ? defaultSegments : segments[h]) + 1;
    for (std::uint32_t v = 0; v < count; ++v) {
      const glm::vec3 p = syntheticPoint(h, v);
      for (int c = 0; c < 3; ++c) putF32(bytes, bytes.size(), p[c]);
    }
  }
  return bytes;
}

/// Expects an error whose message contains every one of `parts`.
template <class T>
void expectError(const Result<T>& result, std::initializer_list<const char*> parts) {
  ASSERT_FALSE(result.has_value()) << "expected an error mentioning " << *parts.begin();
  for (const char* part : parts)
    EXPECT_NE(result.error().message.find(part), std::string::npos)
        << "missing \"" << part << "\" in: " << result.error().message;
}

}  // namespace mane::scenes::testing
