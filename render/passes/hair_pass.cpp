#include "render/passes/hair_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "render/descriptors.hpp"
#include "render/passes/hair_lighting.hpp"

namespace mane::render {
namespace {

// std140 mirror of HairUniforms in shaders/hair_uniforms.glsl.
struct HairUniforms {
  glm::mat4 viewProjection;
  glm::vec4 eye;
  glm::vec4 groom;
  glm::vec4 viewport;
  glm::uvec4 counts;
};
static_assert(sizeof(HairUniforms) == 64 + 4 * 16);

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

Result<void> validate(const HairGroomSettings& groom) {
  if (!(std::isfinite(groom.width) && groom.width > 0.0f))
    return fail("hair groom: width must be a finite number of metres > 0, got " + std::to_string(groom.width));
  if (!(groom.tipWidthScale >= 0.0f && groom.tipWidthScale <= 1.0f))
    return fail("hair groom: tipWidthScale must be in [0, 1], got " + std::to_string(groom.tipWidthScale));
  if (!(groom.opacity >= 0.0f && groom.opacity <= 1.0f))
    return fail("hair groom: opacity must be in [0, 1], got " + std::to_string(groom.opacity));
  if (!(std::isfinite(groom.minimumPixelWidth) && groom.minimumPixelWidth >= 0.25f))
    return fail("hair groom: minimumPixelWidth must be a finite number of pixels ≥ 0.25, got " +
                std::to_string(groom.minimumPixelWidth));
  return {};
}

// Two triangles per segment over the ribbon vertices 2 × (k × Nd + i) + side of the vertex shader,
// counter-clockwise seen from the side s points to: (i, −)(i+1, −)(i+1, +) and (i, −)(i+1, +)(i, +).
// The count fits 32 bits (setStrands checks), and so does every index, as 2·Nd ≤ 6·(Nd − 1).
Buffer ribbonIndices(const Device& device, std::uint32_t strands, std::uint32_t verticesPerStrand) {
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(strands) * (verticesPerStrand - 1) * 6);
  for (std::uint32_t k = 0; k < strands; ++k)
    for (std::uint32_t i = 0; i + 1 < verticesPerStrand; ++i) {
      const std::uint32_t minus = 2 * (k * verticesPerStrand + i), plus = minus + 1;
      const std::uint32_t nextMinus = minus + 2, nextPlus = minus + 3;
      indices.insert(indices.end(), {minus, nextMinus, nextPlus, minus, nextPlus, plus});
    }
  if (indices.empty()) indices.push_back(0);  // a zero-sized buffer is not allowed
  return Buffer::withData(device, std::as_bytes(std::span(indices)), vk::BufferUsageFlagBits::eIndexBuffer);
}

}  // namespace

Result<std::unique_ptr<HairPass>> HairPass::create(const Device& device, const HairPassSettings& settings) {
  try {
    return std::unique_ptr<HairPass>(new HairPass(device, settings));
  } catch (const vk::SystemError& error) {
    return fail(std::string("hair pass: Vulkan error while creating the pipeline: ") + error.what());
  }
}

