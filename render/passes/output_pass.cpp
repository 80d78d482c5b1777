#include "render/passes/output_pass.hpp"

#include "render/descriptors.hpp"

namespace mane::render {

OutputPass::OutputPass(const Device& device, const RenderTarget& target) {
  layout_ = makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, vk::ShaderStageFlagBits::eFragment}});
  pipeline_ = makeGraphicsPipeline(
      device, GraphicsPipelineSettings{.vertexShader = "fullscreen.vert",
                                       .fragmentShader = "output.frag",
                                       .colorFormats = {RenderTarget::kOutputFormat},
                                       .setLayouts = {*layout_},
                                       .pushConstants = {{vk::ShaderStageFlagBits::eFragment, 0, sizeof(float)}}});
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
  pool_ = makeDescriptorPool(device, 1, {{vk::DescriptorType::eCombinedImageSampler, 1}});
  set_ = allocateSet(device, pool_, layout_);
  writeSampledImage(device, set_, 0, target.hdr(), sampler_);
}

void OutputPass::record(const vk::raii::CommandBuffer& commands, const RenderTarget& target, float exposure) const {
  const vk::RenderingAttachmentInfo color{.imageView = *target.output().view(),
                                          .imageLayout = vk::ImageLayout::eColorAttachmentOptimal,
                                          .loadOp = vk::AttachmentLoadOp::eDontCare,
                                          .storeOp = vk::AttachmentStoreOp::eStore};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = target.extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color});
  setViewportAndScissor(commands, target.extent());
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline_.layout, 0, {*set_}, {});
  commands.pushConstants<float>(*pipeline_.layout, vk::ShaderStageFlagBits::eFragment, 0, exposure);
  commands.draw(3, 1, 0, 0);
  commands.endRendering();
}

}  // namespace mane::render
