#pragma once
// Guide-strand files → strands in memory: AMD TressFX `.tfx` (v3 and v4 layouts) and Cem
// Yuksel's HAIR format (`.hair`). Positions are returned as stored, in the file's own units and
// axes (the TressFX samples use the units of the head mesh they were groomed on); placing them
// in the scene is the caller's job (see World).
//
// Both formats are little-endian binary with 32-bit counts. Every count and offset is checked
// against the file's size with 64-bit arithmetic before anything is allocated or read, so a
// truncated or hostile file gives an error, never a huge allocation or an out-of-bounds read.

#include <cstddef>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::scenes {

/// The guide strands of one groom file: `strands[s]` holds strand s's points, root first, in
/// the file's units. This is the shape `physics::HairSystem::create` takes, so a loaded set can
/// be handed over without copying. Every strand has at least 2 points, all finite, no two
/// consecutive ones equal.
struct StrandSet {
  std::vector<std::vector<glm::vec3>> strands;

  /// Total number of points over all strands.
  [[nodiscard]] std::size_t pointCount() const;
};

/// Reads an AMD TressFX `.tfx` file (guide strands only; UVs, thickness and colours are not
/// read). The float `version` at byte 0 picks the layout (AMD TressFX 3.1 `TressFXFileObject`
/// and 4.x `TressFXTFXFileHeader`):
/// - 3.x: uint32 numStrands at byte 4, verticesPerStrand at 8, vertex-array offset at byte 144
///   (after numFollowHairs, bothEndsImmovable and 31 reserved words); float3 vertices. The
///   header is 296 bytes.
/// - 4.x: the same counts, vertex-array offset at byte 12; float4 vertices (w ignored). The
///   header is 160 bytes.
/// Vertices are stored strand after strand, verticesPerStrand each, root first.
/// Errors name the file and, as it applies, the strand, the vertex and the byte offset: an
/// unsupported version, a file shorter than its header, no strands, fewer than 2 vertices per
/// strand, a vertex array that overlaps the header or does not fit in the file, a NaN or
/// infinite position, two consecutive vertices of a strand at the same position.
[[nodiscard]] Result<StrandSet> loadTfx(const std::filesystem::path& file);

/// Reads a HAIR file (Cem Yuksel, http://www.cemyuksel.com/research/hairmodels/): a 128-byte
/// header — "HAIR", uint32 hair count, uint32 point count, uint32 array flags (bit 0 segments,
/// 1 points, 2 thickness, 3 transparency, 4 colours), uint32 default segment count, float default
/// thickness, float default transparency, float[3] default colour, 88 bytes of text — followed
/// by the arrays the flags announce, in that order: uint16 segments per hair, float3 points,
/// float thickness, float transparency, float3 colours (per point). A hair with k segments has
/// k + 1 points; without a segments array every hair has the default count. Only positions are
/// returned; the other arrays are checked to be present (the file is complete) but not read.
/// Errors name the file and, as it applies, the hair (strand), the point and the byte offset:
/// wrong signature, a file shorter than its header or its arrays, no point array, no hairs, a
/// hair with 0 segments, segment counts that do not add up to the point count, a NaN or infinite
/// position, two consecutive points of a hair at the same position.
[[nodiscard]] Result<StrandSet> loadCyHair(const std::filesystem::path& file);

/// Loads a groom by extension (case-insensitive): `.tfx` → `loadTfx`, `.hair` → `loadCyHair`;
/// any other extension is an error naming the file.
[[nodiscard]] Result<StrandSet> loadGroomFile(const std::filesystem::path& file);

}  // namespace mane::scenes
