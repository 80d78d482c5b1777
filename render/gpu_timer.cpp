#include "render/gpu_timer.hpp"

#include <stdexcept>

namespace mane::render {

GpuTimer::GpuTimer(const Device& device, std::uint32_t maxPasses)
    : device_(&device), capacity_(maxPasses), supported_(device.limits().timestampComputeAndGraphics == VK_TRUE) {
  const std::uint32_t validBits =
      device.physicalDevice().getQueueFamilyProperties()[device.queueFamily()].timestampValidBits;
  supported_ = supported_ && validBits > 0;
  if (validBits > 0 && validBits < 64) validMask_ = (std::uint64_t(1) << validBits) - 1;
  if (supported_)
    pool_ = vk::raii::QueryPool(
        device.device(), vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2 * maxPasses});
}

void GpuTimer::reset(const vk::raii::CommandBuffer& commands) {
  passes_.clear();
  if (supported_) commands.resetQueryPool(*pool_, 0, 2 * capacity_);
}

void GpuTimer::begin(const vk::raii::CommandBuffer& commands, std::string pass) {
  if (passes_.size() == capacity_) throw std::logic_error("GpuTimer: more passes than its capacity");
  if (supported_)
    commands.writeTimestamp2(vk::PipelineStageFlagBits2::eAllCommands, *pool_,
                             static_cast<std::uint32_t>(2 * passes_.size()));
  passes_.push_back(std::move(pass));
}

void GpuTimer::end(const vk::raii::CommandBuffer& commands) {
  if (supported_)
    commands.writeTimestamp2(vk::PipelineStageFlagBits2::eAllCommands, *pool_,
                             static_cast<std::uint32_t>(2 * passes_.size() - 1));
}

std::vector<PassTiming> GpuTimer::results() const {
  std::vector<PassTiming> timings;
  if (!supported_ || passes_.empty()) return timings;
  const auto count = static_cast<std::uint32_t>(2 * passes_.size());
  const auto [result, ticks] =
      pool_.getResults<std::uint64_t>(0, count, count * sizeof(std::uint64_t), sizeof(std::uint64_t),
                                      vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
  if (result != vk::Result::eSuccess) return timings;
  const double nanosecondsPerTick = device_->limits().timestampPeriod;
  for (std::size_t i = 0; i < passes_.size(); ++i) {
    // Counters narrower than 64 bits wrap; the masked difference is still the elapsed ticks.
    const std::uint64_t elapsed = (ticks[2 * i + 1] - ticks[2 * i]) & validMask_;
    const std::uint64_t start = (ticks[2 * i] - ticks[0]) & validMask_;
    timings.push_back(
        {passes_[i], double(elapsed) * nanosecondsPerTick * 1e-6, double(start) * nanosecondsPerTick * 1e-6});
  }
  return timings;
}

}  // namespace mane::render
