#include "render/passes/strand_interpolation.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "render/descriptors.hpp"

namespace mane::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 64;  // local_size_x of strand_interpolation.comp
constexpr std::uint32_t kMaxVertices = 4096;  // per guide and per dense strand, as physics
constexpr float kWeightTolerance = 1e-5f;

struct PushConstants {
  std::uint32_t strandCount;
  std::uint32_t guideVertexCount;
  std::uint32_t vertexCount;
};

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string where(std::size_t strand) {
  return "Strand interpolation: dense strand " + std::to_string(strand);
}

// The rules of physics::validateDenseGroomLayout: the shader indexes guides with these numbers,
// so an index out of range would read outside its buffer rather than fail.
Result<void> validateLayout(const DenseStrandLayout& layout) {
  if (layout.guideCount == 0 || layout.strands.empty())
    return fail("Strand interpolation: the layout is empty (" + std::to_string(layout.guideCount) + " guides, " +
                std::to_string(layout.strands.size()) + " dense strands).");
  if (layout.guideVertexCount < 2 || layout.vertexCount < 2 || layout.guideVertexCount > kMaxVertices ||
      layout.vertexCount > kMaxVertices)
    return fail("Strand interpolation: guides and dense strands need 2 to 4096 vertices each (layout has " +
                std::to_string(layout.guideVertexCount) + " and " + std::to_string(layout.vertexCount) + ").");
  if (layout.guideFrames.size() != layout.guideCount)
    return fail("Strand interpolation: the layout has " + std::to_string(layout.guideFrames.size()) +
                " guide frames for " + std::to_string(layout.guideCount) + " guides.");
  for (std::size_t g = 0; g < layout.guideFrames.size(); ++g)
    if (layout.guideFrames[g].partnerA >= layout.guideCount || layout.guideFrames[g].partnerB >= layout.guideCount)
      return fail("Strand interpolation: guide " + std::to_string(g) + "'s frame partners are out of range (" +
                  std::to_string(layout.guideCount) + " guides).");

  const float guideSpan = static_cast<float>(layout.guideVertexCount - 1);
  const float denseSpan = static_cast<float>(layout.vertexCount - 1);
  for (std::size_t s = 0; s < layout.strands.size(); ++s) {
    const DenseStrand& strand = layout.strands[s];
    if (strand.guideCount < 1 || strand.guideCount > 3)
      return fail(where(s) + " has " + std::to_string(strand.guideCount) + " guides; 1 to 3 are allowed.");
    float sum = 0.0f;
    for (std::uint32_t k = 0; k < strand.guideCount; ++k) {
      if (strand.guides[k] >= layout.guideCount)
        return fail(where(s) + ": guide index " + std::to_string(strand.guides[k]) + " is out of range (" +
                    std::to_string(layout.guideCount) + " guides).");
      if (!std::isfinite(strand.weights[k]))
        return fail(where(s) + ": weight " + std::to_string(k) + " is not finite.");
      sum += strand.weights[k];
    }
    if (!(std::abs(sum - 1.0f) <= kWeightTolerance))
      return fail(where(s) + ": weights sum to " + std::to_string(sum) + ", not 1 (tolerance 1e-5).");
    if (!isFinite(strand.rootOffset) || !isFinite(strand.tipJitter))
      return fail(where(s) + ": root offset or tip jitter is not finite.");
    if (!(strand.clump >= 0.0f && strand.clump <= 1.0f))
      return fail(where(s) + ": clump " + std::to_string(strand.clump) + " is outside [0, 1].");
    if (!(strand.vertexScale >= 0.0f && denseSpan * strand.vertexScale <= guideSpan))
      return fail(where(s) + ": vertexScale " + std::to_string(strand.vertexScale) +
                  " is negative, not finite, or reaches past the guides' tips.");
  }
  return {};
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
  if (auto valid = validateLayout(layout); !valid) return std::unexpected(valid.error());
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
      strandCount_(static_cast<std::uint32_t>(layout.strands.size())),
      hostReadable_(settings.hostReadable),
      guideFrames_(layout.guideFrames.begin(), layout.guideFrames.end()) {
  const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
  const auto hostMemory = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
  guides_ = Buffer(device, vk::DeviceSize(guideCount_) * guideVertexCount_ * sizeof(glm::vec4), storage, hostMemory);
  std::memset(guides_.mapped().data(), 0, guides_.mapped().size());
  frames_ = Buffer::withData(device, std::as_bytes(layout.guideFrames), storage);
  strands_ = Buffer::withData(device, std::as_bytes(layout.strands), storage);
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
  const std::size_t ng = guideVertexCount_;
  const std::size_t expected = std::size_t(guideCount_) * ng;
  if (guidePositions.size() != expected)
    return fail("Strand interpolation: expected " + std::to_string(guideCount_) + " guides × " + std::to_string(ng) +
                " vertices = " + std::to_string(expected) + " guide positions, got " +
                std::to_string(guidePositions.size()) + " (mismatched guide or particle count).");
  for (std::size_t i = 0; i < guidePositions.size(); ++i)
    if (!isFinite(guidePositions[i]))
      return fail("Strand interpolation: guide " + std::to_string(i / ng) + ", vertex " + std::to_string(i % ng) +
                  " is not finite (NaN or infinite).");
  // The frame's normal is cross(A − root, B − root): zero makes the shader divide by zero.
  for (std::size_t g = 0; g < guideCount_; ++g) {
    const GuideFrameRef ref = guideFrames_[g];
    if (ref.partnerA == g && ref.partnerB == g) continue;
    const glm::vec3 root = guidePositions[g * ng];
    const glm::vec3 a = guidePositions[ref.partnerA * ng] - root;
    const glm::vec3 b = guidePositions[ref.partnerB * ng] - root;
    const glm::vec3 normal{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    const float lengthA = a.x * a.x + a.y * a.y + a.z * a.z;
    const float lengthNormal = normal.x * normal.x + normal.y * normal.y + normal.z * normal.z;
    if (!(lengthA > 0.0f && lengthNormal > 0.0f))
      return fail("Strand interpolation: guide " + std::to_string(g) + "'s root is collinear with its frame partners " +
                  std::to_string(ref.partnerA) + " and " + std::to_string(ref.partnerB) + " (collapsed scalp).");
  }
  auto* packed = reinterpret_cast<glm::vec4*>(guides_.mapped().data());
  for (std::size_t i = 0; i < guidePositions.size(); ++i) packed[i] = glm::vec4(guidePositions[i], 1.0f);
  return {};
}

void StrandInterpolationPass::record(const vk::raii::CommandBuffer& commands) const {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  // Write-after-read: the previous frame's draws must have fetched the old vertices. The
  // guides need nothing: host writes before vkQueueSubmit are visible to the submission.
  const vk::MemoryBarrier2 beforeWrite{.srcStageMask = Stage::eVertexAttributeInput | Stage::eVertexShader,
                                       .dstStageMask = Stage::eComputeShader,
                                       .dstAccessMask = Access::eShaderStorageWrite};
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &beforeWrite});

  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.layout, 0, {*set_}, {});
  commands.pushConstants<PushConstants>(*pipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0,
                                        PushConstants{strandCount_, guideVertexCount_, vertexCount_});
  commands.dispatch((strandCount_ + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1);

  vk::PipelineStageFlags2 readers = Stage::eVertexAttributeInput | Stage::eVertexShader | Stage::eCopy;
  vk::AccessFlags2 reads = Access::eVertexAttributeRead | Access::eShaderStorageRead | Access::eTransferRead;
  if (hostReadable_) {
    readers |= Stage::eHost;
    reads |= Access::eHostRead;
  }
  const auto afterWrite = [&](const Buffer& buffer) {
    return vk::BufferMemoryBarrier2{.srcStageMask = Stage::eComputeShader,
                                    .srcAccessMask = Access::eShaderStorageWrite,
                                    .dstStageMask = readers,
                                    .dstAccessMask = reads,
                                    .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .buffer = *buffer.buffer(),
                                    .offset = 0,
                                    .size = VK_WHOLE_SIZE};
  };
  const std::array barriers{afterWrite(positions_), afterWrite(tangents_)};
  commands.pipelineBarrier2(
      vk::DependencyInfo{.bufferMemoryBarrierCount = barriers.size(), .pBufferMemoryBarriers = barriers.data()});
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
