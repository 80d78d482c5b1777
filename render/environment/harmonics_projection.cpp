#include "render/environment/harmonics_projection.hpp"

#include <array>
#include <string>

#include <glm/vec4.hpp>
#include <glm/vec3.hpp>

#include "render/descriptors.hpp"
#include "render/pipelines.hpp"

namespace mane::render {

Result<SphericalHarmonics9> projectRadianceOnGpu(const Device& device, const Image& cube) {
  const std::uint32_t size = cube.extent().width;
  const std::size_t rows = std::size_t(size) * 6;
  try {
    // The pipeline, the view of the faces as layers and the row sums live only for the projection.
    const vk::raii::DescriptorSetLayout setLayout =
        makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, vk::ShaderStageFlagBits::eCompute},
                               {vk::DescriptorType::eStorageBuffer, vk::ShaderStageFlagBits::eCompute}});
    const Pipeline pipeline =
        makeComputePipeline(device, "environment_harmonics.comp", setLayout, sizeof(std::uint32_t));
    const vk::raii::DescriptorPool pool = makeDescriptorPool(
        device, 1, {{vk::DescriptorType::eCombinedImageSampler, 1}, {vk::DescriptorType::eStorageBuffer, 1}});
    const vk::raii::ImageView faces(
        device.device(), vk::ImageViewCreateInfo{.image = *cube.image(),
                                                 .viewType = vk::ImageViewType::e2DArray,
                                                 .format = cube.format(),
                                                 .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 6}});
    const vk::raii::Sampler sampler = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
    Buffer sums(device, rows * 9 * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer,
                vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    const vk::raii::DescriptorSet set = allocateSet(device, pool, setLayout);
    writeSampledImage(device, set, 0, faces, sampler);
    writeStorageBuffer(device, set, 1, sums);
    device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
      commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, {*set}, {});
      commands.pushConstants<std::uint32_t>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0, size);
      commands.dispatch(size, 6, 1);
      const vk::MemoryBarrier2 toHost{.srcStageMask = vk::PipelineStageFlagBits2::eComputeShader,
                                      .srcAccessMask = vk::AccessFlagBits2::eShaderStorageWrite,
                                      .dstStageMask = vk::PipelineStageFlagBits2::eHost,
                                      .dstAccessMask = vk::AccessFlagBits2::eHostRead};
      commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
    });
    // The rows added in double, face by face and row by row.
    const auto* rowSums = reinterpret_cast<const glm::vec4*>(sums.mapped().data());
    std::array<glm::dvec3, 9> total{};
    for (std::size_t row = 0; row < rows; ++row)
      for (std::size_t i = 0; i < 9; ++i) total[i] += glm::dvec3(rowSums[row * 9 + i]);
    SphericalHarmonics9 result;
    for (std::size_t i = 0; i < 9; ++i) result[i] = glm::vec3(total[i]);
    return result;
  } catch (const std::exception& error) {
    return fail(std::string("environment: projecting the cube map on spherical harmonics failed: ") + error.what());
  }
}

}  // namespace mane::render
