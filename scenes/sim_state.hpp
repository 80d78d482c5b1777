#pragma once
// A World's simulated state at one moment as plain arrays, and its binary file (`.msim`, laid out
// in docs/sim-state-format.md): what `mane sim --save` writes and each frame of a simulation
// cache holds (scenes/sim_cache.hpp). Grooms and cloths keep their full Verlet state (positions
// and previous positions); moving furs keep only the leans the renderer bends its shells by.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::scenes {

class World;

/// One simulated groom's guides.
struct GroomState {
  std::string name;                            ///< the scene's groom name
  std::vector<std::uint32_t> pointsPerStrand;  ///< particles of each guide, root first, ≥ 2 each
  std::vector<glm::vec3> positions;            ///< world space, metres, guide after guide
  std::vector<glm::vec3> previousPositions;    ///< one fixed step earlier, metres
};

/// One cloth's particles, in the order of its mesh's vertices.
struct ClothState {
  std::string name;                          ///< the scene's cloth name
  std::vector<glm::vec3> positions;          ///< world space, metres
  std::vector<glm::vec3> previousPositions;  ///< one fixed step earlier, metres
};

/// One drawn moving fur's per-vertex leans (World::FurLeans).
struct FurLeanState {
  std::uint32_t fur = 0;         ///< index into the renderer's StaticScene::furs
  std::vector<glm::vec3> leans;  ///< per mesh vertex, world space, in fur heights
};

struct SimulatedState {
  /// World::advance calls since the world was loaded: fixed steps for `mane sim --steps`,
  /// frames for a simulation cache.
  std::uint64_t step = 0;
  double time = 0.0;            ///< World::time(), seconds of animation
  std::uint64_t stateHash = 0;  ///< World::stateHash() at this moment
  std::vector<GroomState> grooms;
  std::vector<ClothState> cloths;
  std::vector<FurLeanState> furs;
};

/// The state of `world` now, labelled `step`. Fur leans are those of drawn furs only (a world
/// loaded without textures draws none).
[[nodiscard]] SimulatedState captureSimulatedState(const World& world, std::uint64_t step);

/// The `.msim` bytes of `state` (docs/sim-state-format.md).
[[nodiscard]] std::vector<unsigned char> encodeSimulatedState(const SimulatedState& state);
/// Reads `.msim` bytes; `name` (a file name) starts every error, which also names the byte offset
/// and what was expected there: a wrong signature or version, a truncated array, bytes left over,
/// a guide of fewer than 2 points, point counts that do not add up.
[[nodiscard]] Result<SimulatedState> decodeSimulatedState(std::span<const unsigned char> bytes,
                                                          const std::string& name);

[[nodiscard]] Result<void> writeSimulatedState(const std::filesystem::path& file, const SimulatedState& state);
[[nodiscard]] Result<SimulatedState> readSimulatedState(const std::filesystem::path& file);

/// Writes `bytes` to `file`, creating its folder; errors name the file.
[[nodiscard]] Result<void> writeFileBytes(const std::filesystem::path& file, std::span<const unsigned char> bytes);
/// Reads the whole of `file`; errors name it.
[[nodiscard]] Result<std::vector<unsigned char>> readFileBytes(const std::filesystem::path& file);

}  // namespace mane::scenes
