#include "render/window.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdlib>

namespace mane::render {

Result<std::unique_ptr<Window>> Window::open(const std::string& title, std::uint32_t width, std::uint32_t height) {
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
    return fail(
        "no display ($DISPLAY and $WAYLAND_DISPLAY are unset); use `mane render` for headless output "
        "or run under Xvfb (xvfb-run mane view ...)");
  if (!glfwInit()) {
    const char* reason = nullptr;
    glfwGetError(&reason);
    return fail(std::string("GLFW could not start: ") + (reason ? reason : "unknown reason"));
  }
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    return fail("GLFW finds no Vulkan loader that can present to this display");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  std::unique_ptr<Window> window(new Window());
  window->window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!window->window_) {
    const char* reason = nullptr;
    glfwGetError(&reason);
    glfwTerminate();
    return fail(std::string("could not open a window: ") + (reason ? reason : "unknown reason"));
  }
  return window;
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() const {
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  return {names, names + count};
}

bool Window::shouldClose() const {
  return glfwWindowShouldClose(window_);
}

vk::Extent2D Window::framebufferExtent() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return {std::uint32_t(std::max(width, 0)), std::uint32_t(std::max(height, 0))};
}

Result<std::unique_ptr<Swapchain>> Swapchain::create(const Device& device, const Window& window) {
  try {
    VkSurfaceKHR raw = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(*device.instance(), window.handle(), nullptr, &raw) != VK_SUCCESS)
      return fail("could not create a Vulkan surface for the window");
    vk::raii::SurfaceKHR surface(device.instance(), raw);
    if (!device.physicalDevice().getSurfaceSupportKHR(device.queueFamily(), *surface))
      return fail(device.info().name + " cannot present to this window from its graphics queue");
    std::unique_ptr<Swapchain> swapchain(new Swapchain(device, window, std::move(surface)));
    if (auto built = swapchain->rebuild(); !built) return std::unexpected(built.error());
    return swapchain;
  } catch (const std::exception& error) {
    return fail(std::string("creating the swapchain failed: ") + error.what());
  }
}

Swapchain::Swapchain(const Device& device, const Window& window, vk::raii::SurfaceKHR surface)
    : device_(&device), window_(&window), surface_(std::move(surface)) {
  const auto& vkDevice = device.device();
  imageAvailable_ = vk::raii::Semaphore(vkDevice, vk::SemaphoreCreateInfo{});
  frameDone_ = vk::raii::Fence(vkDevice, vk::FenceCreateInfo{.flags = vk::FenceCreateFlagBits::eSignaled});
  pool_ = vk::raii::CommandPool(vkDevice,
                                vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                                          .queueFamilyIndex = device.queueFamily()});
  commands_ = std::move(
      vk::raii::CommandBuffers(vkDevice, vk::CommandBufferAllocateInfo{.commandPool = *pool_,
                                                                       .level = vk::CommandBufferLevel::ePrimary,
                                                                       .commandBufferCount = 1})
          .front());
}

Swapchain::~Swapchain() {
  // The queue may still present an image or wait on one of our semaphores; never throw here.
  const auto& vkDevice = device_->device();
  static_cast<void>(vkDevice.getDispatcher()->vkDeviceWaitIdle(*vkDevice));
}

Result<void> Swapchain::rebuild() {
  device_->device().waitIdle();
  const auto& physical = device_->physicalDevice();
  const auto capabilities = physical.getSurfaceCapabilitiesKHR(*surface_);
  const auto formats = physical.getSurfaceFormatsKHR(*surface_);
  if (formats.empty()) return fail("the window's surface offers no image formats");
  if (!(capabilities.supportedUsageFlags & vk::ImageUsageFlagBits::eTransferDst))
    return fail("the window's swapchain images cannot be copied into (no TRANSFER_DST usage)");
  // An sRGB swapchain keeps the blit from our sRGB output image a plain copy of colours.
  format_ = formats.front().format;
  for (const auto& candidate : formats)
    if (candidate.format == vk::Format::eB8G8R8A8Srgb || candidate.format == vk::Format::eR8G8B8A8Srgb)
      format_ = candidate.format;
  extent_ = capabilities.currentExtent.width != UINT32_MAX ? capabilities.currentExtent : window_->framebufferExtent();
  const std::uint32_t imageCount = capabilities.maxImageCount == 0
                                       ? capabilities.minImageCount + 1
                                       : std::min(capabilities.minImageCount + 1, capabilities.maxImageCount);
  swapchain_ = nullptr;
  swapchain_ = vk::raii::SwapchainKHR(
      device_->device(), vk::SwapchainCreateInfoKHR{.surface = *surface_,
                                                    .minImageCount = imageCount,
                                                    .imageFormat = format_,
                                                    .imageColorSpace = vk::ColorSpaceKHR::eSrgbNonlinear,
                                                    .imageExtent = extent_,
                                                    .imageArrayLayers = 1,
                                                    .imageUsage = vk::ImageUsageFlagBits::eTransferDst,
                                                    .preTransform = capabilities.currentTransform,
                                                    .compositeAlpha = vk::CompositeAlphaFlagBitsKHR::eOpaque,
                                                    .presentMode = vk::PresentModeKHR::eFifo,
                                                    .clipped = VK_TRUE});
  images_ = swapchain_.getImages();
  if (!(physical.getFormatProperties(format_).optimalTilingFeatures & vk::FormatFeatureFlagBits::eBlitDst))
    return fail("the window's image format " + vk::to_string(format_) + " cannot be a blit destination");
  copyFinished_.clear();
  for (std::size_t i = 0; i < images_.size(); ++i)
    copyFinished_.emplace_back(device_->device(), vk::SemaphoreCreateInfo{});
  return {};
}

