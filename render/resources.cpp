#include "render/resources.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

namespace mane::render {

Allocation::Allocation(const Device& device, const vk::MemoryRequirements& requirements,
                       vk::MemoryPropertyFlags properties)
    : device_(&device),
      memory_(device.device(), vk::MemoryAllocateInfo{.allocationSize = requirements.size,
                                                      .memoryTypeIndex = device.findMemoryType(
                                                          requirements.memoryTypeBits, properties)}),
      size_(requirements.size) {
  device.trackAllocation(static_cast<std::int64_t>(size_));
}

Allocation::Allocation(Allocation&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)),
      memory_(std::move(other.memory_)),
      size_(std::exchange(other.size_, 0)) {}

Allocation& Allocation::operator=(Allocation&& other) noexcept {
  if (this != &other) {
    if (device_) device_->trackAllocation(-static_cast<std::int64_t>(size_));
    device_ = std::exchange(other.device_, nullptr);
    memory_ = std::move(other.memory_);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

Allocation::~Allocation() {
  if (device_) device_->trackAllocation(-static_cast<std::int64_t>(size_));
}

Buffer::Buffer(const Device& device, vk::DeviceSize size, vk::BufferUsageFlags usage,
               vk::MemoryPropertyFlags properties)
    : buffer_(device.device(), vk::BufferCreateInfo{.size = size, .usage = usage}), size_(size), usage_(usage) {
  allocation_ = Allocation(device, buffer_.getMemoryRequirements(), properties);
  buffer_.bindMemory(*allocation_.memory(), 0);
  if (properties & vk::MemoryPropertyFlagBits::eHostVisible)
    mapped_ = {static_cast<std::byte*>(allocation_.memory().mapMemory(0, size)), static_cast<std::size_t>(size)};
}

Buffer Buffer::withData(const Device& device, std::span<const std::byte> bytes, vk::BufferUsageFlags usage) {
  const vk::DeviceSize size = std::max<vk::DeviceSize>(bytes.size(), 4);
  Buffer staging(device, size, vk::BufferUsageFlagBits::eTransferSrc,
                 vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  // Not memcpy: an empty span (the buffer is then 4 bytes of nothing) has a null data(), which
  // memcpy may not be given even for zero bytes.
  std::ranges::copy(bytes, staging.mapped().begin());
  Buffer result(device, size, usage | vk::BufferUsageFlagBits::eTransferDst, vk::MemoryPropertyFlagBits::eDeviceLocal);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    commands.copyBuffer(*staging.buffer(), *result.buffer(), vk::BufferCopy{.size = size});
  });
  return result;
}

Image::Image(const Device& device, const ImageSettings& settings)
    : settings_(settings),
      image_(device.device(),
             vk::ImageCreateInfo{
                 .flags = settings.cube ? vk::ImageCreateFlagBits::eCubeCompatible : vk::ImageCreateFlags{},
                 .imageType = settings.depth > 0 ? vk::ImageType::e3D : vk::ImageType::e2D,
                 .format = settings.format,
                 .extent = {settings.extent.width, settings.extent.height, std::max(settings.depth, 1u)},
                 .mipLevels = settings.mipLevels,
                 .arrayLayers = settings.layers,
                 .samples = settings.samples,
                 .tiling = vk::ImageTiling::eOptimal,
                 .usage = settings.usage,
                 .initialLayout = vk::ImageLayout::eUndefined}) {
  allocation_ = Allocation(device, image_.getMemoryRequirements(), vk::MemoryPropertyFlagBits::eDeviceLocal);
  image_.bindMemory(*allocation_.memory(), 0);
  view_ = vk::raii::ImageView(
      device.device(),
      vk::ImageViewCreateInfo{.image = *image_,
                              .viewType = settings.cube         ? vk::ImageViewType::eCube
                                          : settings.depth > 0  ? vk::ImageViewType::e3D
                                          : settings.layers > 1 ? vk::ImageViewType::e2DArray
                                                                : vk::ImageViewType::e2D,
                              .format = settings.format,
                              .subresourceRange = {settings.aspect, 0, settings.mipLevels, 0, settings.layers}});
}

void imageBarrier(const vk::raii::CommandBuffer& commands, vk::Image image, const vk::ImageSubresourceRange& range,
                  vk::ImageLayout from, vk::ImageLayout to, vk::PipelineStageFlags2 srcStage,
                  vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage, vk::AccessFlags2 dstAccess) {
  const vk::ImageMemoryBarrier2 barrier{.srcStageMask = srcStage,
                                        .srcAccessMask = srcAccess,
                                        .dstStageMask = dstStage,
                                        .dstAccessMask = dstAccess,
                                        .oldLayout = from,
                                        .newLayout = to,
                                        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                        .image = image,
                                        .subresourceRange = range};
  commands.pipelineBarrier2(vk::DependencyInfo{.imageMemoryBarrierCount = 1, .pImageMemoryBarriers = &barrier});
}

void transition(const vk::raii::CommandBuffer& commands, const Image& image, vk::ImageLayout from, vk::ImageLayout to,
                vk::PipelineStageFlags2 srcStage, vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage,
                vk::AccessFlags2 dstAccess) {
  imageBarrier(commands, *image.image(),
               {image.settings().aspect, 0, image.settings().mipLevels, 0, image.settings().layers}, from, to, srcStage,
               srcAccess, dstStage, dstAccess);
}

Image Image::texture(const Device& device, std::uint32_t width, std::uint32_t height,
                     std::span<const std::uint8_t> rgba, vk::Format format) {
  // Callers validate at their boundary (Renderer::setScene); this guards the GPU copy.
  if (width == 0 || height == 0 || rgba.size() != std::size_t(width) * height * 4)
    throw std::invalid_argument("texture texels do not match its size");
  const std::uint32_t mipLevels = std::bit_width(std::max(width, height));
  Image result(device, ImageSettings{.extent = {width, height},
                                     .format = format,
                                     .usage = vk::ImageUsageFlagBits::eSampled | vk::ImageUsageFlagBits::eTransferDst |
                                              vk::ImageUsageFlagBits::eTransferSrc,
                                     .mipLevels = mipLevels});
  Buffer staging(device, rgba.size(), vk::BufferUsageFlagBits::eTransferSrc,
                 vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  std::memcpy(staging.mapped().data(), rgba.data(), rgba.size());

  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    const vk::Image image = *result.image();
    auto mipBarrier = [&](std::uint32_t level, vk::ImageLayout from, vk::ImageLayout to, vk::PipelineStageFlags2 src,
                          vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dst, vk::AccessFlags2 dstAccess) {
      imageBarrier(commands, image, {vk::ImageAspectFlagBits::eColor, level, 1, 0, 1}, from, to, src, srcAccess, dst,
                   dstAccess);
    };
    using Stage = vk::PipelineStageFlagBits2;
    using Access = vk::AccessFlagBits2;
    using Layout = vk::ImageLayout;
    transition(commands, result, Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone, Access::eNone,
               Stage::eTransfer, Access::eTransferWrite);
    commands.copyBufferToImage(*staging.buffer(), image, Layout::eTransferDstOptimal,
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                                   .imageExtent = {width, height, 1}});
    // Each level is a linear box-filtered blit of the one above it.
    std::int32_t w = static_cast<std::int32_t>(width), h = static_cast<std::int32_t>(height);
    for (std::uint32_t level = 1; level < mipLevels; ++level) {
      mipBarrier(level - 1, Layout::eTransferDstOptimal, Layout::eTransferSrcOptimal, Stage::eTransfer,
                 Access::eTransferWrite, Stage::eTransfer, Access::eTransferRead);
      const std::int32_t nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
      const vk::ImageBlit blit{.srcSubresource = {vk::ImageAspectFlagBits::eColor, level - 1, 0, 1},
                               .srcOffsets = std::array{vk::Offset3D{0, 0, 0}, vk::Offset3D{w, h, 1}},
                               .dstSubresource = {vk::ImageAspectFlagBits::eColor, level, 0, 1},
                               .dstOffsets = std::array{vk::Offset3D{0, 0, 0}, vk::Offset3D{nw, nh, 1}}};
      commands.blitImage(image, Layout::eTransferSrcOptimal, image, Layout::eTransferDstOptimal, blit,
                         vk::Filter::eLinear);
      mipBarrier(level - 1, Layout::eTransferSrcOptimal, Layout::eShaderReadOnlyOptimal, Stage::eTransfer,
                 Access::eTransferRead, Stage::eFragmentShader, Access::eShaderSampledRead);
      w = nw;
      h = nh;
    }
    mipBarrier(mipLevels - 1, Layout::eTransferDstOptimal, Layout::eShaderReadOnlyOptimal, Stage::eTransfer,
               Access::eTransferWrite, Stage::eFragmentShader, Access::eShaderSampledRead);
  });
  return result;
}

