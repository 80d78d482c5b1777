#pragma once
// What the render, sim and view commands share: the default scene, and loading a scene file
// into a World with its fallback notes printed.

#include <filesystem>
#include <string>

#include "render/renderer.hpp"
#include "scenes/world.hpp"

namespace mane::app {

/// scenes/nalu.json of the source tree this program was built from.
std::filesystem::path defaultScenePath();

/// Loads `scenePath` into a World, printing each fallback note as "note: ..." on stdout.
Result<scenes::World> loadWorld(const std::filesystem::path& scenePath, const scenes::WorldSettings& settings);

/// Hands the world's moving meshes (cloth) their current vertices, the grooms their guides and
/// moving fur its leans; call after advancing.
Result<void> uploadDynamicMeshes(const scenes::World& world, render::Renderer& renderer);

/// Re-tessellates the world's subdivided meshes for `camera` and an image of `size` pixels (and
/// the meshes' current placement) and hands the renderer those that changed (issue 6). An older
/// StaticScene's mesh spans are stale afterwards.
Result<void> refineSubdivided(scenes::World& world, render::Renderer& renderer, const render::Camera& camera,
                              glm::uvec2 size, unsigned threads);

/// Parses "WIDTHxHEIGHT" (e.g. 1280x720).
Result<std::pair<std::uint32_t, std::uint32_t>> parseSize(const std::string& text);

}  // namespace mane::app
