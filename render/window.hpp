#pragma once
// A GLFW window with a Vulkan swapchain, for `mane view`. Lives in its own library
// (mane_window) so that offscreen rendering never needs GLFW or a display.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/device.hpp"
#include "render/resources.hpp"

struct GLFWwindow;

namespace mane::render {

class Window {
public:
  /// Opens a window; an error when there is no display (no $DISPLAY / $WAYLAND_DISPLAY).
  static Result<std::unique_ptr<Window>> open(const std::string& title, std::uint32_t width, std::uint32_t height);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  /// Instance extensions Vulkan needs to present to this window system.
  std::vector<std::string> requiredInstanceExtensions() const;
  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  /// Framebuffer size in pixels (may differ from the window size on high-DPI screens).
  vk::Extent2D framebufferExtent() const;

private:
  Window() = default;
  GLFWwindow* window_ = nullptr;
};

/// The swapchain of one window. `present` copies an image (TRANSFER_SRC layout, any size) into
/// the next swapchain image, scaled to fit, and presents it.
class Swapchain {
public:
  static Result<std::unique_ptr<Swapchain>> create(const Device& device, const Window& window);

  /// Returns false when the swapchain had to be rebuilt (window resized); the frame is dropped.
  Result<bool> present(const Image& image);

  /// Waits until the last present no longer uses this swapchain's objects.
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

private:
  Swapchain(const Device& device, const Window& window, vk::raii::SurfaceKHR surface);
  /// Recreates the swapchain for the window's current size; an error names what the surface
  /// cannot do.
  Result<void> rebuild();

  const Device* device_;
  const Window* window_;
  vk::raii::SurfaceKHR surface_;
  vk::raii::SwapchainKHR swapchain_{nullptr};
  vk::Format format_ = vk::Format::eUndefined;
  vk::Extent2D extent_{};
  std::vector<vk::Image> images_;
  vk::raii::Semaphore imageAvailable_{nullptr};
  /// One per swapchain image: the present engine may still wait on an image's semaphore after
  /// our fence signalled, so it is reused only when that image comes back.
  std::vector<vk::raii::Semaphore> copyFinished_;
  vk::raii::Fence frameDone_{nullptr};
  vk::raii::CommandPool pool_{nullptr};
  vk::raii::CommandBuffer commands_{nullptr};
};

}  // namespace mane::render
