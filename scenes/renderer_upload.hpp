#pragma once
// Handing a World's per-frame state to a Renderer: what every program that draws a World does
// between advancing it and rendering (mane render and view, the frame bench, the tests).

#include <glm/vec2.hpp>

#include "common/error.hpp"
#include "render/renderer.hpp"
#include "scenes/world.hpp"

namespace mane::scenes {

/// Hands the world's moving meshes (cloth) their current vertices, the grooms their guides and
/// moving fur its leans; call after advancing.
[[nodiscard]] Result<void> uploadFrameState(const World& world, render::Renderer& renderer);

/// Re-tessellates the world's subdivided meshes for `camera` and an image of `size` pixels (and
/// the meshes' current placement) and hands the renderer those that changed (issue 6). An older
/// StaticScene's mesh spans are stale afterwards.
[[nodiscard]] Result<void> refineSubdivided(World& world, render::Renderer& renderer, const render::Camera& camera,
                                            glm::uvec2 size, unsigned threads);

}  // namespace mane::scenes
