#pragma once
// Effects over the opaque scene, drawn in the main pass after it (before any hair) with blending
// and no depth written, far to near: round particles (spray, smoke) as soft discs facing the eye,
// lines (rigging) and flat triangles (debris). Each is six vertices made in shaders/effects.vert from one record of a
// storage buffer (no vertex buffers) and lit there, at its vertices, by the frame's lights, ambient and environment:
// spray and smoke cover much of the screen several times over, so their fragments only blend.
//
// A line's width follows its distance. Where it would be thinner than a pixel it is drawn one
// pixel wide and as much fainter (alpha × width in pixels), so that a far rope keeps its
// brightness on average instead of breaking into dashes; discs are kept a pixel in radius the
// same way (Persson, "Phone-wire AA", GPU Pro 5, 2014).
//
// The shaders bind the surfaces' frame set (SurfaceScene::frameLayout) as set 0, their records
// as set 1.

#include <cstdint>
#include <memory>

#include "common/error.hpp"
#include "render/frame.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

class EffectsPass {
public:
  struct Formats {
    vk::Format color = vk::Format::eUndefined;
    vk::Format depth = vk::Format::eUndefined;
    vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  };

  /// Drawing into `formats` with the surfaces' frame set (of layout `frameLayout`) as set 0.
  [[nodiscard]] static Result<std::unique_ptr<EffectsPass>> create(const Device& device, const Formats& formats,
                                                                   vk::DescriptorSetLayout frameLayout);

  EffectsPass(const EffectsPass&) = delete;
  EffectsPass& operator=(const EffectsPass&) = delete;

  /// Checks `frame.effects` (errors name the effect and the field) and writes them, far to near
  /// from the camera, for an image `height` pixels tall. Between frames.
  [[nodiscard]] Result<void> prepare(const FrameInput& frame, std::uint32_t height);

  /// Records the effects inside the main pass, after everything opaque.
  void draw(const vk::raii::CommandBuffer& commands, const vk::raii::DescriptorSet& frameSet,
            vk::Extent2D extent) const;

private:
  explicit EffectsPass(const Device& device) : device_(&device) {}

  const Device* device_;
  Buffer records_;  // host-visible, shaders/effects.vert's Record
  std::uint32_t count_ = 0;
  float pixelAngle_ = 0.0f;  // radians a pixel spans at the image's centre, roughly
  vk::raii::DescriptorSetLayout layout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Pipeline pipeline_;
};

}  // namespace mane::render
