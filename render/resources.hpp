#pragma once
// Owners of GPU memory: buffers, images with their views, samplers. Each owns its Vulkan
// objects through vk::raii and reports its bytes to the Device so memory use is measurable.

#include <cstdint>
#include <span>
#include <vector>

#include "render/device.hpp"

namespace mane::render {

/// Device memory bound to one buffer or image, counted in Device::allocatedBytes().
class Allocation {
public:
  Allocation() = default;
  Allocation(const Device& device, const vk::MemoryRequirements& requirements, vk::MemoryPropertyFlags properties);
  Allocation(Allocation&& other) noexcept;
  Allocation& operator=(Allocation&& other) noexcept;
  ~Allocation();

  const vk::raii::DeviceMemory& memory() const { return memory_; }
  vk::DeviceSize size() const { return size_; }

private:
  const Device* device_ = nullptr;
  vk::raii::DeviceMemory memory_{nullptr};
  vk::DeviceSize size_ = 0;
};

class Buffer {
public:
  Buffer() = default;
  /// A buffer of `size` bytes. Host-visible buffers stay mapped for their lifetime.
  Buffer(const Device& device, vk::DeviceSize size, vk::BufferUsageFlags usage, vk::MemoryPropertyFlags properties);

  /// A device-local buffer filled with `bytes` through a staging copy.
  static Buffer withData(const Device& device, std::span<const std::byte> bytes, vk::BufferUsageFlags usage);

  const vk::raii::Buffer& buffer() const { return buffer_; }
  vk::DeviceSize size() const { return size_; }
  vk::BufferUsageFlags usage() const { return usage_; }
  /// The mapped bytes of a host-visible buffer, empty otherwise.
  std::span<std::byte> mapped() const { return mapped_; }

private:
  vk::raii::Buffer buffer_{nullptr};
  Allocation allocation_;
  vk::DeviceSize size_ = 0;
  vk::BufferUsageFlags usage_{};
  std::span<std::byte> mapped_;
};

struct ImageSettings {
  vk::Extent2D extent{};
  vk::Format format = vk::Format::eR8G8B8A8Unorm;
  vk::ImageUsageFlags usage{};
  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  std::uint32_t mipLevels = 1;
  vk::ImageAspectFlags aspect = vk::ImageAspectFlagBits::eColor;
  std::uint32_t layers = 1;  ///< more than 1: an array image, viewed as a 2D array
  bool cube = false;         ///< six layers viewed as a cube map (+X, −X, +Y, −Y, +Z, −Z)
  std::uint32_t depth = 0;   ///< 0: a 2D image; otherwise a 3D image of this many slices
};

class Image {
public:
  Image() = default;
  Image(const Device& device, const ImageSettings& settings);

  /// A sampled 2D texture with a full mip chain, uploaded from tightly packed RGBA8 texels.
  static Image texture(const Device& device, std::uint32_t width, std::uint32_t height,
                       std::span<const std::uint8_t> rgba, vk::Format format);

  const vk::raii::Image& image() const { return image_; }
  const vk::raii::ImageView& view() const { return view_; }
  const ImageSettings& settings() const { return settings_; }
  vk::Extent2D extent() const { return settings_.extent; }
  vk::Format format() const { return settings_.format; }

private:
  ImageSettings settings_;
  vk::raii::Image image_{nullptr};
  Allocation allocation_;
  vk::raii::ImageView view_{nullptr};
};

/// One image memory barrier with a layout transition (synchronization2), for `range` of `image`.
void imageBarrier(const vk::raii::CommandBuffer& commands, vk::Image image, const vk::ImageSubresourceRange& range,
                  vk::ImageLayout from, vk::ImageLayout to, vk::PipelineStageFlags2 srcStage,
                  vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage, vk::AccessFlags2 dstAccess);

/// `imageBarrier` over the whole image, all mips.
void transition(const vk::raii::CommandBuffer& commands, const Image& image, vk::ImageLayout from, vk::ImageLayout to,
                vk::PipelineStageFlags2 srcStage, vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage,
                vk::AccessFlags2 dstAccess);

/// Copies a single-sample colour image (in TRANSFER_SRC layout) into host memory, tightly
/// packed, with the transfer→host barrier the spec asks for before mapping.
std::vector<std::byte> readBack(const Device& device, const Image& image, std::uint32_t bytesPerTexel);

vk::raii::Sampler makeLinearSampler(const Device& device, vk::SamplerAddressMode address, float maxAnisotropy);

}  // namespace mane::render
