#include "render/render_target.hpp"

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

}  // namespace mane::render
