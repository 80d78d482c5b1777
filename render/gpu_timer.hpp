#pragma once
// GPU timestamps around each pass of a frame, read back after the frame completes.

#include <string>
#include <vector>

#include "render/device.hpp"
#include "render/frame.hpp"

namespace mane::render {

class GpuTimer {
public:
  /// Room for `maxPasses` passes per frame.
  GpuTimer(const Device& device, std::uint32_t maxPasses);

  /// Resets the queries; record before the first pass.
  void reset(const vk::raii::CommandBuffer& commands);
  void begin(const vk::raii::CommandBuffer& commands, std::string pass);
  void end(const vk::raii::CommandBuffer& commands);
  /// After the frame's commands finished: the time of each pass. Empty where the device has
  /// no timestamps.
  std::vector<PassTiming> results() const;

private:
  const Device* device_;
  vk::raii::QueryPool pool_{nullptr};
  std::uint32_t capacity_;
  std::vector<std::string> passes_;
  bool supported_;
  std::uint64_t validMask_ = ~std::uint64_t(0);  ///< the bits of a timestamp the queue writes
};

}  // namespace mane::render
