#pragma once
// The scene's furred meshes (StaticScene::furs): one FurPass per (mesh, fur material) pair,
// updated from the frame and drawn in the main pass after the opaque surfaces (whose depth the
// shells test against). The surface pass leaves those instances to this while
// FrameInput::furShells is on. Each fur receives the frame's hair shadows and casts into them:
// the renderer registers shadowCasters() after its grooms (HairShadowPass keeps up to 4 maps).
// Fur opacity in the map: each vertex's strand stands for a column of fur one mean edge wide (at
// the instance's scale), in a map whose texel spans about one such column (so that the columns
// fill it), and each column crossed keeps exp(−κ·o) = exp(−kFurColumnOpacity) of the light. The
// body itself is not in the map: light reaching the far side has crossed the fur twice, not been
// stopped.

#include <memory>
#include <span>
#include <vector>

#include "render/frame.hpp"
#include "render/passes/fur_pass.hpp"

namespace mane::render {

/// Opacity o of one fur column in the hair shadow map, with κ = 1 (file comment).
inline constexpr float kFurColumnOpacity = 0.3f;

class FurSurfaces {
public:
  FurSurfaces() = default;

  /// One FurPass per entry of `scene.furs`, drawing into `target` formats. Errors name the fur
  /// entry: a mesh or material out of range, a material that is not kFur, a missing photo, a mesh
  /// without normals or uvs, or what FurPass refuses.
  [[nodiscard]] static Result<FurSurfaces> create(const Device& device, const StaticScene& scene,
                                                  const FurPassSettings& target, const HairShadowPass& shadows);

  /// The furs as hair shadow casters, in StaticScene::furs order.
  [[nodiscard]] std::vector<HairShadowPass::Groom> shadowCasters() const;

  /// Whether fur `fur` was drawn by the last update(); its shadowBounds() are then current.
  [[nodiscard]] bool drawn(std::size_t fur) const { return furs_.at(fur).drawn; }
  [[nodiscard]] const BoundingSphere& shadowBounds(std::size_t fur) const { return furs_.at(fur).pass->shadowBounds(); }
  /// The width its shadow strands stand for, metres, as of the last update() that drew it.
  [[nodiscard]] float shadowColumnWidth(std::size_t fur) const { return furs_.at(fur).pass->shadowColumnWidth(); }

  /// FurPass::refreshShadows of every fur.
  void refreshShadows();
  /// FurPass::setShadowUniforms of every fur.
  void setShadowUniforms(const HairShadowUniforms& uniforms);

  /// Whether `instance` is drawn as fur this frame (its mesh and material name a fur entry).
  [[nodiscard]] bool draws(const MeshInstance& instance, const FrameInput& frame) const;

  /// Points each fur at the first instance of the frame that draws it (the others are not
  /// drawn: one uniform block per pass) with the first light, `ambient` radiance and the
  /// `environment`'s irradiance over π (zeros: none). Errors as FurPass::update.
  [[nodiscard]] Result<void> update(const FrameInput& frame, glm::vec3 ambient, const SphericalHarmonics9& environment,
                                    vk::Extent2D extent, float aspect);

  /// Records the furs update() found instances for, inside the main pass.
  void draw(const vk::raii::CommandBuffer& commands) const;

  /// Per-vertex leans of fur `fur` (FurPass::setLeans).
  [[nodiscard]] Result<void> setLeans(std::size_t fur, std::span<const glm::vec3> leans);

  /// The shape of fur `fur`'s mesh this frame, when it is deformed on the GPU (FurPass::setPose).
  [[nodiscard]] Result<void> setPose(std::size_t fur, std::span<const glm::vec4> positions,
                                     std::span<const glm::vec4> normals);

  [[nodiscard]] std::size_t size() const { return furs_.size(); }
  /// The scene mesh fur `fur` grows on.
  [[nodiscard]] std::size_t mesh(std::size_t fur) const { return furs_.at(fur).mesh; }
  [[nodiscard]] const FurPass& pass(std::size_t fur) const { return *furs_.at(fur).pass; }

private:
  struct Fur {
    std::size_t mesh = 0;
    std::size_t material = 0;
    FurLook look;
    std::unique_ptr<FurPass> pass;
    bool drawn = false;  ///< an instance drew it this frame
  };
  std::vector<Fur> furs_;
};

}  // namespace mane::render
