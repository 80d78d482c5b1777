#include "render/passes/environment_pass.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/matrix.hpp>

#include "render/descriptors.hpp"
#include "render/environment/harmonics_projection.hpp"

namespace mane::render {
namespace {

constexpr int kMaxCubeSize = 4096;
// Level 0 of the specular chain, the mirror level; level 7, roughness 1, is then 1 texel.
constexpr std::uint32_t kSpecularBaseSize = 128;

Result<void> validate(const CubeMap& cube) {
  if (cube.size < 1 || cube.size > kMaxCubeSize)
    return fail("environment: the cube map is " + std::to_string(cube.size) + " texels a side (1 to " +
                std::to_string(kMaxCubeSize) + ")");
  const std::size_t texels = std::size_t(cube.size) * std::size_t(cube.size);
  for (int face = 0; face < 6; ++face) {
    const std::vector<glm::vec3>& texelsOfFace = cube.faces[std::size_t(face)];
    if (texelsOfFace.size() != texels)
      return fail("environment: cube face " + std::to_string(face) + " holds " + std::to_string(texelsOfFace.size()) +
                  " texels, not " + std::to_string(texels));
    for (std::size_t i = 0; i < texels; ++i) {
      const glm::vec3 t = texelsOfFace[i];
      if (!(t.x >= 0.0f && t.y >= 0.0f && t.z >= 0.0f && std::isfinite(t.x) && std::isfinite(t.y) &&
            std::isfinite(t.z)))
        return fail("environment: cube face " + std::to_string(face) + ", texel " + std::to_string(i) +
                    " is negative or not finite");
    }
  }
  return {};
}

}  // namespace

Result<std::unique_ptr<EnvironmentPass>> EnvironmentPass::create(const Device& device,
                                                                 const EnvironmentData& environment,
                                                                 const Formats& formats) {
  if (auto valid = validate(environment.radiance); !valid) return std::unexpected(valid.error());
  std::unique_ptr<EnvironmentPass> pass(new EnvironmentPass());
  try {
    pass->cube_ = uploadCubeWithMips(device, environment.radiance);
    pass->sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
    auto specular = SpecularChain::bake(device, pass->cube_, pass->sampler_, kSpecularBaseSize);
    if (!specular) return std::unexpected(specular.error());
    pass->specular_ = std::move(*specular);
    pass->setLayout_ =
        makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, vk::ShaderStageFlagBits::eFragment}});
    pass->pool_ = makeDescriptorPool(device, 1, {{vk::DescriptorType::eCombinedImageSampler, 1}});
    pass->set_ = allocateSet(device, pass->pool_, pass->setLayout_);
    writeSampledImage(device, pass->set_, 0, pass->cube_.view(), pass->sampler_);
    pass->pipeline_ = makeGraphicsPipeline(
        device,
        GraphicsPipelineSettings{.vertexShader = "environment_background.vert",
                                 .fragmentShader = "environment_background.frag",
                                 .colorFormats = {formats.color},
                                 .depthFormat = formats.depth,
                                 .depthTest = formats.depth != vk::Format::eUndefined,
                                 .samples = formats.samples,
                                 .setLayouts = {*pass->setLayout_},
                                 .pushConstants = {{vk::ShaderStageFlagBits::eFragment, 0, sizeof(glm::mat4)}}});
  } catch (const std::exception& error) {
    return fail(std::string("environment: uploading the cube map failed: ") + error.what());
  }
  auto radiance = projectRadianceOnGpu(device, pass->cube_);
  if (!radiance) return std::unexpected(radiance.error());
  SphericalHarmonics9 irradiance = irradianceFromRadiance(*radiance);
  for (glm::vec3& coefficient : irradiance) coefficient /= std::numbers::pi_v<float>;
  pass->irradianceOverPi_ = irradiance;
  return pass;
}

void EnvironmentPass::draw(const vk::raii::CommandBuffer& commands, const Camera& camera, vk::Extent2D extent) const {
  const float aspect = float(extent.width) / float(extent.height);
  // Directions only: the view without its translation.
  const glm::mat4 ndcToDirection = glm::inverse(camera.projection(aspect) * glm::mat4(glm::mat3(camera.view())));
  setViewportAndScissor(commands, extent);
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline_.layout, 0, {*set_}, {});
  commands.pushConstants<glm::mat4>(*pipeline_.layout, vk::ShaderStageFlagBits::eFragment, 0, ndcToDirection);
  commands.draw(3, 1, 0, 0);
}

}  // namespace mane::render
