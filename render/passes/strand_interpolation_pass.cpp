#include "render/passes/strand_interpolation_pass.hpp"

#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "render/descriptors.hpp"

namespace mane::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 64;  // local_size_x of strand_interpolation.comp

struct PushConstants {
  std::uint32_t strandCount;
  std::uint32_t guideVertexCount;
  std::uint32_t vertexCount;
  std::uint32_t curve;
};

Error strandInterpolationError(const Error& error) {
  return Error{"Strand interpolation: " + error.message};
}

// Sizes the device must hold: one dispatch row of workgroups, and every buffer within the
// storage-buffer range (which also keeps the shader's 32-bit element indices from overflowing).
Result<void> checkLimits(const DenseStrandLayout& layout, const vk::PhysicalDeviceLimits& limits) {
  const std::uint64_t groups = (layout.strands.size() + kWorkgroupSize - 1) / kWorkgroupSize;
  if (groups > limits.maxComputeWorkGroupCount[0])
    return fail("Strand interpolation: " + std::to_string(layout.strands.size()) +
                " dense strands need more workgroups than the device's limit of " +
                std::to_string(limits.maxComputeWorkGroupCount[0]) + " × " + std::to_string(kWorkgroupSize) + ".");
  const std::uint64_t outputBytes = std::uint64_t(layout.strands.size()) * layout.vertexCount * 16;
  const std::uint64_t guideBytes = std::uint64_t(layout.guideCount) * layout.guideVertexCount * 16;
  const std::uint64_t strandBytes = std::uint64_t(layout.strands.size()) * sizeof(DenseStrand);
  for (const auto& [bytes, what] :
       {std::pair{outputBytes, "the dense positions"}, std::pair{guideBytes, "the guide positions"},
        std::pair{strandBytes, "the dense strand layout"}})
    if (bytes > limits.maxStorageBufferRange)
      return fail(std::string("Strand interpolation: ") + what + " take " + std::to_string(bytes) +
                  " bytes, more than the device's storage buffer range of " +
                  std::to_string(limits.maxStorageBufferRange) + " bytes.");
  return {};
}

}  // namespace

Result<std::unique_ptr<StrandInterpolationPass>> StrandInterpolationPass::create(
    const Device& device, const DenseStrandLayout& layout, const StrandInterpolationSettings& settings) {
  // The shader indexes guides with the layout's numbers: one out of range would read outside its
  // buffer rather than fail.
  if (auto valid = validateStrandLayout(layout); !valid)
    return std::unexpected(strandInterpolationError(valid.error()));
  if (auto fits = checkLimits(layout, device.limits()); !fits) return std::unexpected(fits.error());
  try {
    return std::unique_ptr<StrandInterpolationPass>(new StrandInterpolationPass(device, layout, settings));
  } catch (const std::exception& error) {
    return fail(std::string("Strand interpolation: creating the pass failed: ") + error.what());
  }
}

