#pragma once
// Cem Yuksel's HAIR format (cyHairFile.h), shared by its reader (groom_loader.cpp) and writer
// (groom_writer.cpp): a 128-byte header — "HAIR", hair count, point count, array flags, default
// segment count, thickness, transparency, colour, 88 bytes of text — then the arrays its flags
// announce, in flag order.

#include <cstddef>
#include <cstdint>

namespace mane::scenes::detail {

inline constexpr std::size_t kHairHeaderBytes = 128;
inline constexpr std::size_t kHairInfoBytes = 88;
inline constexpr std::uint32_t kHairSegmentsBit = 1;      ///< uint16 segments per hair
inline constexpr std::uint32_t kHairPointsBit = 2;        ///< float3 points
inline constexpr std::uint32_t kHairThicknessBit = 4;     ///< float per point
inline constexpr std::uint32_t kHairTransparencyBit = 8;  ///< float per point
inline constexpr std::uint32_t kHairColoursBit = 16;      ///< float3 per point

}  // namespace mane::scenes::detail
