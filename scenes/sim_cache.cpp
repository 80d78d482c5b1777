#include "scenes/sim_cache.hpp"

#include <charconv>
#include <fstream>

#include <nlohmann/json.hpp>

#include "physics/hash.hpp"
#include "scenes/mesh.hpp"

namespace mane::scenes {
namespace {

constexpr const char* kManifestName = "cache.json";
constexpr const char* kFormat = "mane-sim-cache";
constexpr int kVersion = 1;

/// Whether `state` has the shape of `world`'s simulated state; the error says what differs.
Result<void> checkFits(const SimulatedState& state, const World& world, const std::string& name) {
  auto mismatch = [&](const std::string& what) {
    return fail(name + ": " + what + " (a cache of another scene, or of this scene before it changed?)");
  };
  if (state.grooms.size() != world.simulatedGroomCount())
    return mismatch(std::to_string(state.grooms.size()) + " grooms, the scene simulates " +
                    std::to_string(world.simulatedGroomCount()));
  for (std::size_t g = 0; g < state.grooms.size(); ++g)
    if (state.grooms[g].name != world.simulatedGroomName(g) ||
        state.grooms[g].positions.size() != world.simulatedGroom(g).particles().size())
      return mismatch("groom " + std::to_string(g) + " is '" + state.grooms[g].name + "' of " +
                      std::to_string(state.grooms[g].positions.size()) + " particles, the scene's '" +
                      world.simulatedGroomName(g) + "' has " +
                      std::to_string(world.simulatedGroom(g).particles().size()));
  if (state.cloths.size() != world.cloths().size())
    return mismatch(std::to_string(state.cloths.size()) + " cloths, the scene has " +
                    std::to_string(world.cloths().size()));
  for (std::size_t c = 0; c < state.cloths.size(); ++c)
    if (state.cloths[c].positions.size() != world.cloths()[c].surface().positions.size())
      return mismatch("cloth '" + state.cloths[c].name + "' has " + std::to_string(state.cloths[c].positions.size()) +
                      " vertices, the scene's " + std::to_string(world.cloths()[c].surface().positions.size()));
  const auto furs = world.furLeans();
  if (state.furs.size() != furs.size())
    return mismatch(std::to_string(state.furs.size()) + " moving furs, the scene draws " + std::to_string(furs.size()));
  for (std::size_t f = 0; f < furs.size(); ++f)
    if (state.furs[f].fur != furs[f].fur || state.furs[f].leans.size() != furs[f].leans.size())
      return mismatch("moving fur " + std::to_string(f) + " differs from the scene's");
  return {};
}

}  // namespace

std::filesystem::path cacheFramePath(const std::filesystem::path& folder, std::uint32_t frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06u.msim", frame);
  return folder / name;
}

Result<void> writeCacheManifest(const std::filesystem::path& folder, const SimCacheManifest& manifest) {
  nlohmann::json hashes = nlohmann::json::array();
  for (std::uint64_t hash : manifest.stateHashes) hashes.push_back(physics::hashText(hash));
  const nlohmann::json json = {{"format", kFormat},   {"version", kVersion},       {"scene", manifest.scene},
                               {"fps", manifest.fps}, {"frames", manifest.frames}, {"state_hashes", hashes}};
  const std::string text = json.dump(2) + "\n";
  return writeFileBytes(folder / kManifestName,
                        std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
}

Result<SimCacheManifest> readCacheManifest(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / kManifestName;
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in)
    return fail(name + ": not found: " + folder.string() +
                " is no simulation cache, or its `mane sim --cache` did not finish");
  SimCacheManifest manifest;
  try {
    const nlohmann::json json = nlohmann::json::parse(in);
    if (json.value("format", "") != kFormat) return fail(name + ": \"format\" is not \"" + kFormat + "\"");
    if (json.value("version", 0) != kVersion)
      return fail(name + ": \"version\" " + json.value("version", nlohmann::json()).dump() +
                  "; this program reads version " + std::to_string(kVersion));
    manifest.scene = json.at("scene").get<std::string>();
    manifest.fps = json.at("fps").get<double>();
    manifest.frames = json.at("frames").get<std::uint32_t>();
    const nlohmann::json& hashes = json.at("state_hashes");
    for (std::size_t i = 0; i < hashes.size(); ++i) {
      const std::string text = hashes[i].get<std::string>();
      std::uint64_t hash = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), hash, 16);
      if (error != std::errc() || end != text.data() + text.size() || text.size() != 16)
        return fail(name + ": state_hashes[" + std::to_string(i) + "]: expected 16 hex digits, got \"" + text + "\"");
      manifest.stateHashes.push_back(hash);
    }
  } catch (const std::exception& error) {
    return fail(name + ": " + error.what());
  }
  if (!(manifest.fps > 0.0) || manifest.stateHashes.size() != manifest.frames)
    return fail(name + ": \"fps\" must be > 0 and \"state_hashes\" hold one hash per frame");
  return manifest;
}

Result<SimulatedState> readCacheFrame(const std::filesystem::path& folder, const SimCacheManifest& manifest,
                                      std::uint32_t frame, const World& world) {
  const std::filesystem::path file = cacheFramePath(folder, frame);
  if (frame >= manifest.frames)
    return fail(folder.string() + ": frame " + std::to_string(frame) + " is not in the cache (frames 0 to " +
                std::to_string(manifest.frames) + " − 1)");
  auto state = readSimulatedState(file);
  if (!state) return state;
  if (state->step != frame || state->stateHash != manifest.stateHashes[frame])
    return fail(file.string() + ": holds step " + std::to_string(state->step) + " with state hash " +
                physics::hashText(state->stateHash) + ", not frame " + std::to_string(frame) + " with the manifest's " +
                physics::hashText(manifest.stateHashes[frame]));
  if (auto fits = checkFits(*state, world, file.string()); !fits) return std::unexpected(fits.error());
  return state;
}

Result<void> showSimulatedState(const SimulatedState& state, World& world, render::Renderer& renderer) {
  if (auto shown = world.showTime(state.time); !shown) return shown;
  for (const auto& skinned : world.skinnedMeshes())
    if (auto updated = renderer.updateSkinning(skinned.mesh, skinned.jointMatrices, skinned.morphWeights); !updated)
      return updated;
  for (const auto& hair : world.hairGuides())
    if (auto updated = renderer.updateHair(hair.groom, state.grooms.at(hair.simulatedGroom).positions); !updated)
      return updated;
  const auto cloths = world.dynamicMeshes();
  for (std::size_t c = 0; c < cloths.size(); ++c) {
    // The world's own recipe (SceneCloth): the particles are the vertices, normals smoothed.
    Mesh surface = world.cloths()[c].surface();
    surface.positions = state.cloths.at(c).positions;
    computeSmoothNormals(surface);
    if (auto updated = renderer.updateMesh(cloths[c].mesh, surface.positions, surface.normals); !updated)
      return updated;
  }
  for (const FurLeanState& fur : state.furs)
    if (auto updated = renderer.updateFurLeans(fur.fur, fur.leans); !updated) return updated;
  return {};
}

}  // namespace mane::scenes
