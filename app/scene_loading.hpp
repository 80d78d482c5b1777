#pragma once
// What the render, sim and view commands share: the default scene, and loading a scene file
// into a World with its fallback notes printed.

#include <filesystem>
#include <cstdint>
#include <string>
#include <utility>

#include "scenes/world.hpp"

namespace mane::app {

/// scenes/nalu.json of the source tree this program was built from.
std::filesystem::path defaultScenePath();

/// Loads `scenePath` into a World, printing each fallback note as "note: ..." on stdout unless
/// `printNotes` is false (machine-readable output carries them itself: World::notes). With
/// `settings.strictGrooms`, every groom file of the scene is loaded strictly (`Groom::strict`).
Result<scenes::World> loadWorld(const std::filesystem::path& scenePath, const scenes::WorldSettings& settings,
                                bool printNotes = true);

/// Help of the commands' `--strict` flag, which sets `WorldSettings::strictGrooms`.
inline constexpr const char* kStrictGroomsHelp =
    "Refuse groom files with flawed strands (repeated or non-finite points, too few points, absurd lengths) "
    "instead of repairing or dropping them with a note, as if every groom of the scene said \"strict\": true";

/// Whether stdout is a terminal (a person watching, rather than a file or a pipe).
bool stdoutIsTerminal();

/// Parses "WIDTHxHEIGHT" (e.g. 1280x720).
Result<std::pair<std::uint32_t, std::uint32_t>> parseSize(const std::string& text);

}  // namespace mane::app
