#pragma once
// The frame of every program that draws a World (docs/design.md#the-frame): advance the world,
// hand the renderer what moved (cloth vertices, hair guides, fur leans), tessellate the subdivided
// meshes again for the frame's camera, render. `mane render`, `mane view` and the frame bench run
// their frames through it; what they do with the picture (files, a window, timings) stays theirs.

#include <vector>

#include <glm/vec2.hpp>

#include "common/error.hpp"
#include "render/renderer.hpp"
#include "scenes/world.hpp"

namespace mane::scenes {

struct FrameLoopSettings {
  /// Pixels of the rendered image: the subdivided meshes are tessellated for it (> 0 each way).
  glm::uvec2 imageSize{0};
  /// Workers for the simulation and the tessellation (≥ 1); the results do not depend on it.
  unsigned threads = 1;
};

/// What renderFrame does with the subdivided meshes before it renders.
enum class Refinement {
  kForCamera,  ///< tessellate them again for the frame's camera and their placement now
  kKeep,       ///< draw the triangles they have (while a camera is dragged; tests of one tessellation)
};

/// Wall-clock milliseconds of the stages the loop ran last, for benchmarks.
struct FrameStageTimes {
  double simulateMs = 0.0;  ///< World::advance, in the last advance
  double uploadMs = 0.0;    ///< the moving state handed to the renderer, in the last advance
  double refineMs = 0.0;    ///< the re-tessellation and its upload, in the last renderFrame
};

/// Runs frames of `world` through `renderer`. Holds both by reference: they must outlive it.
/// Order of a frame: advance (simulate, upload), then renderFrame (refine, render).
class FrameLoop {
public:
  /// A loop over `world` and `renderer`; no work yet. Fails when `settings` are out of range.
  [[nodiscard]] static Result<FrameLoop> create(World& world, render::Renderer& renderer,
                                                const FrameLoopSettings& settings);

  /// Hands the renderer `statics` (world.staticScene(), perhaps with other techniques chosen),
  /// then the world's moving state as it is now. Call before the first frame, and again to change
  /// the scene's techniques once no frame is in flight.
  [[nodiscard]] Result<void> setScene(const render::StaticScene& statics);

  /// Advances the world by `frameDt` seconds (finite, ≥ 0) and hands the renderer its new state.
  [[nodiscard]] Result<void> advance(double frameDt);

  /// Renders `frame` (usually world.frameInput() with the caller's camera, post or lights),
  /// re-tessellating the subdivided meshes for frame.camera first unless `refinement` is kKeep
  /// (the mesh spans of a StaticScene taken before are stale afterwards). Returns each pass's GPU
  /// time.
  [[nodiscard]] Result<std::vector<render::PassTiming>> renderFrame(const render::FrameInput& frame,
                                                                    Refinement refinement = Refinement::kForCamera);

  [[nodiscard]] const FrameStageTimes& lastStageTimes() const noexcept { return times_; }

private:
  FrameLoop(World& world, render::Renderer& renderer, const FrameLoopSettings& settings);
  /// Cloth vertices, hair guides and fur leans, as the world has them now.
  Result<void> uploadMovingState();
  /// The meshes World::refineForCamera changed, replaced in the renderer.
  Result<void> refine(const render::Camera& camera);

  World* world_;
  render::Renderer* renderer_;
  FrameLoopSettings settings_;
  FrameStageTimes times_;
};

}  // namespace mane::scenes