StrandInterpolationPass::StrandInterpolationPass(const Device& device, const DenseStrandLayout& layout,
                                                 const StrandInterpolationSettings& settings)
    : guideCount_(layout.guideCount),
      guideVertexCount_(layout.guideVertexCount),
      vertexCount_(layout.vertexCount),
      curve_(layout.curve),
      strandCount_(static_cast<std::uint32_t>(layout.strands.size())),
      hostReadable_(settings.hostReadable),
      guideFrames_(layout.guideFrames.begin(), layout.guideFrames.end()) {
  const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
  const auto hostMemory = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
  guides_ = Buffer(device, vk::DeviceSize(guideCount_) * guideVertexCount_ * sizeof(glm::vec4), storage, hostMemory);
  std::memset(guides_.mapped().data(), 0, guides_.mapped().size());
  frames_ = Buffer::withData(device, std::as_bytes(std::span(layout.guideFrames)), storage);
  strands_ = Buffer::withData(device, std::as_bytes(std::span(layout.strands)), storage);
  const vk::DeviceSize outputBytes = vk::DeviceSize(vertexTotal()) * kVertexStride;
  // Texel buffers too: HairPass's compute step reads them as such (render/passes/hair_pass.hpp).
  const auto outputUsage = storage | vk::BufferUsageFlagBits::eVertexBuffer | vk::BufferUsageFlagBits::eTransferSrc |
                           vk::BufferUsageFlagBits::eUniformTexelBuffer;
  const vk::MemoryPropertyFlags outputMemory = hostReadable_ ? hostMemory : vk::MemoryPropertyFlagBits::eDeviceLocal;
  positions_ = Buffer(device, outputBytes, outputUsage, outputMemory);
  tangents_ = Buffer(device, outputBytes, outputUsage, outputMemory);

  const auto compute = vk::ShaderStageFlagBits::eCompute;
  setLayout_ = makeSetLayout(device, {{vk::DescriptorType::eStorageBuffer, compute},
                                      {vk::DescriptorType::eStorageBuffer, compute},
                                      {vk::DescriptorType::eStorageBuffer, compute},
                                      {vk::DescriptorType::eStorageBuffer, compute},
                                      {vk::DescriptorType::eStorageBuffer, compute}});
  pipeline_ = makeComputePipeline(device, "strand_interpolation.comp", setLayout_, sizeof(PushConstants));

  pool_ = makeDescriptorPool(device, 1, {{vk::DescriptorType::eStorageBuffer, 5}});
  set_ = allocateSet(device, pool_, setLayout_);
  writeStorageBuffer(device, set_, 0, guides_);
  writeStorageBuffer(device, set_, 1, frames_);
  writeStorageBuffer(device, set_, 2, strands_);
  writeStorageBuffer(device, set_, 3, positions_);
  writeStorageBuffer(device, set_, 4, tangents_);
}

Result<void> StrandInterpolationPass::updateGuides(std::span<const glm::vec3> guidePositions) {
  if (auto valid = validateGuidePositions(guidePositions, guideCount_, guideVertexCount_, guideFrames_); !valid)
    return std::unexpected(strandInterpolationError(valid.error()));
  auto* packed = reinterpret_cast<glm::vec4*>(guides_.mapped().data());
  for (std::size_t i = 0; i < guidePositions.size(); ++i) packed[i] = glm::vec4(guidePositions[i], 1.0f);
  return {};
}

void StrandInterpolationPass::declare(FrameGraph::Builder& pass) const {
  // The guides need nothing: host writes before vkQueueSubmit are visible to the submission.
  pass.write(positions_, ResourceUse::storageWrite(vk::PipelineStageFlagBits2::eComputeShader));
  pass.write(tangents_, ResourceUse::storageWrite(vk::PipelineStageFlagBits2::eComputeShader));
}

void StrandInterpolationPass::execute(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.layout, 0, {*set_}, {});
  commands.pushConstants<PushConstants>(
      *pipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0,
      PushConstants{strandCount_, guideVertexCount_, vertexCount_, static_cast<std::uint32_t>(curve_)});
  commands.dispatch((strandCount_ + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1);
}

void StrandInterpolationPass::record(const vk::raii::CommandBuffer& commands) const {
  const ResourceUse readers = ResourceUse::computedVertices(hostReadable_);
  FrameGraph::recordAlone(commands, PassName::kStrands, *this, {{positions_, readers}, {tangents_, readers}});
}

std::span<const glm::vec4> StrandInterpolationPass::mappedPositions() const {
  if (!hostReadable_) return {};
  return {reinterpret_cast<const glm::vec4*>(positions_.mapped().data()), vertexTotal()};
}

std::span<const glm::vec4> StrandInterpolationPass::mappedTangents() const {
  if (!hostReadable_) return {};
  return {reinterpret_cast<const glm::vec4*>(tangents_.mapped().data()), vertexTotal()};
}

}  // namespace mane::render
