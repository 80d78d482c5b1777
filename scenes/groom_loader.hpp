#pragma once
// Guide-strand files → strands in memory: AMD TressFX `.tfx` (v3 and v4 layouts) and Cem
// Yuksel's HAIR format (`.hair`). Positions are returned as stored, in the file's own units and
// axes (the TressFX samples use the units of the head mesh they were groomed on); placing them
// in the scene is the caller's job (see World).
//
// Flawed strands (repeated points, NaNs, strands too short or absurdly long) are repaired or
// dropped as groom_repair.hpp describes, and reported in `StrandSet::repairs`; with
// `GroomLoadOptions::strict` the first one is an error instead. A file whose structure is broken
// (truncated arrays, counts that do not add up) is always an error.
//
// Both formats are little-endian binary with 32-bit counts. Every count and offset is checked
// against the file's size with 64-bit arithmetic before anything is allocated or read, so a
// truncated or hostile file gives an error, never a huge allocation or an out-of-bounds read.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "scenes/groom_repair.hpp"

namespace mane::scenes {

/// The guide strands of one groom file: `strands[s]` holds strand s's points, root first, in
/// the file's units. This is the shape `physics::HairSystem::create` takes, so a loaded set can
/// be handed over without copying. Every strand has at least 2 points, all finite, no two
/// consecutive ones equal (flawed strands were repaired or dropped: `repairs`).
///
/// What the file carries beyond positions, where it has it (each attribute array is empty when
/// the file has none, else aligned with `strands`, and follows them through repairs):
struct StrandSet {
  std::vector<std::vector<glm::vec3>> strands;
  /// `.hair` thickness array: `thickness[s][i]` is the width at `strands[s][i]`, in the file's units.
  std::vector<std::vector<float>> thickness;
  /// `.hair` transparency array: `transparency[s][i]` at `strands[s][i]`, 0 opaque to 1 invisible.
  std::vector<std::vector<float>> transparency;
  /// `.hair` colour array: `colours[s][i]` at `strands[s][i]`, RGB as stored (nominally 0–1).
  std::vector<std::vector<glm::vec3>> colours;
  /// `.hair` header defaults: the thickness, transparency and colour of every point where the
  /// file has no array of its own (the arrays above then stay empty). Absent for `.tfx`.
  struct HairDefaults {
    float thickness = 0.0f;     ///< file units
    float transparency = 0.0f;  ///< 0 opaque to 1 invisible
    glm::vec3 colour{0.0f};     ///< RGB as stored (nominally 0–1)
  };
  std::optional<HairDefaults> hairDefaults;
  /// `.tfx` per-strand thickness: `strandThickness[s]` for strand s, as stored (TressFX uses it
  /// as a multiplier of the groom's width).
  std::vector<float> strandThickness;
  /// `.tfx` per-strand texture coordinates: `strandUvs[s]`, where strand s's root lies on the
  /// head mesh's texture (its colour comes from there).
  std::vector<glm::vec2> strandUvs;
  /// Which strands were repaired or dropped on load, and why.
  GroomRepairReport repairs;

  /// Total number of points over all strands.
  [[nodiscard]] std::size_t pointCount() const;
};

/// How to treat flawed strands (groom_repair.hpp lists the flaws).
struct GroomLoadOptions {
  /// Refuse the file at its first flawed strand, naming the strand, the point and its byte
  /// offset, rather than repairing or dropping it.
  bool strict = false;
};

/// Reads an AMD TressFX `.tfx` file: its guide strands and, where the header gives their offsets
/// (non-zero), the per-strand thickness and texture coordinates (per-vertex UVs, thickness and
/// colours are not read). The float `version` at byte 0 picks the layout (AMD TressFX 3.1 `TressFXFileObject`
/// and 4.x `TressFXTFXFileHeader`):
/// - 3.x: uint32 numStrands at byte 4, verticesPerStrand at 8, then (after numFollowHairs,
///   bothEndsImmovable and 31 reserved words) the offsets of the vertex array at byte 144, of
///   the per-strand UVs (float2) at 148 and of the per-strand thickness (float) at 156; float3
///   vertices. The header is 296 bytes.
/// - 4.x: the same counts, then the offsets of the vertex array at byte 12, of the per-strand
///   UVs at 16 and of the per-strand thickness at 24; float4 vertices (w ignored). The header
///   is 160 bytes.
/// Vertices are stored strand after strand, verticesPerStrand each, root first.
/// Errors name the file and, as it applies, the strand, the vertex and the byte offset: an
/// unsupported version, a file shorter than its header, no strands, fewer than 2 vertices per
/// strand, an array that overlaps the header or does not fit in the file, every strand flawed;
/// under `strict`, the first flawed strand.
[[nodiscard]] Result<StrandSet> loadTfx(const std::filesystem::path& file, const GroomLoadOptions& options = {});

/// Reads a HAIR file (Cem Yuksel, http://www.cemyuksel.com/research/hairmodels/): a 128-byte
/// header — "HAIR", uint32 hair count, uint32 point count, uint32 array flags (bit 0 segments,
/// 1 points, 2 thickness, 3 transparency, 4 colours), uint32 default segment count, float default
/// thickness, float default transparency, float[3] default colour, 88 bytes of text — followed
/// by the arrays the flags announce, in that order: uint16 segments per hair, float3 points,
/// float thickness, float transparency, float3 colours (per point). A hair with k segments has
/// k + 1 points; without a segments array every hair has the default count (a hair with 0
/// segments has one point: a flawed strand). Positions, thickness, transparency and colours are
/// returned, and the header's default thickness, transparency and colour (`hairDefaults`), which
/// stand for the arrays the file lacks.
/// Errors name the file and, as it applies, the hair (strand), the point and the byte offset:
/// wrong signature, a file shorter than its header or its arrays, no point array, no hairs,
/// segment counts that do not add up to the point count, every hair flawed; under `strict`, the
/// first flawed hair.
[[nodiscard]] Result<StrandSet> loadCyHair(const std::filesystem::path& file, const GroomLoadOptions& options = {});

/// Loads a groom by extension (case-insensitive): `.tfx` → `loadTfx`, `.hair` → `loadCyHair`;
/// any other extension is an error naming the file.
[[nodiscard]] Result<StrandSet> loadGroomFile(const std::filesystem::path& file,
                                             const GroomLoadOptions& options = {});

}  // namespace mane::scenes
