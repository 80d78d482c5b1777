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
  queries_ = 0;
  ended_ = false;
  if (supported_) commands.resetQueryPool(*pool_, 0, 2 * capacity_);
}

void GpuTimer::writeTimestamp(const vk::raii::CommandBuffer& commands) {
  if (queries_ == 2 * capacity_) throw std::logic_error("GpuTimer: more timestamps than its capacity");
  if (supported_) commands.writeTimestamp2(vk::PipelineStageFlagBits2::eAllCommands, *pool_, queries_);
  ++queries_;
}

void GpuTimer::handOff(const vk::raii::CommandBuffer& commands) {
  writeTimestamp(commands);
  ended_ = false;
}

void GpuTimer::begin(const vk::raii::CommandBuffer& commands, PassName pass) {
  if (passes_.size() == capacity_) throw std::logic_error("GpuTimer: more passes than its capacity");
  if (!ended_) writeTimestamp(commands);
  ended_ = false;
  passes_.push_back({pass, queries_ - 1, queries_ - 1});
}

void GpuTimer::end(const vk::raii::CommandBuffer& commands) {
  if (passes_.empty() || ended_) throw std::logic_error("GpuTimer: end without a pass begun");
  writeTimestamp(commands);
  passes_.back().endQuery = queries_ - 1;
  ended_ = true;
}

std::vector<PassTiming> GpuTimer::results() const {
  std::vector<PassTiming> timings;
  if (!supported_ || passes_.empty()) return timings;
  const std::uint32_t count = queries_;
  const auto [result, ticks] =
      pool_.getResults<std::uint64_t>(0, count, count * sizeof(std::uint64_t), sizeof(std::uint64_t),
                                      vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
  if (result != vk::Result::eSuccess) return timings;
  const double nanosecondsPerTick = device_->limits().timestampPeriod;
  for (std::size_t i = 0; i < passes_.size(); ++i) {
    // Counters narrower than 64 bits wrap; the masked difference is still the elapsed ticks.
    const std::uint64_t elapsed = (ticks[passes_[i].endQuery] - ticks[passes_[i].beginQuery]) & validMask_;
    const std::uint64_t start = (ticks[passes_[i].beginQuery] - ticks[0]) & validMask_;
    timings.push_back(
        {passes_[i].name, double(elapsed) * nanosecondsPerTick * 1e-6, double(start) * nanosecondsPerTick * 1e-6});
  }
  return timings;
}

}  // namespace mane::render
