#include "scenes/frame_loop.hpp"

#include <chrono>
#include <string>

namespace mane::scenes {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

FrameLoop::FrameLoop(World& world, render::Renderer& renderer, const FrameLoopSettings& settings)
    : world_(&world), renderer_(&renderer), settings_(settings) {}

Result<FrameLoop> FrameLoop::create(World& world, render::Renderer& renderer, const FrameLoopSettings& settings) {
  if (settings.imageSize.x == 0 || settings.imageSize.y == 0)
    return fail("Frame loop: the image size must be at least 1×1 pixels, got " + std::to_string(settings.imageSize.x) +
                "×" + std::to_string(settings.imageSize.y) + ".");
  if (settings.threads < 1) return fail("Frame loop: threads must be at least 1.");
  return FrameLoop(world, renderer, settings);
}

Result<void> FrameLoop::setScene(const render::StaticScene& statics) {
  if (auto set = renderer_->setScene(statics); !set) return set;
  return uploadMovingState();
}

Result<void> FrameLoop::advance(double frameDt) {
  auto start = Clock::now();
  if (auto advanced = world_->advance(frameDt, settings_.threads); !advanced) return advanced;
  times_.simulateMs = millisecondsSince(start);
  start = Clock::now();
  if (auto uploaded = uploadMovingState(); !uploaded) return uploaded;
  times_.uploadMs = millisecondsSince(start);
  return {};
}

Result<std::vector<render::PassTiming>> FrameLoop::renderFrame(const render::FrameInput& frame, Refinement refinement) {
  const auto start = Clock::now();
  if (refinement == Refinement::kForCamera)
    if (auto refined = refine(frame.camera); !refined) return std::unexpected(refined.error());
  times_.refineMs = millisecondsSince(start);
  return renderer_->render(frame);
}

Result<void> FrameLoop::uploadMovingState() {
  for (const auto& mesh : world_->dynamicMeshes())
    if (auto updated = renderer_->updateMesh(mesh.mesh, mesh.positions, mesh.normals); !updated) return updated;
  for (const auto& skinned : world_->skinnedMeshes())
    if (auto updated = renderer_->updateSkinning(skinned.mesh, skinned.jointMatrices, skinned.morphWeights); !updated)
      return updated;
  for (const auto& hair : world_->hairGuides())
    if (auto updated = renderer_->updateHair(hair.groom, hair.positions); !updated) return updated;
  for (const auto& fur : world_->furLeans())
    if (auto updated = renderer_->updateFurLeans(fur.fur, fur.leans); !updated) return updated;
  return {};
}

Result<void> FrameLoop::refine(const render::Camera& camera) {
  auto refined = world_->refineForCamera(camera, settings_.imageSize, settings_.threads);
  if (!refined) return std::unexpected(refined.error());
  for (const std::size_t mesh : *refined)
    if (auto replaced = renderer_->replaceMesh(mesh, world_->meshData(mesh)); !replaced) return replaced;
  return {};
}

}  // namespace mane::scenes
