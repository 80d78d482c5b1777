#include "render/renderer.hpp"

#include <cstring>

namespace mane::render {
namespace {

vk::SampleCountFlagBits sampleCount(std::uint32_t samples) {
  return samples >= 4 ? vk::SampleCountFlagBits::e4 : vk::SampleCountFlagBits::e1;
}

}  // namespace

Renderer::Renderer(const Device& device, const RendererSettings& settings)
    : device_(&device),
      target_(device, {.extent = settings.extent, .samples = sampleCount(settings.msaaSamples)}),
      surfaces_(device, RenderTarget::kHdrFormat, RenderTarget::kDepthFormat, target_.samples()),
      output_(device, target_),
      timer_(device, 8) {}

Result<std::unique_ptr<Renderer>> Renderer::create(const Device& device, const RendererSettings& settings) {
  if (settings.extent.width == 0 || settings.extent.height == 0)
    return fail("the image size must be at least 1x1 pixels");
  if (settings.msaaSamples != 1 && settings.msaaSamples != 4)
    return fail("MSAA must be 1 or 4 samples, not " + std::to_string(settings.msaaSamples));
  const auto& limits = device.limits();
  if (settings.extent.width > limits.maxFramebufferWidth || settings.extent.height > limits.maxFramebufferHeight)
    return fail("the image size " + std::to_string(settings.extent.width) + "x" +
                std::to_string(settings.extent.height) + " exceeds the device's framebuffer limit");
  try {
    return std::unique_ptr<Renderer>(new Renderer(device, settings));
  } catch (const vk::SystemError& error) {
    return fail(std::string("creating the renderer failed: ") + error.what());
  }
}

Result<void> Renderer::setScene(const StaticScene& scene) {
  try {
    surfaces_.setScene(scene);
  } catch (const vk::SystemError& error) {
    return fail(std::string("uploading the scene failed: ") + error.what());
  }
  return {};
}

void Renderer::record(const vk::raii::CommandBuffer& commands, const FrameInput& frame) {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  surfaces_.update(frame, target_.aspect());
  timer_.reset(commands);

  // Main pass: previous contents are discarded (UNDEFINED) and cleared.
  transition(commands, target_.sceneColor(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
             Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
  if (target_.multisampled())
    transition(commands, target_.hdr(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
               Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
  transition(commands, target_.depth(), Layout::eUndefined, Layout::eDepthAttachmentOptimal, Stage::eAllCommands,
             Access::eNone, Stage::eEarlyFragmentTests | Stage::eLateFragmentTests,
             Access::eDepthStencilAttachmentWrite | Access::eDepthStencilAttachmentRead);

  timer_.begin(commands, "surfaces");
  vk::RenderingAttachmentInfo color{
      .imageView = *target_.sceneColor().view(),
      .imageLayout = Layout::eColorAttachmentOptimal,
      .loadOp = vk::AttachmentLoadOp::eClear,
      .storeOp = vk::AttachmentStoreOp::eStore,
      .clearValue = {.color = {.float32 = std::array{frame.background.r, frame.background.g, frame.background.b, 1.0f}}}};
  if (target_.multisampled()) {
    color.resolveMode = vk::ResolveModeFlagBits::eAverage;
    color.resolveImageView = *target_.hdr().view();
    color.resolveImageLayout = Layout::eColorAttachmentOptimal;
    color.storeOp = vk::AttachmentStoreOp::eDontCare;
  }
  const vk::RenderingAttachmentInfo depth{.imageView = *target_.depth().view(),
                                          .imageLayout = Layout::eDepthAttachmentOptimal,
                                          .loadOp = vk::AttachmentLoadOp::eClear,
                                          .storeOp = vk::AttachmentStoreOp::eDontCare,
                                          .clearValue = {.depthStencil = {.depth = 1.0f, .stencil = 0}}};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = target_.extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color,
                                            .pDepthAttachment = &depth});
  setViewportAndScissor(commands, target_.extent());
  surfaces_.draw(commands, frame);
  commands.endRendering();
  timer_.end(commands);

  transition(commands, target_.hdr(), Layout::eColorAttachmentOptimal, Layout::eShaderReadOnlyOptimal,
             Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eFragmentShader,
             Access::eShaderSampledRead);
  transition(commands, target_.output(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eAllCommands,
             Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
  timer_.begin(commands, "output");
  output_.record(commands, target_, frame.exposure);
  timer_.end(commands);
  transition(commands, target_.output(), Layout::eColorAttachmentOptimal, Layout::eTransferSrcOptimal,
             Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eTransfer,
             Access::eTransferRead);
}

Result<std::vector<PassTiming>> Renderer::render(const FrameInput& frame) {
  try {
    device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) { record(commands, frame); });
  } catch (const vk::SystemError& error) {
    return fail(std::string("rendering the frame failed: ") + error.what());
  }
  return timer_.results();
}

Result<std::vector<std::uint8_t>> Renderer::readOutput() const {
  try {
    const auto bytes = readBack(*device_, target_.output(), 4);
    std::vector<std::uint8_t> rgba(bytes.size());
    std::memcpy(rgba.data(), bytes.data(), bytes.size());
    return rgba;
  } catch (const vk::SystemError& error) {
    return fail(std::string("reading the frame back failed: ") + error.what());
  }
}

}  // namespace mane::render