Result<bool> Swapchain::present(const Image& image) {
  try {
    const vk::Extent2D current = window_->framebufferExtent();
    if (current.width == 0 || current.height == 0) return false;  // minimised
    if (current != extent_) {
      if (auto rebuilt = rebuild(); !rebuilt) return std::unexpected(rebuilt.error());
      return false;
    }
    const auto& vkDevice = device_->device();
    (void)vkDevice.waitForFences(*frameDone_, VK_TRUE, UINT64_MAX);
    // A suboptimal image is still usable this frame; the swapchain is rebuilt after presenting.
    const auto [acquired, index] = swapchain_.acquireNextImage(UINT64_MAX, *imageAvailable_);
    vkDevice.resetFences(*frameDone_);

    const vk::Image target = images_[index];
    auto barrier = [&](vk::ImageLayout from, vk::ImageLayout to, vk::PipelineStageFlags2 srcStage,
                       vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage, vk::AccessFlags2 dstAccess) {
      imageBarrier(commands_, target, {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}, from, to, srcStage, srcAccess,
                   dstStage, dstAccess);
    };
    commands_.reset();
    commands_.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    barrier(vk::ImageLayout::eUndefined, vk::ImageLayout::eTransferDstOptimal, vk::PipelineStageFlagBits2::eTransfer,
            vk::AccessFlagBits2::eNone, vk::PipelineStageFlagBits2::eTransfer, vk::AccessFlagBits2::eTransferWrite);
    const auto source = image.extent();
    const vk::ImageBlit blit{
        .srcSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
        .srcOffsets =
            std::array{vk::Offset3D{0, 0, 0}, vk::Offset3D{std::int32_t(source.width), std::int32_t(source.height), 1}},
        .dstSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
        .dstOffsets = std::array{vk::Offset3D{0, 0, 0},
                                 vk::Offset3D{std::int32_t(extent_.width), std::int32_t(extent_.height), 1}}};
    commands_.blitImage(*image.image(), vk::ImageLayout::eTransferSrcOptimal, target,
                        vk::ImageLayout::eTransferDstOptimal, blit, vk::Filter::eLinear);
    barrier(vk::ImageLayout::eTransferDstOptimal, vk::ImageLayout::ePresentSrcKHR,
            vk::PipelineStageFlagBits2::eTransfer, vk::AccessFlagBits2::eTransferWrite,
            vk::PipelineStageFlagBits2::eNone, vk::AccessFlagBits2::eNone);
    commands_.end();

    const vk::SemaphoreSubmitInfo wait{.semaphore = *imageAvailable_,
                                       .stageMask = vk::PipelineStageFlagBits2::eTransfer};
    const vk::SemaphoreSubmitInfo signal{.semaphore = *copyFinished_[index],
                                         .stageMask = vk::PipelineStageFlagBits2::eTransfer};
    const vk::CommandBufferSubmitInfo commandInfo{.commandBuffer = *commands_};
    device_->queue().submit2(vk::SubmitInfo2{.waitSemaphoreInfoCount = 1,
                                             .pWaitSemaphoreInfos = &wait,
                                             .commandBufferInfoCount = 1,
                                             .pCommandBufferInfos = &commandInfo,
                                             .signalSemaphoreInfoCount = 1,
                                             .pSignalSemaphoreInfos = &signal},
                             *frameDone_);
    const vk::SwapchainKHR swapchain = *swapchain_;
    const vk::Semaphore finished = *copyFinished_[index];
    const vk::Result presented = device_->queue().presentKHR(vk::PresentInfoKHR{.waitSemaphoreCount = 1,
                                                                                .pWaitSemaphores = &finished,
                                                                                .swapchainCount = 1,
                                                                                .pSwapchains = &swapchain,
                                                                                .pImageIndices = &index});
    if (acquired == vk::Result::eSuboptimalKHR || presented == vk::Result::eSuboptimalKHR)
      if (auto rebuilt = rebuild(); !rebuilt) return std::unexpected(rebuilt.error());
    return true;
  } catch (const vk::OutOfDateKHRError&) {
    if (auto rebuilt = rebuild(); !rebuilt) return std::unexpected(rebuilt.error());
    return false;
  } catch (const std::exception& error) {
    return fail(std::string("presenting failed: ") + error.what());
  }
}

}  // namespace mane::render
