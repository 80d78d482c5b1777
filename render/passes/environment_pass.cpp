#include "render/passes/environment_pass.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <numbers>

#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

constexpr int kMaxCubeSize = 4096;

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
      if (!(t.x >= 0.0f && t.y >= 0.0f && t.z >= 0.0f && std::isfinite(t.x + t.y + t.z)))
        return fail("environment: cube face " + std::to_string(face) + ", texel " + std::to_string(i) +
                    " is negative or not finite");
    }
  }
  return {};
}

// Radiance above fp16's largest value (65504) is clamped to it, not turned into infinity.
std::vector<std::uint16_t> halfTexels(const CubeMap& cube) {
  std::vector<std::uint16_t> halves;
  halves.reserve(std::size_t(cube.size) * std::size_t(cube.size) * 6 * 4);
  for (const std::vector<glm::vec3>& face : cube.faces)
    for (const glm::vec3& texel : face) {
      const glm::vec3 clamped = glm::min(texel, glm::vec3(65504.0f));
      for (int c = 0; c < 3; ++c) halves.push_back(glm::packHalf1x16(clamped[c]));
      halves.push_back(glm::packHalf1x16(1.0f));
    }
  return halves;
}

Image uploadCube(const Device& device, const CubeMap& cube) {
  const auto size = static_cast<std::uint32_t>(cube.size);
  Image image(device, ImageSettings{.extent = {size, size},
                                    .format = vk::Format::eR16G16B16A16Sfloat,
                                    .usage = vk::ImageUsageFlagBits::eSampled | vk::ImageUsageFlagBits::eTransferDst,
                                    .layers = 6,
                                    .cube = true});
  const std::vector<std::uint16_t> halves = halfTexels(cube);
  const std::span<const std::byte> bytes = std::as_bytes(std::span(halves));
  Buffer staging(device, bytes.size(), vk::BufferUsageFlagBits::eTransferSrc,
                 vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  std::memcpy(staging.mapped().data(), bytes.data(), bytes.size());
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    using Stage = vk::PipelineStageFlagBits2;
    using Access = vk::AccessFlagBits2;
    transition(commands, image, vk::ImageLayout::eUndefined, vk::ImageLayout::eTransferDstOptimal, Stage::eNone,
               Access::eNone, Stage::eTransfer, Access::eTransferWrite);
    // The faces lie one after the other in the staging buffer, as the six layers.
    commands.copyBufferToImage(*staging.buffer(), *image.image(), vk::ImageLayout::eTransferDstOptimal,
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 6},
                                                   .imageExtent = {size, size, 1}});
    transition(commands, image, vk::ImageLayout::eTransferDstOptimal, vk::ImageLayout::eShaderReadOnlyOptimal,
               Stage::eTransfer, Access::eTransferWrite, Stage::eFragmentShader, Access::eShaderSampledRead);
  });
  return image;
}

}  // namespace

Result<std::unique_ptr<EnvironmentPass>> EnvironmentPass::create(const Device& device,
                                                                 const EnvironmentData& environment,
                                                                 const Formats& formats) {
  if (auto valid = validate(environment.radiance); !valid) return std::unexpected(valid.error());
  std::unique_ptr<EnvironmentPass> pass(new EnvironmentPass());
  try {
    pass->cube_ = uploadCube(device, environment.radiance);
    pass->sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
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
  SphericalHarmonics9 irradiance = irradianceFromRadiance(projectRadiance(environment.radiance));
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
