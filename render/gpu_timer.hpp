#pragma once
// GPU timestamps around each pass of a frame, read back after the frame completes.
//
// A pass begun right after another ended shares that end's timestamp: the commands recorded
// between the two (barriers, layout transitions) count with the later pass, and a frame of
// back-to-back passes writes one timestamp per pass instead of two. They are not free: lavapipe
// flushes its rasterizer for each (docs/lavapipe.md#timestamps).

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
  /// Starts timing `pass`: from the previous pass's end where that was the last call, else from now.
  void begin(const vk::raii::CommandBuffer& commands, PassName pass);
  void end(const vk::raii::CommandBuffer& commands);
  /// Writes a timestamp that times nothing, for what it makes lavapipe do: it bins the draws of a
  /// rendering scope and rasterizes none of them before a flush, and a timestamp flushes without
  /// waiting, so its raster threads rasterize the draws before it while the recording thread
  /// bins those after it. No pass ends there: inside a rendering scope lavapipe records when the
  /// last tile of the work after the timestamp starts, not when the work before it ended.
  void handOff(const vk::raii::CommandBuffer& commands);
  /// After the frame's commands finished: the time of each pass. Empty where the device has
  /// no timestamps.
  std::vector<PassTiming> results() const;

private:
  const Device* device_;
  vk::raii::QueryPool pool_{nullptr};
  std::uint32_t capacity_;
  struct Pass {
    PassName name;
    std::uint32_t beginQuery;
    std::uint32_t endQuery;
  };
  void writeTimestamp(const vk::raii::CommandBuffer& commands);

  std::vector<Pass> passes_;
  std::uint32_t queries_ = 0;  ///< timestamps written this frame
  bool ended_ = false;         ///< the last call was `end`: its timestamp can begin the next pass
  bool supported_;
  std::uint64_t validMask_ = ~std::uint64_t(0);  ///< the bits of a timestamp the queue writes
};

}  // namespace mane::render
