#pragma once
// Procedural guide grooms for tests, benchmarks and the built-in demo content: roots scattered
// over a spherical scalp cap, strands growing straight out of the scalp or as helical curls.
//
// Deterministic for a seed on every platform: the random numbers come from splitmix64
// (physics/split_mix64.hpp), floats are made from its top 24 bits, and the geometry uses only
// + − × ÷ and sqrt (all correctly rounded by IEEE 754) — no std::uniform_real_distribution
// (implementation-defined) and no libm trigonometry (which may differ between libraries).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "physics/split_mix64.hpp"

namespace mane::physics {

/// Parameters of a procedural groom. Lengths in metres, angles in radians.
struct GroomSettings {
  std::uint64_t seed = 1;               ///< PRNG seed; equal seeds give bit-identical grooms
  std::size_t strandCount = 64;         ///< number of guide strands (≥ 1)
  std::size_t particlesPerStrand = 16;  ///< points per strand, root included (≥ 2)
  float strandLength = 0.25f;           ///< mean length along the growth direction, m (> 0)
  float lengthJitter = 0.1f;            ///< relative random variation of the length, in [0, 1)
  glm::vec3 scalpCentre{0.0f};          ///< centre of the spherical scalp, head-local, m
  float scalpRadius = 0.1f;             ///< scalp radius, m (> 0)
  /// Roots cover the cap of the sphere whose outward normal has a Y component of at least this
  /// (1 = only the crown, 0 = the upper hemisphere, −1 = the whole sphere).
  float capMinNormalY = 0.2f;
  float curlRadius = 0.0f;  ///< helix radius, m; 0 gives straight strands
  /// Helix turn per segment, radians (|angle| ≤ π/2); used when curlRadius > 0.
  float curlAnglePerSegment = 0.5f;
  /// Combing, head-local: each strand grows along n + c_t instead of its scalp normal n, where c_t
  /// is the part of `comb` along the scalp (c − (c·n)n). Its length sets how far the strands lean
  /// over: 1 tilts them 45° from the normal where the comb lies along the scalp. Zero: no combing.
  glm::vec3 comb{0.0f};
  /// A parting, head-local: roots in front of (z above) `partingBackZ` are combed away from the
  /// plane x = `partingX` as well, `partingComb` added to `comb` along +x on its +x side and
  /// along −x on the other, fading in over the kPartingFade metres in front of `partingBackZ` so
  /// that the crown behind the parting keeps the plain comb. Zero: no parting.
  float partingComb = 0.0f;
  float partingX = 0.0f;
  float partingBackZ = 0.0f;
};

/// How far in front of GroomSettings::partingBackZ the parting's comb reaches its full strength, m.
inline constexpr float kPartingFade = 0.02f;

/// The comb a root at `root` (head-local) grows with: GroomSettings::comb, plus the parting's.
[[nodiscard]] glm::vec3 combAt(const GroomSettings& settings, const glm::vec3& root) noexcept;

/// Generates guide strands (head-local points, root first, on the scalp) for `settings`.
/// Each strand grows along the scalp normal at its root, combed (GroomSettings::comb); curls wind
/// around that axis and start at the root. Fails with a message naming the field when a setting is out of range.
[[nodiscard]] Result<std::vector<std::vector<glm::vec3>>> generateGroom(const GroomSettings& settings);

/// Generates guide strands rooted on a region of a triangle mesh (the scalp): roots spread by
/// area over `scalpTriangles` (indices of triangles in `indices`, 3 per triangle), weighted by
/// `density` (a relative root density ≥ 0 per scalp triangle; empty: uniform), each growing
/// along its triangle's normal (counter-clockwise winding faces out). Positions and lengths in
/// metres, in the mesh's space. Uses every setting except the sphere's (scalpCentre,
/// scalpRadius, capMinNormalY). Fails, naming it, on an index out of range, an empty region or
/// one without area, densities that are not one per triangle or not finite and ≥ 0, and on
/// settings out of range.
[[nodiscard]] Result<std::vector<std::vector<glm::vec3>>> generateGroomOnMesh(
    const GroomSettings& settings, std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
    std::span<const std::uint32_t> scalpTriangles, std::span<const float> density = {});

/// Grows one guide strand from each of `roots` (head-local points, metres) along its unit
/// `normals` entry: the length, jitter, curl and seed settings as for the other generators;
/// `strandCount` and the sphere's settings are not used. For roots placed by the caller, e.g.
/// on a subdivision surface's limit (scenes/limit_scalp.hpp). Fails, naming it, on settings out
/// of range, no roots, counts that differ, or a root or normal that is not finite (or a normal
/// not of unit length within 1e-3).
[[nodiscard]] Result<std::vector<std::vector<glm::vec3>>> generateGroomFromRoots(const GroomSettings& settings,
                                                                                 std::span<const glm::vec3> roots,
                                                                                 std::span<const glm::vec3> normals);

}  // namespace mane::physics
