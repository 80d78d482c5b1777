#include "render/render_target.hpp"

#include <array>

#include "render/pipelines.hpp"

namespace mane::render {

RenderTarget::RenderTarget(const Device& device, const RenderTargetSettings& settings) : settings_(settings) {
  using Usage = vk::ImageUsageFlagBits;
  if (multisampled())
    msaaColor_ = Image(device, {.extent = settings.extent,
                                .format = kHdrFormat,
                                .usage = Usage::eColorAttachment,  // kept between the scene's two halves
                                .samples = settings.samples});
  hdr_ = Image(device, {.extent = settings.extent,
                        .format = kHdrFormat,
                        .usage = Usage::eColorAttachment | Usage::eSampled | Usage::eTransferSrc});
  if (settings.skinGBuffer && !multisampled())
    for (std::size_t i = 0; i < kGBufferImages; ++i)
      skinGBuffer_.emplace_back(device, ImageSettings{.extent = settings.extent,
                                                      .format = kGBufferFormat,
                                                      .usage = Usage::eColorAttachment | Usage::eSampled});
  depth_ = Image(device, {.extent = settings.extent,
                          .format = kDepthFormat,
                          .usage = Usage::eDepthStencilAttachment | Usage::eSampled,  // HairOcclusion reads it
                          .samples = settings.samples,
                          .aspect = vk::ImageAspectFlagBits::eDepth});
  output_ = Image(
      device,
      {.extent = settings.extent, .format = kOutputFormat, .usage = Usage::eColorAttachment | Usage::eTransferSrc});
}

void RenderTarget::beginScene(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor,
                              bool afterSkin) const {
  begin(commands, clearColor, ScenePart::kWhole, afterSkin);
}

void RenderTarget::beginOpaque(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor,
                               bool afterSkin) const {
  begin(commands, clearColor, ScenePart::kOpaque, afterSkin);
}

void RenderTarget::resumeScene(const vk::raii::CommandBuffer& commands) const {
  begin(commands, glm::vec4(0.0f), ScenePart::kRest, false);
}

void RenderTarget::beginSkinGBuffer(const vk::raii::CommandBuffer& commands) const {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  std::array<vk::RenderingAttachmentInfo, kGBufferImages> colors;
  for (std::size_t i = 0; i < kGBufferImages; ++i) {
    transition(commands, skinGBuffer_.at(i), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
               Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
    // Not cleared: the lighting reads only where the skin wrote depth, and so every target.
    // Clearing the four 32-bit targets (59 MB at 1280×720) took lavapipe about 10 ms a frame.
    colors[i] = {.imageView = *skinGBuffer_[i].view(),
                 .imageLayout = Layout::eColorAttachmentOptimal,
                 .loadOp = vk::AttachmentLoadOp::eDontCare,
                 .storeOp = vk::AttachmentStoreOp::eStore};
  }
  transition(commands, depth(), Layout::eUndefined, Layout::eDepthAttachmentOptimal, Stage::eAllCommands, Access::eNone,
             Stage::eEarlyFragmentTests | Stage::eLateFragmentTests,
             Access::eDepthStencilAttachmentWrite | Access::eDepthStencilAttachmentRead);
  const vk::RenderingAttachmentInfo depthAttachment{.imageView = *depth().view(),
                                                    .imageLayout = Layout::eDepthAttachmentOptimal,
                                                    .loadOp = vk::AttachmentLoadOp::eClear,
                                                    .storeOp = vk::AttachmentStoreOp::eStore,
                                                    .clearValue = {.depthStencil = {.depth = 1.0f, .stencil = 0}}};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = static_cast<std::uint32_t>(colors.size()),
                                            .pColorAttachments = colors.data(),
                                            .pDepthAttachment = &depthAttachment});
  setViewportAndScissor(commands, extent());
}

void RenderTarget::begin(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor, ScenePart part,
                         bool afterSkin) const {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  const bool starts = part != ScenePart::kRest;
  const bool ends = part != ScenePart::kOpaque;
  const auto depthTests = Stage::eEarlyFragmentTests | Stage::eLateFragmentTests;
  if (starts) {
    transition(commands, sceneColor(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
               Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
    if (multisampled())
      transition(commands, hdr(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
                 Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
  }
  if (afterSkin) {
    // The G-buffer pass's writes, before this pass reads the G-buffer and tests against its depth.
    for (const Image& image : skinGBuffer_)
      transition(commands, image, Layout::eColorAttachmentOptimal, Layout::eShaderReadOnlyOptimal,
                 Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eFragmentShader,
                 Access::eShaderSampledRead);
    const vk::MemoryBarrier2 depthDrawn{
        .srcStageMask = depthTests,
        .srcAccessMask = Access::eDepthStencilAttachmentWrite,
        .dstStageMask = depthTests,
        .dstAccessMask = Access::eDepthStencilAttachmentRead | Access::eDepthStencilAttachmentWrite};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &depthDrawn});
  } else if (starts) {
    transition(commands, depth(), Layout::eUndefined, Layout::eDepthAttachmentOptimal, Stage::eAllCommands,
               Access::eNone, depthTests, Access::eDepthStencilAttachmentWrite | Access::eDepthStencilAttachmentRead);
  } else {
    // The first half's colour and depth writes, before this half blends over them and tests against them.
    const vk::MemoryBarrier2 drawn{
        .srcStageMask = Stage::eColorAttachmentOutput | depthTests,
        .srcAccessMask = Access::eColorAttachmentWrite | Access::eDepthStencilAttachmentWrite,
        .dstStageMask = Stage::eColorAttachmentOutput | depthTests,
        .dstAccessMask = Access::eColorAttachmentRead | Access::eColorAttachmentWrite |
                         Access::eDepthStencilAttachmentRead | Access::eDepthStencilAttachmentWrite};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &drawn});
  }
  const vk::AttachmentLoadOp load = starts ? vk::AttachmentLoadOp::eClear : vk::AttachmentLoadOp::eLoad;
  vk::RenderingAttachmentInfo color{
      .imageView = *sceneColor().view(),
      .imageLayout = Layout::eColorAttachmentOptimal,
      .loadOp = load,
      .storeOp = vk::AttachmentStoreOp::eStore,
      .clearValue = {.color = {.float32 = std::array{clearColor.r, clearColor.g, clearColor.b, clearColor.a}}}};
  if (multisampled() && ends) {
    color.resolveMode = vk::ResolveModeFlagBits::eAverage;
    color.resolveImageView = *hdr().view();
    color.resolveImageLayout = Layout::eColorAttachmentOptimal;
    color.storeOp = vk::AttachmentStoreOp::eDontCare;
  }
  const vk::RenderingAttachmentInfo depthAttachment{
      .imageView = *depth().view(),
      .imageLayout = Layout::eDepthAttachmentOptimal,
      .loadOp = afterSkin ? vk::AttachmentLoadOp::eLoad : load,
      .storeOp = ends ? vk::AttachmentStoreOp::eDontCare : vk::AttachmentStoreOp::eStore,
      .clearValue = {.depthStencil = {.depth = 1.0f, .stencil = 0}}};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color,
                                            .pDepthAttachment = &depthAttachment});
  setViewportAndScissor(commands, extent());
}

}  // namespace mane::render
