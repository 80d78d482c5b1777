#include "render/render_target.hpp"

#include "render/pipelines.hpp"

namespace mane::render {

RenderTarget::RenderTarget(const Device& device, const RenderTargetSettings& settings) : settings_(settings) {
  using Usage = vk::ImageUsageFlagBits;
  if (multisampled())
    msaaColor_ = Image(device, {.extent = settings.extent,
                                .format = kHdrFormat,
                                .usage = Usage::eColorAttachment | Usage::eTransientAttachment,
                                .samples = settings.samples});
  hdr_ = Image(device, {.extent = settings.extent,
                        .format = kHdrFormat,
                        .usage = Usage::eColorAttachment | Usage::eSampled | Usage::eTransferSrc});
  depth_ = Image(device, {.extent = settings.extent,
                          .format = kDepthFormat,
                          .usage = Usage::eDepthStencilAttachment,
                          .samples = settings.samples,
                          .aspect = vk::ImageAspectFlagBits::eDepth});
  output_ = Image(
      device,
      {.extent = settings.extent, .format = kOutputFormat, .usage = Usage::eColorAttachment | Usage::eTransferSrc});
}

void RenderTarget::beginScene(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor) const {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  transition(commands, sceneColor(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
             Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
  if (multisampled())
    transition(commands, hdr(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands, Access::eNone,
               Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
  transition(commands, depth(), Layout::eUndefined, Layout::eDepthAttachmentOptimal, Stage::eAllCommands, Access::eNone,
             Stage::eEarlyFragmentTests | Stage::eLateFragmentTests,
             Access::eDepthStencilAttachmentWrite | Access::eDepthStencilAttachmentRead);
  vk::RenderingAttachmentInfo color{
      .imageView = *sceneColor().view(),
      .imageLayout = Layout::eColorAttachmentOptimal,
      .loadOp = vk::AttachmentLoadOp::eClear,
      .storeOp = vk::AttachmentStoreOp::eStore,
      .clearValue = {.color = {.float32 = std::array{clearColor.r, clearColor.g, clearColor.b, clearColor.a}}}};
  if (multisampled()) {
    color.resolveMode = vk::ResolveModeFlagBits::eAverage;
    color.resolveImageView = *hdr().view();
    color.resolveImageLayout = Layout::eColorAttachmentOptimal;
    color.storeOp = vk::AttachmentStoreOp::eDontCare;
  }
  const vk::RenderingAttachmentInfo depthAttachment{.imageView = *depth().view(),
                                                    .imageLayout = Layout::eDepthAttachmentOptimal,
                                                    .loadOp = vk::AttachmentLoadOp::eClear,
                                                    .storeOp = vk::AttachmentStoreOp::eDontCare,
                                                    .clearValue = {.depthStencil = {.depth = 1.0f, .stencil = 0}}};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color,
                                            .pDepthAttachment = &depthAttachment});
  setViewportAndScissor(commands, extent());
}

}  // namespace mane::render
