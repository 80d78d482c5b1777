#pragma once
// A simulation cache: a folder with one simulated state per frame (`frame_NNNNNN.msim`,
// scenes/sim_state.hpp) and a manifest (`cache.json`), written by `mane sim --cache` and read by
// `mane render --cache`, so a long sequence is simulated once and its frames rendered anywhere,
// in any ranges (docs/render-farm.md).
//
// Frame f is the world after f calls of World::advance(1 / fps) from the loaded (and settled)
// world, the very calls `mane render` makes between its frames: frame 0 is time 0, and a frame
// rendered from the cache shows what the same frame of a plain `mane render` shows.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "render/renderer.hpp"
#include "scenes/sim_state.hpp"
#include "scenes/world.hpp"

namespace mane::scenes {

struct SimCacheManifest {
  std::string scene;                       ///< the scene file simulated, as an absolute path
  double fps = 30.0;                       ///< frames per second: frame f is at f / fps seconds (summed)
  std::uint32_t frames = 0;                ///< frames 0 .. frames − 1 are in the folder
  std::vector<std::uint64_t> stateHashes;  ///< World::stateHash() of each frame
};

/// `<folder>/frame_NNNNNN.msim` (six digits, more when needed).
[[nodiscard]] std::filesystem::path cacheFramePath(const std::filesystem::path& folder, std::uint32_t frame);

/// Writes `<folder>/cache.json`. Write it last: a folder without one is an unfinished cache.
[[nodiscard]] Result<void> writeCacheManifest(const std::filesystem::path& folder, const SimCacheManifest& manifest);
/// Reads `<folder>/cache.json`; errors name the file and the field (a folder that is no cache,
/// or one whose simulation did not finish, has none).
[[nodiscard]] Result<SimCacheManifest> readCacheManifest(const std::filesystem::path& folder);

/// Reads frame `frame` of the cache and checks that it is that frame of `manifest` (its step
/// and state hash) and that it fits `world` (the same grooms, cloths and drawn furs with the
/// same particle counts).
[[nodiscard]] Result<SimulatedState> readCacheFrame(const std::filesystem::path& folder,
                                                    const SimCacheManifest& manifest, std::uint32_t frame,
                                                    const World& world);

/// Shows `state` (one that fits `world`) instead of simulating: sets the world's clock to its
/// time (characters posed there) and hands the renderer the characters' skinning, the hair
/// guides, the cloth surfaces (normals computed as the world computes them) and the fur leans.
/// Then render world.frameInput() as usual (FrameLoop::renderFrame).
[[nodiscard]] Result<void> showSimulatedState(const SimulatedState& state, World& world, render::Renderer& renderer);

}  // namespace mane::scenes
