#pragma once
// Vulkan instance and device: picks a hardware GPU when there is one and Mesa's lavapipe
// otherwise, turns the validation layers on where asked, and collects their messages so a
// test can fail on any of them.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "render/vulkan.hpp"

namespace mane::render {

namespace detail {
struct ValidationLog;
}

enum class DevicePreference {
  kAuto,      ///< a hardware GPU if present, else lavapipe; MANE_DEVICE=lavapipe|gpu overrides
  kLavapipe,  ///< Mesa's CPU driver
  kGpu,       ///< a hardware GPU; an error when there is none
};

struct DeviceSettings {
  DevicePreference preference = DevicePreference::kAuto;
  /// Khronos validation layer and a messenger that records every warning and error.
  bool validation = false;
  /// Instance extensions a window system needs (from glfwGetRequiredInstanceExtensions).
  std::vector<std::string> instanceExtensions;
  /// Ask for VK_KHR_swapchain on the device (a window will present).
  bool presentation = false;
};

/// A feature the renderer relies on, and whether the chosen device has it.
struct FeatureSupport {
  std::string name;
  bool present = false;
};

/// What `mane info` shows.
struct DeviceInfo {
  std::string name;
  std::string driverName;
  std::string driverInfo;
  std::string apiVersion;  ///< e.g. "1.3.230"
  bool software = false;   ///< a CPU implementation (lavapipe)
  std::vector<FeatureSupport> features;
};

/// The settings the environment asks for: validation from MANE_VALIDATION=1 (always on in
/// debug builds), the device from MANE_DEVICE.
DeviceSettings deviceSettingsFromEnvironment();

class Device {
public:
  /// Creates instance, device and one graphics+compute queue. Returns an error naming what
  /// is missing when no usable Vulkan 1.3 device exists.
  static Result<std::unique_ptr<Device>> create(const DeviceSettings& settings);

  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  ~Device();

  const DeviceInfo& info() const { return info_; }
  const vk::raii::Instance& instance() const { return instance_; }
  const vk::raii::PhysicalDevice& physicalDevice() const { return physicalDevice_; }
  const vk::raii::Device& device() const { return device_; }
  const vk::raii::Queue& queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queueFamily_; }
  const vk::PhysicalDeviceLimits& limits() const { return limits_; }
  /// Whether lines wider than 1 pixel may be drawn (the wideLines feature, enabled where supported).
  bool wideLines() const { return wideLines_; }

  /// Records commands with `record`, submits them and waits for the queue to finish. Not
  /// thread-safe: one thread records at a time (the command pool is shared).
  void submitAndWait(const std::function<void(const vk::raii::CommandBuffer&)>& record) const;

  /// A memory type index with all of `required` among those allowed by `typeBits`.
  std::uint32_t findMemoryType(std::uint32_t typeBits, vk::MemoryPropertyFlags required) const;

  /// Bytes of device memory currently allocated through resources.hpp.
  std::uint64_t allocatedBytes() const { return allocatedBytes_.load(); }
  /// Called by resources.hpp's owners when they allocate (+) or free (−) device memory.
  void trackAllocation(std::int64_t bytes) const { allocatedBytes_ += static_cast<std::uint64_t>(bytes); }

  /// Validation warnings and errors seen so far (empty when validation is off).
  std::vector<std::string> validationMessages() const;
  void clearValidationMessages();

private:
  Device();

  // Declared first so it is destroyed last: the layer may still report while the device and
  // messenger below are destroyed.
  std::unique_ptr<detail::ValidationLog> log_;
  vk::raii::Context context_;
  vk::raii::Instance instance_{nullptr};
  vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
  vk::raii::PhysicalDevice physicalDevice_{nullptr};
  vk::raii::Device device_{nullptr};
  vk::raii::Queue queue_{nullptr};
  vk::raii::CommandPool commandPool_{nullptr};
  std::uint32_t queueFamily_ = 0;
  vk::PhysicalDeviceLimits limits_{};
  bool wideLines_ = false;
  DeviceInfo info_;
  mutable std::atomic<std::uint64_t> allocatedBytes_ = 0;
};

}  // namespace mane::render