std::vector<std::byte> readBack(const Device& device, const Image& image, std::uint32_t bytesPerTexel) {
  const vk::Extent2D extent = image.extent();
  const vk::DeviceSize size = vk::DeviceSize(extent.width) * extent.height * bytesPerTexel;
  Buffer host(device, size, vk::BufferUsageFlagBits::eTransferDst,
              vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    commands.copyImageToBuffer(*image.image(), vk::ImageLayout::eTransferSrcOptimal, *host.buffer(),
                               vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                                   .imageExtent = {extent.width, extent.height, 1}});
    const vk::MemoryBarrier2 toHost{.srcStageMask = vk::PipelineStageFlagBits2::eTransfer,
                                    .srcAccessMask = vk::AccessFlagBits2::eTransferWrite,
                                    .dstStageMask = vk::PipelineStageFlagBits2::eHost,
                                    .dstAccessMask = vk::AccessFlagBits2::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
  });
  const auto bytes = host.mapped();
  return {bytes.begin(), bytes.end()};
}

vk::raii::Sampler makeLinearSampler(const Device& device, vk::SamplerAddressMode address, float maxAnisotropy) {
  const bool anisotropic = maxAnisotropy > 1.0f;
  return vk::raii::Sampler(device.device(), vk::SamplerCreateInfo{.magFilter = vk::Filter::eLinear,
                                                                  .minFilter = vk::Filter::eLinear,
                                                                  .mipmapMode = vk::SamplerMipmapMode::eLinear,
                                                                  .addressModeU = address,
                                                                  .addressModeV = address,
                                                                  .addressModeW = address,
                                                                  .anisotropyEnable = anisotropic,
                                                                  .maxAnisotropy = anisotropic ? maxAnisotropy : 1.0f,
                                                                  .maxLod = VK_LOD_CLAMP_NONE});
}

}  // namespace mane::render