HairPass::HairPass(const Device& device, const HairPassSettings& settings) : device_(&device) {
  using Stage = vk::ShaderStageFlagBits;
  using Type = vk::DescriptorType;
  setLayout_ = makeSetLayout(device, {{Type::eUniformBuffer, Stage::eVertex | Stage::eFragment},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex}});
  const bool depth = settings.depthFormat != vk::Format::eUndefined;
  pipeline_ = makeGraphicsPipeline(device, GraphicsPipelineSettings{.vertexShader = "hair.vert",
                                                                    .fragmentShader = "hair.frag",
                                                                    .cullMode = vk::CullModeFlagBits::eNone,
                                                                    .colorFormats = {settings.colorFormat},
                                                                    .blend = Blend::kPremultipliedAlpha,
                                                                    .depthFormat = settings.depthFormat,
                                                                    .depthTest = depth,
                                                                    .depthWrite = false,
                                                                    .samples = settings.samples,
                                                                    .setLayouts = {*setLayout_}});
  pool_ = makeDescriptorPool(device, 1, {{Type::eUniformBuffer, 1}, {Type::eStorageBuffer, 4}});
  set_ = allocateSet(device, pool_, setLayout_);
  uniforms_ = Buffer(device, sizeof(HairUniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                     vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  writeUniformBuffer(device, set_, 0, uniforms_);
}

Result<void> HairPass::setStrands(const HairStrands& strands) {
  if (!strands.positions || !strands.tangents || !strands.radiance)
    return fail("hair strands: the position, tangent or radiance buffer is null");
  if (strands.verticesPerStrand < 2)
    return fail("hair strands: need at least 2 vertices per strand, got " + std::to_string(strands.verticesPerStrand));
  const std::uint64_t indices = std::uint64_t(strands.strandCount) * (strands.verticesPerStrand - 1) * 6;
  if (indices > std::numeric_limits<std::uint32_t>::max())
    return fail("hair strands: " + std::to_string(strands.strandCount) + " strands × " +
                std::to_string(strands.verticesPerStrand) + " vertices need " + std::to_string(indices) +
                " ribbon indices, more than one draw can count (2^32 − 1)");

  const std::array buffers{vk::DescriptorBufferInfo{.buffer = strands.positions, .offset = 0, .range = VK_WHOLE_SIZE},
                           vk::DescriptorBufferInfo{.buffer = strands.tangents, .offset = 0, .range = VK_WHOLE_SIZE},
                           vk::DescriptorBufferInfo{.buffer = strands.radiance, .offset = 0, .range = VK_WHOLE_SIZE}};
  device_->device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set_,
                                                                .dstBinding = 1,
                                                                .descriptorCount = 3,
                                                                .descriptorType = vk::DescriptorType::eStorageBuffer,
                                                                .pBufferInfo = buffers.data()},
                                         {});
  // Buffer order until setDrawOrder says otherwise.
  order_ = Buffer(*device_, std::max<vk::DeviceSize>(strands.strandCount, 1) * sizeof(std::uint32_t),
                  vk::BufferUsageFlagBits::eStorageBuffer,
                  vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  auto* order = reinterpret_cast<std::uint32_t*>(order_.mapped().data());
  for (std::uint32_t s = 0; s < strands.strandCount; ++s) order[s] = s;
  writeStorageBuffer(*device_, set_, 4, order_);
  indices_ = ribbonIndices(*device_, strands.strandCount, strands.verticesPerStrand);
  strandCount_ = strands.strandCount;
  indexCount_ = static_cast<std::uint32_t>(indices);
  verticesPerStrand_ = strands.verticesPerStrand;
  // Keep the uniforms of an earlier update in step (counts.y is Nd).
  std::memcpy(uniforms_.mapped().data() + offsetof(HairUniforms, counts) + sizeof(std::uint32_t), &verticesPerStrand_,
              sizeof(verticesPerStrand_));
  return {};
}

Result<void> HairPass::setDrawOrder(std::span<const std::uint32_t> order) {
  if (order.size() != strandCount_)
    return fail("hair draw order: " + std::to_string(order.size()) + " entries for " + std::to_string(strandCount_) +
                " strands");
  std::vector<bool> seen(strandCount_, false);
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (order[k] >= strandCount_ || seen[order[k]])
      return fail("hair draw order: entry " + std::to_string(k) + " (" + std::to_string(order[k]) +
                  ") is out of range or repeats a strand");
    seen[order[k]] = true;
  }
  std::memcpy(order_.mapped().data(), order.data(), order.size_bytes());
  return {};
}

Result<void> HairPass::update(const HairView& view, const HairGroomSettings& groom) {
  if (auto valid = validate(groom); !valid) return valid;
  if (view.extent.width == 0 || view.extent.height == 0) return fail("hair view: the extent is empty");
  const float determinant = glm::determinant(view.viewProjection);
  if (!finite(view.viewProjection) || !std::isfinite(determinant) || determinant == 0.0f)
    return fail("hair view: the view-projection matrix is not finite and invertible");

  HairUniforms uniforms{};
  uniforms.viewProjection = view.viewProjection;
  uniforms.eye = hairEye(view.viewProjection);
  uniforms.groom = glm::vec4(groom.width, groom.tipWidthScale, groom.opacity, groom.minimumPixelWidth);
  uniforms.viewport = glm::vec4(float(view.extent.width), float(view.extent.height), 0.0f, 0.0f);
  uniforms.counts = glm::uvec4(0u, verticesPerStrand_, 0u, 0u);
  std::memcpy(uniforms_.mapped().data(), &uniforms, sizeof(uniforms));
  extent_ = view.extent;
  return {};
}

Result<void> HairPass::update(const FrameInput& frame, vk::Extent2D extent, const HairGroomSettings& groom) {
  if (extent.width == 0 || extent.height == 0) return fail("hair view: the extent is empty");
  const float aspect = float(extent.width) / float(extent.height);
  return update(HairView{frame.camera.projection(aspect) * frame.camera.view(), extent}, groom);
}

void HairPass::draw(const vk::raii::CommandBuffer& commands) const {
  if (indexCount_ == 0 || extent_.width == 0) return;
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline_.layout, 0, {*set_}, {});
  setViewportAndScissor(commands, extent_);
  commands.bindIndexBuffer(*indices_.buffer(), 0, vk::IndexType::eUint32);
  commands.drawIndexed(indexCount_, 1, 0, 0, 0);
}

}  // namespace mane::render
