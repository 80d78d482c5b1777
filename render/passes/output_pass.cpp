#include "render/passes/output_pass.hpp"

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

// Push constants of shaders/output.frag.
struct OutputConstants {
  float exposure;
  float glowStrength;
  glm::vec2 glowUvScale;
  float godRays;
};

bool glows(const PostSettings& post) {
  return post.glowStrength > 0.0f;
}

// Only where the chain made them this frame: no light on screen, no rays (and the plain pipeline).
bool addsGodRays(const PostSettings& post, const PostChain& chain) {
  return post.godRays > 0.0f && chain.godRaysRecorded();
}

std::size_t variantOf(const PostSettings& post, bool godRays) {
  return 8 * std::size_t(post.toneMapping == ToneMapping::kReinhard) + 4 * std::size_t(post.autoGain) +
         2 * std::size_t(glows(post)) + std::size_t(godRays);
}

}  // namespace

OutputPass::OutputPass(const Device& device, const RenderTarget& target, const PostChain& post)
    : device_(&device), post_(&post) {
  const vk::ShaderStageFlags fragment = vk::ShaderStageFlagBits::eFragment;
  layout_ = makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, fragment},
                                   {vk::DescriptorType::eCombinedImageSampler, fragment},
                                   {vk::DescriptorType::eStorageBuffer, fragment},
                                   {vk::DescriptorType::eCombinedImageSampler, fragment}});
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
  pool_ = makeDescriptorPool(device, 1,
                             {{vk::DescriptorType::eCombinedImageSampler, 3}, {vk::DescriptorType::eStorageBuffer, 1}});
  set_ = allocateSet(device, pool_, layout_);
  writeSampledImage(device, set_, 0, target.hdr(), sampler_);
  // The glow and the god rays stay in GENERAL layout (the post chain writes them as storage images).
  const auto writeGeneral = [&](std::uint32_t binding, const Image& image) {
    const vk::DescriptorImageInfo info{
        .sampler = *post.sampler(), .imageView = *image.view(), .imageLayout = vk::ImageLayout::eGeneral};
    device.device().updateDescriptorSets(
        vk::WriteDescriptorSet{.dstSet = *set_,
                               .dstBinding = binding,
                               .descriptorCount = 1,
                               .descriptorType = vk::DescriptorType::eCombinedImageSampler,
                               .pImageInfo = &info},
        {});
  };
  writeGeneral(1, post.glow());
  writeStorageBuffer(device, set_, 2, post.exposureState());
  writeGeneral(3, post.godRays());
  pipelineFor(PostSettings{}, false);
}

const Pipeline& OutputPass::pipelineFor(const PostSettings& post, bool godRays) {
  Pipeline& pipeline = pipelines_[variantOf(post, godRays)];
  if (*pipeline.pipeline) return pipeline;
  pipeline = makeGraphicsPipeline(
      *device_,
      GraphicsPipelineSettings{.vertexShader = "fullscreen.vert",
                               .fragmentShader = "output.frag",
                               .colorFormats = {RenderTarget::kOutputFormat},
                               .setLayouts = {*layout_},
                               .pushConstants = {{vk::ShaderStageFlagBits::eFragment, 0, sizeof(OutputConstants)}},
                               .constants = {std::uint32_t(post.toneMapping), std::uint32_t(post.autoGain),
                                             std::uint32_t(glows(post)), std::uint32_t(godRays)}});
  return pipeline;
}

void OutputPass::record(const vk::raii::CommandBuffer& commands, const RenderTarget& target, float exposure,
                        const PostSettings& post) {
  const bool godRays = addsGodRays(post, *post_);
  const Pipeline& pipeline = pipelineFor(post, godRays);
  const vk::RenderingAttachmentInfo color{.imageView = *target.output().view(),
                                          .imageLayout = vk::ImageLayout::eColorAttachmentOptimal,
                                          .loadOp = vk::AttachmentLoadOp::eDontCare,
                                          .storeOp = vk::AttachmentStoreOp::eStore};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = target.extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color});
  setViewportAndScissor(commands, target.extent());
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline.layout, 0, {*set_}, {});
  const OutputConstants constants{.exposure = exposure,
                                  .glowStrength = post.glowStrength,
                                  .glowUvScale = post_->glowUvScale(),
                                  .godRays = godRays ? post.godRays : 0.0f};
  commands.pushConstants<OutputConstants>(*pipeline.layout, vk::ShaderStageFlagBits::eFragment, 0, constants);
  commands.draw(3, 1, 0, 0);
  commands.endRendering();
}

}  // namespace mane::render
