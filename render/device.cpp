#include "render/device.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>

namespace mane::render {

namespace detail {
struct ValidationLog {
  std::mutex mutex;
  std::vector<std::string> messages;
};
}  // namespace detail

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string versionString(std::uint32_t version) {
  return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
         std::to_string(VK_API_VERSION_PATCH(version));
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* log = static_cast<detail::ValidationLog*>(user);
  const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
  std::lock_guard lock(log->mutex);
  log->messages.push_back(std::string("validation ") + level + ": " + (data->pMessage ? data->pMessage : "?"));
  return VK_FALSE;
}

Result<DevicePreference> preferenceFromEnvironment(DevicePreference fallback) {
  const char* value = std::getenv("MANE_DEVICE");
  if (!value || !*value) return fallback;
  if (std::strcmp(value, "lavapipe") == 0) return DevicePreference::kLavapipe;
  if (std::strcmp(value, "gpu") == 0) return DevicePreference::kGpu;
  return fail(std::string("MANE_DEVICE=") + value + ": expected lavapipe or gpu");
}

bool hasExtension(const std::vector<vk::ExtensionProperties>& available, const char* name) {
  return std::any_of(available.begin(), available.end(),
                     [&](const vk::ExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::optional<std::uint32_t> graphicsComputeFamily(const vk::raii::PhysicalDevice& physical) {
  const auto families = physical.getQueueFamilyProperties();
  for (std::uint32_t i = 0; i < families.size(); ++i) {
    const auto flags = families[i].queueFlags;
    if ((flags & vk::QueueFlagBits::eGraphics) && (flags & vk::QueueFlagBits::eCompute)) return i;
  }
  return std::nullopt;
}

// Lower is better; negative means "not acceptable for this preference".
int rank(const vk::PhysicalDeviceProperties& properties, DevicePreference preference) {
  const bool cpu = properties.deviceType == vk::PhysicalDeviceType::eCpu;
  const bool discrete = properties.deviceType == vk::PhysicalDeviceType::eDiscreteGpu;
  switch (preference) {
    case DevicePreference::kLavapipe: return cpu ? 0 : -1;
    case DevicePreference::kGpu: return cpu ? -1 : (discrete ? 0 : 1);
    case DevicePreference::kAuto: return discrete ? 0 : (cpu ? 2 : 1);
  }
  return -1;
}

}  // namespace

DeviceSettings deviceSettingsFromEnvironment() {
  DeviceSettings settings;
#ifndef NDEBUG
  settings.validation = true;
#endif
  if (const char* value = std::getenv("MANE_VALIDATION")) settings.validation = std::strcmp(value, "0") != 0;
  settings.preference = preferenceFromEnvironment(DevicePreference::kAuto).value_or(DevicePreference::kAuto);
  return settings;
}

Device::Device() : log_(std::make_unique<detail::ValidationLog>()) {}

Device::~Device() {
  // Owners of GPU work are destroyed before the device; wait for it, but never throw here.
  if (*device_) static_cast<void>(device_.getDispatcher()->vkDeviceWaitIdle(*device_));
}

Result<std::unique_ptr<Device>> Device::create(const DeviceSettings& requested) {
  DeviceSettings settings = requested;
  const auto preference = preferenceFromEnvironment(settings.preference);
  if (!preference) return std::unexpected(preference.error());
  settings.preference = *preference;
  std::unique_ptr<Device> self(new Device());
  try {
    const std::uint32_t loaderVersion = self->context_.enumerateInstanceVersion();
    if (loaderVersion < VK_API_VERSION_1_3)
      return fail("the Vulkan loader offers " + versionString(loaderVersion) + "; mane needs Vulkan 1.3");

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    for (const auto& name : settings.instanceExtensions) extensions.push_back(name.c_str());
    if (settings.validation) {
      const auto available = self->context_.enumerateInstanceLayerProperties();
      const bool found = std::any_of(available.begin(), available.end(), [](const vk::LayerProperties& layer) {
        return std::strcmp(layer.layerName, kValidationLayer) == 0;
      });
      if (!found)
        return fail(std::string("validation was asked for, but ") + kValidationLayer +
                    " is not installed (Debian package vulkan-validationlayers)");
      layers.push_back(kValidationLayer);
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }

    const vk::ApplicationInfo appInfo{.pApplicationName = "mane",
                                      .applicationVersion = 1,
                                      .pEngineName = "mane",
                                      .engineVersion = 1,
                                      .apiVersion = VK_API_VERSION_1_3};
    self->instance_ = vk::raii::Instance(
        self->context_, vk::InstanceCreateInfo{.pApplicationInfo = &appInfo,
                                               .enabledLayerCount = static_cast<std::uint32_t>(layers.size()),
                                               .ppEnabledLayerNames = layers.data(),
                                               .enabledExtensionCount = static_cast<std::uint32_t>(extensions.size()),
                                               .ppEnabledExtensionNames = extensions.data()});
    if (settings.validation) {
      self->messenger_ = vk::raii::DebugUtilsMessengerEXT(
          self->instance_,
          vk::DebugUtilsMessengerCreateInfoEXT{.messageSeverity = vk::DebugUtilsMessageSeverityFlagBitsEXT::eWarning |
                                                                  vk::DebugUtilsMessageSeverityFlagBitsEXT::eError,
                                               .messageType = vk::DebugUtilsMessageTypeFlagBitsEXT::eGeneral |
                                                              vk::DebugUtilsMessageTypeFlagBitsEXT::eValidation,
                                               .pfnUserCallback = &onValidationMessage,
                                               .pUserData = self->log_.get()});
    }

    // Choose the best-ranked device that has Vulkan 1.3, a graphics+compute queue and, when a
    // window will present, the swapchain extension.
    vk::raii::PhysicalDevices candidates(self->instance_);
    int bestRank = -1;
    std::string rejected;
    for (auto& candidate : candidates) {
      const auto properties = candidate.getProperties();
      const int candidateRank = rank(properties, settings.preference);
      std::string why;
      if (candidateRank < 0)
        why = "not the kind asked for";
      else if (properties.apiVersion < VK_API_VERSION_1_3)
        why = "Vulkan " + versionString(properties.apiVersion);
      else if (!graphicsComputeFamily(candidate))
        why = "no graphics+compute queue";
      else if (settings.presentation &&
               !hasExtension(candidate.enumerateDeviceExtensionProperties(), VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        why = "no swapchain";
      if (!why.empty()) {
        rejected += std::string(rejected.empty() ? "" : "; ") + properties.deviceName.data() + ": " + why;
        continue;
      }
      if (bestRank < 0 || candidateRank < bestRank) {
        bestRank = candidateRank;
        self->physicalDevice_ = std::move(candidate);
      }
    }
    if (bestRank < 0)
      return fail("no usable Vulkan device" +
                  (rejected.empty() ? std::string(" (none found)") : " (" + rejected + ")") +
                  "; install mesa-vulkan-drivers for lavapipe");

    const vk::raii::PhysicalDevice& physical = self->physicalDevice_;
    const auto properties = physical.getProperties();
    self->limits_ = properties.limits;
    self->queueFamily_ = *graphicsComputeFamily(physical);

    const auto supported = physical.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features,
                                                 vk::PhysicalDeviceVulkan13Features>();
    const auto& core = supported.get<vk::PhysicalDeviceFeatures2>().features;
    const auto& v12 = supported.get<vk::PhysicalDeviceVulkan12Features>();
    const auto& v13 = supported.get<vk::PhysicalDeviceVulkan13Features>();
    if (!v13.dynamicRendering || !v13.synchronization2 || !v13.maintenance4)
      return fail(std::string(properties.deviceName.data()) +
                  " lacks dynamic rendering, synchronization2 or maintenance4 (all required by Vulkan 1.3)");

    vk::StructureChain<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features,
                       vk::PhysicalDeviceVulkan13Features>
        enabled;
    auto& enabledCore = enabled.get<vk::PhysicalDeviceFeatures2>().features;
    enabledCore.samplerAnisotropy = core.samplerAnisotropy;
    enabledCore.independentBlend = core.independentBlend;
    enabledCore.geometryShader = core.geometryShader;
    enabledCore.sampleRateShading = core.sampleRateShading;
    enabledCore.fillModeNonSolid = core.fillModeNonSolid;
    enabledCore.wideLines = core.wideLines;
    self->wideLines_ = core.wideLines == VK_TRUE;
    enabled.get<vk::PhysicalDeviceVulkan12Features>().hostQueryReset = v12.hostQueryReset;
    enabled.get<vk::PhysicalDeviceVulkan12Features>().shaderFloat16 = v12.shaderFloat16;
    // Needed for the DEPTH_ATTACHMENT_OPTIMAL layout of our depth-only images.
    if (!v12.separateDepthStencilLayouts)
      return fail(std::string(properties.deviceName.data()) + " lacks separate depth/stencil layouts");
    enabled.get<vk::PhysicalDeviceVulkan12Features>().separateDepthStencilLayouts = VK_TRUE;
    enabled.get<vk::PhysicalDeviceVulkan13Features>().dynamicRendering = VK_TRUE;
    enabled.get<vk::PhysicalDeviceVulkan13Features>().synchronization2 = VK_TRUE;
    // glslang 12 (Debian 12) declares every compute shader's workgroup size with
    // OpExecutionModeId LocalSizeId, which needs maintenance4
    // (https://github.com/KhronosGroup/glslang/issues/3200).
    enabled.get<vk::PhysicalDeviceVulkan13Features>().maintenance4 = VK_TRUE;

    const float priority = 1.0f;
    const vk::DeviceQueueCreateInfo queueInfo{
        .queueFamilyIndex = self->queueFamily_, .queueCount = 1, .pQueuePriorities = &priority};
    std::vector<const char*> deviceExtensions;
    if (settings.presentation) deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    self->device_ = vk::raii::Device(
        physical, vk::DeviceCreateInfo{.pNext = &enabled.get<vk::PhysicalDeviceFeatures2>(),
                                       .queueCreateInfoCount = 1,
                                       .pQueueCreateInfos = &queueInfo,
                                       .enabledExtensionCount = static_cast<std::uint32_t>(deviceExtensions.size()),
                                       .ppEnabledExtensionNames = deviceExtensions.data()});
    self->queue_ = vk::raii::Queue(self->device_, self->queueFamily_, 0);
    self->commandPool_ = vk::raii::CommandPool(
        self->device_, vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                                 .queueFamilyIndex = self->queueFamily_});

    const auto driver = physical.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties>()
                            .get<vk::PhysicalDeviceDriverProperties>();
    const bool hdrBlend =
        static_cast<bool>(physical.getFormatProperties(vk::Format::eR16G16B16A16Sfloat).optimalTilingFeatures &
                          vk::FormatFeatureFlagBits::eColorAttachmentBlend);
    const bool msaa4 = static_cast<bool>(properties.limits.framebufferColorSampleCounts & vk::SampleCountFlagBits::e4);
    self->info_ = DeviceInfo{.name = properties.deviceName.data(),
                             .driverName = driver.driverName.data(),
                             .driverInfo = driver.driverInfo.data(),
                             .apiVersion = versionString(properties.apiVersion),
                             .software = properties.deviceType == vk::PhysicalDeviceType::eCpu,
                             .features = {
                                 {"dynamic rendering (1.3)", true},
                                 {"synchronization2 (1.3)", true},
                                 {"timestamp queries", properties.limits.timestampComputeAndGraphics == VK_TRUE},
                                 {"RGBA16F colour attachment with blending", hdrBlend},
                                 {"4x MSAA", msaa4},
                                 {"sampler anisotropy", core.samplerAnisotropy == VK_TRUE},
                                 {"independent blend (opacity shadow map targets)", core.independentBlend == VK_TRUE},
                                 {"geometry shaders", core.geometryShader == VK_TRUE},
                                 {"sample rate shading", core.sampleRateShading == VK_TRUE},
                                 {"shader float16", v12.shaderFloat16 == VK_TRUE},
                                 {"host query reset", v12.hostQueryReset == VK_TRUE},
                                 {"validation layers", settings.validation},
                             }};
  } catch (const std::exception& error) {
    return fail(std::string("Vulkan device creation failed: ") + error.what());
  }
  return self;
}

void Device::submitAndWait(const std::function<void(const vk::raii::CommandBuffer&)>& record) const {
  vk::raii::CommandBuffers buffers(
      device_, vk::CommandBufferAllocateInfo{
                   .commandPool = *commandPool_, .level = vk::CommandBufferLevel::ePrimary, .commandBufferCount = 1});
  const vk::raii::CommandBuffer& commands = buffers.front();
  commands.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  record(commands);
  commands.end();
  const vk::raii::Fence fence(device_, vk::FenceCreateInfo{});
  const vk::CommandBufferSubmitInfo commandInfo{.commandBuffer = *commands};
  queue_.submit2(vk::SubmitInfo2{.commandBufferInfoCount = 1, .pCommandBufferInfos = &commandInfo}, *fence);
  if (device_.waitForFences(*fence, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
    throw std::runtime_error("waiting for the GPU failed");
}

std::uint32_t Device::findMemoryType(std::uint32_t typeBits, vk::MemoryPropertyFlags required) const {
  const auto memory = physicalDevice_.getMemoryProperties();
  for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & required) == required) return i;
  throw std::runtime_error("no Vulkan memory type with the required properties");
}

std::vector<std::string> Device::validationMessages() const {
  std::lock_guard lock(log_->mutex);
  return log_->messages;
}

void Device::clearValidationMessages() {
  std::lock_guard lock(log_->mutex);
  log_->messages.clear();
}

}  // namespace mane::render
