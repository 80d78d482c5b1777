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
                          .usage = Usage::eDepthStencilAttachment | Usage::eSampled,  // HairOcclusionPass reads it
                          .samples = settings.samples,
                          .aspect = vk::ImageAspectFlagBits::eDepth});
  output_ = Image(
      device,
      {.extent = settings.extent, .format = kOutputFormat, .usage = Usage::eColorAttachment | Usage::eTransferSrc});
}

void RenderTarget::declareScene(FrameGraph::Builder& pass, ScenePart part, bool afterSkin) const {
  const bool starts = part != ScenePart::kRest;
  const bool ends = part != ScenePart::kOpaque;
  pass.write(sceneColor(), ResourceUse::colorAttachment(), starts ? Contents::kDiscard : Contents::kKeep);
  if (multisampled() && ends) pass.write(hdr(), ResourceUse::colorAttachment(), Contents::kDiscard);  // resolved into
  const bool keepsDepth = afterSkin || !starts;
  pass.write(depth(), ResourceUse::depthAttachment(), keepsDepth ? Contents::kKeep : Contents::kDiscard);
  if (afterSkin)
    for (const Image& image : skinGBuffer_)
      pass.read(image, ResourceUse::sampled(vk::PipelineStageFlagBits2::eFragmentShader));
}

void RenderTarget::beginScene(const vk::raii::CommandBuffer& commands, const glm::vec4& clearColor) const {
  FrameGraph graph;
  graph.addPass(
      PassName::kSurfaces, [this](FrameGraph::Builder& pass) { declareScene(pass, ScenePart::kWhole); },
      [this, &clearColor](const vk::raii::CommandBuffer& c) { beginScenePart(c, ScenePart::kWhole, clearColor); });
  graph.compile();
  graph.execute(commands);
}

void RenderTarget::declareSkinGBuffer(FrameGraph::Builder& pass) const {
  for (const Image& image : skinGBuffer_) pass.write(image, ResourceUse::colorAttachment(), Contents::kDiscard);
  pass.write(depth(), ResourceUse::depthAttachment(), Contents::kDiscard);
}

void RenderTarget::beginSkinGBuffer(const vk::raii::CommandBuffer& commands) const {
  using Layout = vk::ImageLayout;
  std::array<vk::RenderingAttachmentInfo, kGBufferImages> colors;
  for (std::size_t i = 0; i < kGBufferImages; ++i) {
    // Not cleared: the lighting reads only where the skin wrote depth, and so every target.
    // Clearing would write all four 32-bit targets (59 MB at 1280×720) every frame for nothing.
    colors[i] = {.imageView = *skinGBuffer_.at(i).view(),
                 .imageLayout = Layout::eColorAttachmentOptimal,
                 .loadOp = vk::AttachmentLoadOp::eDontCare,
                 .storeOp = vk::AttachmentStoreOp::eStore};
  }
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

void RenderTarget::beginScenePart(const vk::raii::CommandBuffer& commands, ScenePart part, const glm::vec4& clearColor,
                                  bool afterSkin) const {
  using Layout = vk::ImageLayout;
  const bool starts = part != ScenePart::kRest;
  const bool ends = part != ScenePart::kOpaque;
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
      .storeOp = vk::AttachmentStoreOp::eStore,  // the glasses read it after the scene
      .clearValue = {.depthStencil = {.depth = 1.0f, .stencil = 0}}};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color,
                                            .pDepthAttachment = &depthAttachment});
  setViewportAndScissor(commands, extent());
}

}  // namespace mane::render
