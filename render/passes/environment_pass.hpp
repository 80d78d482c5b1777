#pragma once
// The scene's environment on the GPU: its radiance as an fp16 cube map, drawn behind the scene
// (a triangle over the screen at the far plane, depth-tested, first in the main pass after the
// deferred skin), and its diffuse light as nine spherical harmonics of E/π
// (render/environment/spherical_harmonics.hpp, projected from the fp16 cube in a compute pass:
// render/environment/harmonics_projection.hpp) for the surfaces' shaders, in the units of the
// frame's ambient term: a white Lambertian surface under a constant environment of radiance L
// shows L; and its glossy reflections as a chain pre-filtered for eight roughnesses
// (render/environment/specular_chain.hpp).

#include <memory>

#include "common/error.hpp"
#include "render/environment/specular_chain.hpp"
#include "render/environment/spherical_harmonics.hpp"
#include "render/frame.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

class EnvironmentPass {
public:
  struct Formats {
    vk::Format color = vk::Format::eUndefined;
    vk::Format depth = vk::Format::eUndefined;
    vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  };

  /// Uploads `environment` (a cube map of 1 to 4096 texels a side, finite and not negative;
  /// errors say which face and texel is not) and projects its irradiance.
  [[nodiscard]] static Result<std::unique_ptr<EnvironmentPass>> create(const Device& device,
                                                                       const EnvironmentData& environment,
                                                                       const Formats& formats);

  /// Records the background seen through `camera` on an image of `extent`, inside the main pass.
  void draw(const vk::raii::CommandBuffer& commands, const Camera& camera, vk::Extent2D extent) const;

  /// The irradiance over π: Σ coefficient × Y(normal) is what a white Lambertian surface shows.
  [[nodiscard]] const SphericalHarmonics9& irradianceOverPi() const { return irradianceOverPi_; }
  /// The radiance pre-filtered for glossy reflection, a roughness per mip level.
  [[nodiscard]] const SpecularChain& specular() const { return specular_; }
  [[nodiscard]] const vk::raii::Sampler& sampler() const { return sampler_; }

private:
  EnvironmentPass() = default;

  Image cube_;  // with its mip chain, which the specular chain samples
  vk::raii::Sampler sampler_{nullptr};
  SpecularChain specular_;
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Pipeline pipeline_;
  SphericalHarmonics9 irradianceOverPi_{};
};

}  // namespace mane::render
