#pragma once
// The visible discs of directional lights: a sun in the sky behind the scene. Each disc is the
// cone of angular radius DirectionalLight::discRadius around the direction towards the light,
// of radiance color × discRadiance. That is not the radiance a disc of that size needs to give
// the light's irradiance (intensity over the solid angle: thousands for a sun of half a degree):
// the god rays, which stream from the disc where it shows, blur the bright part of the image
// linearly, and such a disc would saturate all of it within their reach. Drawn at the far plane,
// depth-tested but not written, first in the main pass (or after the deferred skin), added to the
// background, so whatever the scene puts in front covers it and blended hair lies over it.

#include <optional>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/frame.hpp"
#include "render/pipelines.hpp"

namespace mane::render {

/// The NDC rectangle (min x, min y, max x, max y) that holds the disc of angular radius
/// `radius` around `towardLight` (unit) seen through `ndcFromDirection` (projection × the view's
/// rotation): clipped to the screen; the whole screen when part of the cone is behind the eye;
/// nothing when none of the disc can be on screen.
std::optional<glm::vec4> discBounds(const glm::mat4& ndcFromDirection, glm::vec3 towardLight, float radius);

class LightDiscPass {
public:
  LightDiscPass(const Device& device, vk::Format colorFormat, vk::Format depthFormat, vk::SampleCountFlagBits samples);

  /// Records the discs of the `lights` that have one (discRadius > 0), seen through `camera` on
  /// an image of `extent`, inside the main pass.
  void draw(const vk::raii::CommandBuffer& commands, const Camera& camera, std::span<const DirectionalLight> lights,
            vk::Extent2D extent) const;

private:
  Pipeline pipeline_;
};

}  // namespace mane::render
